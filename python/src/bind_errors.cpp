// tandem.Error: what the library's Status and Result errors become in Python.
#include "bindings.h"

namespace tandem::python {

void bindErrors(py::module_& module) {
  static py::exception<LibraryError> error(module, "Error", PyExc_RuntimeError);
  error.doc() =
      "An error the Tandem library reported (bad input refused, a step that diverged, a scene "
      "file that does not load). str(e) is the library's message, e.g. "
      "'rope: node count must be >= 2, got 1'.";
  py::register_exception_translator([](std::exception_ptr pending) {
    try {
      if (pending) std::rethrow_exception(pending);
    } catch (const LibraryError& e) {
      error(e.what());
    }
  });
}

}  // namespace tandem::python
