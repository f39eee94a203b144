// World and solver settings.
#include "bindings.h"

#include <tandem/world.h>

namespace tandem::python {

void bindSettings(py::module_& module) {
  py::enum_<FrictionModel>(module, "FrictionModel",
                           "How a contact's friction impulse is bounded: COULOMB |lt| <= mu ln by the contact's own "
                           "normal impulse; PRESSURE the paper's |lt| <= mu m |g.n| h.")
      .value("COULOMB", FrictionModel::Coulomb)
      .value("PRESSURE", FrictionModel::Pressure);

  py::class_<SolverSettings> solver(module, "SolverSettings", "How the interleaved solve runs each step.");
  defKeywordInit<SolverSettings>(solver);
  solver.def_readwrite("iterations", &SolverSettings::iterations,
                       "K: each is one Bullet iteration, then one sweep over Tandem's rows (>= 1).")
      .def_readwrite("substeps", &SolverSettings::substeps, "n: the solve and integration run n times per step over h/n.")
      .def_readwrite("baumgarte", &SolverSettings::baumgarte,
                     "beta*h: the fraction of a position error corrected per step.")
      .def_readwrite("warm_start", &SolverSettings::warmStart, "Start each row from last step's impulse.")
      .def_readwrite("friction", &SolverSettings::friction, "The FrictionModel.")
      .def_readwrite("contact_slop", &SolverSettings::contactSlop, "m of penetration left alone.");

  py::class_<WorldSettings> world(module, "WorldSettings",
                                  "A world's settings. World.settings returns a copy: change it, then assign it "
                                  "back (world.settings = s), which validates it.");
  defKeywordInit<WorldSettings>(world);
  world.def_readwrite("gravity", &WorldSettings::gravity, "m/s^2, world frame.")
      .def_readwrite("solver", &WorldSettings::solver, "The SolverSettings (changed in place: s.solver.iterations = 8).")
      .def_readwrite("divergence_speed", &WorldSettings::divergenceSpeed,
                     "m/s: a node or body faster than this (or non-finite) makes step() raise.");
}

}  // namespace tandem::python
