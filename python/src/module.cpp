// The `tandem._tandem` extension: Tandem's public C++ API for Python. `tandem/__init__.py`
// re-exports it as the `tandem` package.
#include "bindings.h"

PYBIND11_MODULE(_tandem, module) {
  using namespace tandem::python;
  module.doc() =
      "Tandem: rigid (Bullet) and deformable bodies simulated with two-way coupling.\n\n"
      "SI units throughout (m, kg, s, N; impulses in N*s). Vectors are NumPy arrays of 3 floats\n"
      "(any sequence of 3 numbers is accepted), quaternions 4 floats (w, x, y, z). Errors the\n"
      "library reports are raised as tandem.Error with the library's message.";
  module.attr("__version__") = TANDEM_PYTHON_VERSION;
  py::module_::import("numpy");
  bindErrors(module);
  bindIds(module);
  bindSettings(module);
  bindRigid(module);
  bindMesh(module);
  bindDeformable(module);
  bindQueries(module);
  bindReport(module);
  bindWorld(module);
  bindScene(module);
}
