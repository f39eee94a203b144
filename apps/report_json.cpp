// The run's report as one JSON object, written a top-level field at a time so that a long run's
// per-step series are turned into JSON one series at a time, not all at once.
#include "report_json.h"

#include <nlohmann/json.hpp>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <memory>

namespace tandem::cli {
namespace {

using Json = nlohmann::ordered_json;

inline constexpr int kReportFormatVersion = 1;

// "rigid prediction" -> "rigid_prediction": stage and row-type names as JSON keys.
std::string keyOf(std::string_view name) {
  std::string key(name);
  for (char& c : key)
    if (c == ' ') c = '_';
  return key;
}

Json vec(const Vec3& v) { return Json::array({v.x(), v.y(), v.z()}); }

Json spreadJson(const Spread& spread) {
  return Json{{"mean", spread.mean}, {"median", spread.median}, {"p95", spread.p95},
              {"p99", spread.p99},   {"min", spread.min},       {"max", spread.max}};
}

Json settingsJson(const RunDescription& run, const World& world) {
  const WorldSettings& settings = world.settings();
  const SolverSettings& solver = settings.solver;
  return Json{{"time_step", run.timeStep},
              {"gravity", vec(settings.gravity)},
              {"divergence_speed", settings.divergenceSpeed},
              {"solver",
               {{"iterations", solver.iterations},
                {"substeps", solver.substeps},
                {"baumgarte", solver.baumgarte},
                {"warm_start", solver.warmStart},
                {"friction_model", solver.friction == FrictionModel::Coulomb ? "coulomb" : "pressure"},
                {"contact_slop", solver.contactSlop}}}};
}

Json worldJson(const World& world) {
  int nodes = 0;
  for (int d = 0; d < world.deformableCount(); ++d) nodes += static_cast<int>(world.nodePositions(DeformableId{d}).size());
  return Json{{"rigid_bodies", world.rigidBodyCount()},
              {"deformables", world.deformableCount()},
              {"nodes", nodes},
              {"bullet_joints", world.lastReport().bulletJoints}};
}

Json stagesJson(const RunLog& log) {
  double total = 0.0;
  for (double seconds : log.stageTotals()) total += seconds;
  const double steps = static_cast<double>(std::max<int64_t>(log.steps(), 1));
  Json stages = Json::object();
  for (size_t s = 0; s < kStageCount; ++s) {
    const double seconds = log.stageTotals()[s];
    stages[keyOf(kStageNames[s])] = Json{{"mean_ms", 1e3 * seconds / steps},
                                         {"total_ms", 1e3 * seconds},
                                         {"share", total > 0 ? seconds / total : 0.0}};
  }
  return stages;
}

Json rowsJson(const RunLog& log, const StepReport& last) {
  const double steps = static_cast<double>(std::max<int64_t>(log.steps(), 1));
  Json rows = Json::object();
  for (size_t t = 0; t < kRowTypeCount; ++t)
    rows[keyOf(kRowTypeNames[t])] =
        Json{{"last", last.rowCounts[t]}, {"max", log.maxRows()[t]}, {"mean", log.rowSums()[t] / steps}};
  rows["total"] = Json{{"last", last.totalRows()}, {"max", log.maxTotalRows()}};
  return rows;
}

Json convergenceJson(const RunLog& log, const StepReport& last) {
  return Json{{"rms_delta_lambda_last_step", last.rmsDeltaLambda},
              {"rms_delta_lambda_mean", log.meanRmsDeltaLambda()},
              {"block_factorisations", log.blockFactorisations()},
              {"max_model_iterations", log.maxModelIterations()},
              {"unconverged_model_steps", log.unconvergedModelSteps()}};
}

Json impactZonesJson(const RunLog& log, const StepReport& last) {
  return Json{{"last_step", last.impactZones},
              {"last_step_nodes", last.impactZoneNodes},
              {"max", log.maxImpactZones()},
              {"max_nodes", log.maxImpactZoneNodes()},
              {"steps_with_zones", log.stepsWithImpactZones()}};
}

Json violationsJson(const RunLog& log) {
  Json listed = Json::array();
  for (const LoggedViolation& logged : log.violations()) {
    const RowViolation& v = logged.violation;
    listed.push_back(Json{{"step", logged.step},
                          {"time", logged.time},
                          {"kind", v.kind == RowViolation::Kind::AnchorGap ? "anchor_gap" : "edge_stretch"},
                          {"index", v.index},
                          {"value", v.value},
                          {"message", v.message}});
  }
  return Json{{"anchor_gap_limit", kAnchorGapWarning},
              {"edge_stretch_limit", kEdgeStretchWarning},
              {"count", log.violationCount()},
              {"listed", std::move(listed)}};
}

Json rigidBodiesJson(const World& world) {
  Json bodies = Json::array();
  for (int b = 0; b < world.rigidBodyCount(); ++b) {
    const RigidBodyId id{b};
    const Quat q = world.rigidOrientation(id);
    bodies.push_back(Json{{"name", world.rigidName(id)},
                          {"mass", world.rigidMass(id)},
                          {"position", vec(world.rigidPosition(id))},
                          {"orientation", Json::array({q.w(), q.x(), q.y(), q.z()})},
                          {"linear_velocity", vec(world.rigidLinearVelocity(id))},
                          {"angular_velocity", vec(world.rigidAngularVelocity(id))}});
  }
  return bodies;
}

// Writes `{"key": value, ...}` a field at a time; the first error sticks.
class ObjectWriter {
 public:
  ObjectWriter(std::FILE* file, int depth) : m_file(file), m_depth(depth) { std::fputs("{", m_file); }
  void field(const std::string& key, const Json& value, bool indented) {
    std::fprintf(m_file, "%s\n%*s%s: ", m_first ? "" : ",", 2 * m_depth, "", Json(key).dump().c_str());
    const std::string text = indented ? indent(value.dump(2)) : value.dump();
    std::fputs(text.c_str(), m_file);
    m_first = false;
  }
  // Starts a nested object as the next field's value; finish it with its own end().
  ObjectWriter nested(const std::string& key) {
    std::fprintf(m_file, "%s\n%*s%s: ", m_first ? "" : ",", 2 * m_depth, "", Json(key).dump().c_str());
    m_first = false;
    return ObjectWriter(m_file, m_depth + 1);
  }
  void end() { std::fprintf(m_file, "\n%*s}", 2 * (m_depth - 1), ""); }

