// What one step did: the step report.
#include "bindings.h"

#include <tandem/report.h>

namespace tandem::python {
namespace {

// "rigid prediction" -> "rigid_prediction": the library's names as Python keys.
std::string keyOf(std::string_view name) {
  std::string key(name);
  for (char& c : key)
    if (c == ' ') c = '_';
  return key;
}

py::dict stageSeconds(const StepReport& report) {
  py::dict seconds;
  for (size_t s = 0; s < kStageNames.size(); ++s) seconds[py::str(keyOf(kStageNames[s]))] = report.stageSeconds[s];
  return seconds;
}

py::dict rowCounts(const StepReport& report) {
  py::dict counts;
  for (size_t r = 0; r < kRowTypeNames.size(); ++r) counts[py::str(keyOf(kRowTypeNames[r]))] = report.rowCounts[r];
  return counts;
}

py::dict violationDict(const RowViolation& v) {
  py::dict d;
  d["kind"] = v.kind == RowViolation::Kind::AnchorGap ? "anchor_gap" : "edge_stretch";
  d["index"] = v.index;
  d["value"] = v.value;
  d["message"] = v.message;
  return d;
}

}  // namespace

void bindReport(py::module_& module) {
  module.attr("ANCHOR_GAP_WARNING") = kAnchorGapWarning;
  module.attr("EDGE_STRETCH_WARNING") = kEdgeStretchWarning;

  py::class_<RowViolation> violation(module, "RowViolation",
                                     "A row left violated at a step's end beyond what holding means: an anchor "
                                     "more than ANCHOR_GAP_WARNING m apart, an inextensible edge stretched more than "
                                     "EDGE_STRETCH_WARNING. The step still succeeded.");
  py::enum_<RowViolation::Kind>(violation, "Kind")
      .value("ANCHOR_GAP", RowViolation::Kind::AnchorGap)
      .value("EDGE_STRETCH", RowViolation::Kind::EdgeStretch);
  violation.def_readonly("kind", &RowViolation::kind, "RowViolation.Kind.")
      .def_readonly("index", &RowViolation::index,
                    "The anchor's id, or the edge's index among the deformable's inextensible edges.")
      .def_readonly("value", &RowViolation::value, "m apart (anchor) or strain (edge).")
      .def_readonly("message", &RowViolation::message, "Names the deformable, the body and the row.")
      .def("to_dict", &violationDict, "The violation as a dict.");

  py::class_<StepReport>(module, "StepReport",
                         "What one step did: time per stage, rows by type, how the solver converged. Dict keys "
                         "are the library's stage and row names with '_' for spaces ('interleaved_solve', "
                         "'fixed_point').")
      .def_property_readonly("stage_seconds", &stageSeconds,
                             "{stage: seconds}: models, rigid_prediction, collision_detection, row_setup, "
                             "interleaved_solve, integrate.")
      .def_property_readonly("row_counts", &rowCounts,
                             "{row type: scalar rows}: fixed_point, anchor, inextensibility, bending, contact, "
                             "friction, grab.")
      .def_readonly("rms_delta_lambda", &StepReport::rmsDeltaLambda,
                    "RMS of the change of impulse over Tandem's rows in each iteration's sweep (N*s), a list.")
      .def_readonly("bullet_contact_manifolds", &StepReport::bulletContactManifolds, "Bullet's contact manifolds.")
      .def_readonly("bullet_joints", &StepReport::bulletJoints, "Bullet's joints.")
      .def_readonly("impact_zones", &StepReport::impactZones,
                    "Groups of nodes moved rigidly at the step's end because surfaces would have crossed.")
      .def_readonly("impact_zone_nodes", &StepReport::impactZoneNodes, "Nodes in them.")
      .def_readonly("block_factorisations", &StepReport::blockFactorisations,
                    "Sparse factorisations of the direct blocks this step (0 when last step's were kept).")
      .def_readonly("model_iterations", &StepReport::modelIterations,
                    "Conjugate-gradient iterations of the implicit models' solves this step (the most of any).")
      .def_readonly("models_converged", &StepReport::modelsConverged,
                    "Whether every implicit model's solve met its tolerance within its iteration limit.")
      .def_readonly("violations", &StepReport::violations, "RowViolation list, empty when every row holds.")
      .def_readonly("total_seconds", &StepReport::totalSeconds, "Wall-clock seconds the step took.")
      .def_property_readonly("total_rows", &StepReport::totalRows, "Scalar rows of every type.")
      .def(
          "to_dict",
          [](const StepReport& r) {
            py::dict d;
            d["stage_seconds"] = stageSeconds(r);
            d["row_counts"] = rowCounts(r);
            d["rms_delta_lambda"] = r.rmsDeltaLambda;
            d["bullet_contact_manifolds"] = r.bulletContactManifolds;
            d["bullet_joints"] = r.bulletJoints;
            d["impact_zones"] = r.impactZones;
            d["impact_zone_nodes"] = r.impactZoneNodes;
            d["block_factorisations"] = r.blockFactorisations;
            d["model_iterations"] = r.modelIterations;
            d["models_converged"] = r.modelsConverged;
            py::list violations;
            for (const RowViolation& v : r.violations) violations.append(violationDict(v));
            d["violations"] = violations;
            d["total_seconds"] = r.totalSeconds;
            d["total_rows"] = r.totalRows();
            return d;
          },
          "The report as plain dicts, lists and numbers (for json.dumps or pandas).");
}

}  // namespace tandem::python