 private:
  // value.dump(2) indented to this object's depth.
  std::string indent(const std::string& text) const {
    std::string out;
    for (char c : text) {
      out += c;
      if (c == '\n') out.append(static_cast<size_t>(2 * m_depth), ' ');
    }
    return out;
  }
  std::FILE* m_file;
  int m_depth;
  bool m_first = true;
};

void writeSteps(ObjectWriter& report, const RunLog& log) {
  ObjectWriter steps = report.nested("steps");
  const size_t count = log.times().size();
  steps.field("time", Json(log.times()), false);
  steps.field("wall_ms", Json(log.wallMs()), false);
  {
    ObjectWriter stages = steps.nested("stage_ms");
    std::vector<double> series(count);
    for (size_t s = 0; s < kStageCount; ++s) {
      for (size_t i = 0; i < count; ++i) series[i] = 1e3 * log.stageSeconds()[i][s];
      stages.field(keyOf(kStageNames[s]), Json(series), false);
    }
    stages.end();
  }
  {
    ObjectWriter rows = steps.nested("rows");
    std::vector<int> series(count);
    for (size_t t = 0; t < kRowTypeCount; ++t) {
      for (size_t i = 0; i < count; ++i) series[i] = log.rowCounts()[i][t];
      rows.field(keyOf(kRowTypeNames[t]), Json(series), false);
    }
    rows.end();
  }
  std::vector<int> totals(count);
  for (size_t i = 0; i < count; ++i)
    for (int rows : log.rowCounts()[i]) totals[i] += rows;
  steps.field("total_rows", Json(totals), false);
  Json rms = Json::array();
  for (size_t i = 0; i < count; ++i)
    rms.push_back(std::vector<double>(log.rms().begin() + static_cast<std::ptrdiff_t>(log.rmsStart()[i]),
                                      log.rms().begin() + static_cast<std::ptrdiff_t>(log.rmsStart()[i + 1])));
  steps.field("rms_delta_lambda", rms, false);
  steps.field("impact_zones", Json(log.impactZones()), false);
  steps.field("impact_zone_nodes", Json(log.impactZoneNodes()), false);
  steps.field("bullet_contact_manifolds", Json(log.contactManifolds()), false);
  steps.field("violations", Json(log.stepViolations()), false);
  steps.end();
}

struct FileCloser {
  void operator()(std::FILE* file) const { std::fclose(file); }
};

}  // namespace

Status createReportJson(const std::string& path) {
  std::FILE* file = std::fopen(path.c_str(), "w");
  if (!file) return Error{"report-json: cannot write '" + path + "': " + std::strerror(errno)};
  std::fclose(file);
  return {};
}

Status writeReportJson(const std::string& path, const RunDescription& run, const RunLog& log, const World& world) {
  std::unique_ptr<std::FILE, FileCloser> file(std::fopen(path.c_str(), "w"));
  if (!file) return Error{"report-json: cannot write '" + path + "': " + std::strerror(errno)};
  const StepReport& last = world.lastReport();
  const double simulated = static_cast<double>(log.steps()) * run.timeStep;
  ObjectWriter report(file.get(), 1);
  report.field("format", "tandem run report", false);
  report.field("version", kReportFormatVersion, false);
  report.field("scene", Json{{"source", run.scene}, {"name", run.name}, {"description", run.description}}, true);
  report.field("settings", settingsJson(run, world), true);
  report.field("world", worldJson(world), true);
  report.field("run", Json{{"steps", log.steps()},
                           {"simulated_seconds", simulated},
                           {"wall_seconds", run.wallSeconds},
                           {"real_time_factor", run.wallSeconds > 0 ? simulated / run.wallSeconds : 0.0},
                           {"error", run.error.empty() ? Json(nullptr) : Json(run.error)}},
               true);
  report.field("step_ms", spreadJson(log.wallMsSpread()), true);
  report.field("stages", stagesJson(log), true);
  report.field("rows", rowsJson(log, last), true);
  report.field("bullet", Json{{"contact_manifolds_last_step", last.bulletContactManifolds}, {"joints", last.bulletJoints}},
               true);
  report.field("convergence", convergenceJson(log, last), true);
  report.field("impact_zones", impactZonesJson(log, last), true);
  report.field("violations", violationsJson(log), true);
  report.field("rigid_bodies", rigidBodiesJson(world), true);
  if (log.keepsSteps()) writeSteps(report, log);
  report.end();
  std::fputs("\n", file.get());
  std::FILE* f = file.release();
  const bool written = std::fflush(f) == 0 && !std::ferror(f);
  const int error = errno;
  if (std::fclose(f) != 0 || !written)
    return Error{"report-json: writing '" + path + "' failed: " + std::strerror(written ? errno : error)};
  return {};
}

}  // namespace tandem::cli
