// `tandem run --report-json` (apps/report_json.cpp, docs/report-format.md): the command runs a
// scene with a rope too weak for its load; the same scene is stepped here, in process, and every
// number of the JSON that the run decides (settings, times, rows by type per step, RMS Δλ per
// iteration, impact zones, violated rows, final poses) must equal this run's to the last bit;
// the summary's statistics must follow from the file's own per-step series.
#include <tandem/record.h>
#include <tandem/scene_file.h>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "process_temp_folder.h"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <numeric>

#include <sys/wait.h>

namespace tandem {
namespace {

namespace fs = std::filesystem;
using Json = nlohmann::json;

constexpr int kSteps = 40;
constexpr int kIterations = 3;
constexpr int kSubsteps = 2;

// A rope of 11 nodes fixed at its top, a 10 kg box at its end, its edges bounded at 2 N: they
// stretch past 10 % and every step reports them.
constexpr const char* kWeakRope = R"({
  "format": 1, "name": "weak rope", "description": "a rope too weak for its box", "time_step": 0.02,
  "rigid_bodies": [ { "name": "heavy box", "shape": { "type": "box", "half_extents": [0.1, 0.1, 0.1] },
                      "mass": 10, "position": [0, 0.9, 0] },
                    { "name": "ground", "shape": { "type": "plane", "normal": [0, 1, 0], "offset": 0 },
                      "mass": 0 } ],
  "deformables": [ { "name": "weak rope", "mesh": { "type": "rope", "start": [0, 2, 0], "end": [0, 1, 0], "nodes": 11 },
                     "mass": 0.1, "inextensibility": { "max_force": 2 }, "fixed": [ { "nodes": [0] } ] } ],
  "anchors": [ { "deformable": "weak rope", "node": 10, "body": "heavy box" } ]
})";

fs::path tempDir() { return processTempFolder("tandem_report_json_tests"); }

// Runs the command; returns its exit status and its output (stdout and stderr).
int runCommand(const std::string& arguments, std::string& output) {
  FILE* pipe = popen((std::string(TANDEM_CLI) + " " + arguments + " 2>&1").c_str(), "r");
  if (!pipe) return -1;
  char buffer[512];
  while (size_t n = fread(buffer, 1, sizeof buffer, pipe)) output.append(buffer, n);
  return pclose(pipe);
}

class ReportJson : public testing::Test {
 protected:
  static void SetUpTestSuite() {
    scenePath = (tempDir() / "weak_rope.json").string();
    std::ofstream(scenePath) << kWeakRope;
    const std::string reportPath = (tempDir() / "weak_rope_report.json").string();
    std::string output;
    const int status = runCommand("run " + scenePath + " --steps " + std::to_string(kSteps) + " --iterations " +
                                      std::to_string(kIterations) + " --substeps " + std::to_string(kSubsteps) +
                                      " --quiet --report-json " + reportPath,
                                  output);
    // The weak rope tears on purpose (its violations are in the report): `tandem run` finishes
    // and exits 5 (apps/exit_codes.h). A failure here fails every test of the suite (SetUp).
    if (!WIFEXITED(status) || WEXITSTATUS(status) != 5) {
      setupError = "tandem run exited with status " + std::to_string(status) + ", not 5:\n" + output;
      return;
    }
    std::ifstream file(reportPath);
    report = Json::parse(file);
  }
  void SetUp() override { ASSERT_TRUE(setupError.empty()) << setupError; }
  static std::string scenePath, setupError;
  static Json report;
};
std::string ReportJson::scenePath, ReportJson::setupError;
Json ReportJson::report;

TEST_F(ReportJson, SettingsAndTheRunAreTheCommandsAndTheScenes) {
  EXPECT_EQ(report["format"], "tandem run report");
  EXPECT_EQ(report["version"], 1);
  EXPECT_EQ(report["scene"]["name"], "weak rope");
  EXPECT_EQ(report["scene"]["source"], scenePath);
  EXPECT_EQ(report["settings"]["time_step"], 0.02);
  EXPECT_EQ(report["settings"]["solver"]["iterations"], kIterations);
  EXPECT_EQ(report["settings"]["solver"]["substeps"], kSubsteps);
  EXPECT_EQ(report["settings"]["solver"]["friction_model"], "coulomb");
  EXPECT_EQ(report["settings"]["gravity"][1], -9.81);
  EXPECT_EQ(report["world"]["rigid_bodies"], 2);
  EXPECT_EQ(report["world"]["deformables"], 1);
  EXPECT_EQ(report["world"]["nodes"], 11);
  EXPECT_EQ(report["run"]["steps"], kSteps);
  EXPECT_DOUBLE_EQ(report["run"]["simulated_seconds"].get<double>(), kSteps * 0.02);
  const double wall = report["run"]["wall_seconds"];
  EXPECT_GT(wall, 0.0);
  EXPECT_DOUBLE_EQ(report["run"]["real_time_factor"].get<double>(), kSteps * 0.02 / wall);
}

TEST_F(ReportJson, EveryStepEqualsTheSameRunInProcess) {
  Result<Scene> scene = loadScene(scenePath);
  ASSERT_TRUE(scene.ok()) << scene.message();
  World world;
  ASSERT_TRUE(buildScene(*scene, world).ok());
  WorldSettings settings = world.settings();
  settings.solver.iterations = kIterations;
  settings.solver.substeps = kSubsteps;
  ASSERT_TRUE(world.setSettings(settings).ok());

  const Json& steps = report["steps"];
  ASSERT_EQ(steps["time"].size(), static_cast<size_t>(kSteps));
  int violations = 0;
  size_t listed = 0;
  for (int i = 0; i < kSteps; ++i) {
    ASSERT_TRUE(world.step(0.02).ok());
    const StepReport& step = world.lastReport();
    EXPECT_EQ(steps["time"][i].get<double>(), world.time());
    for (size_t t = 0; t < step.rowCounts.size(); ++t) {
      std::string key(kRowTypeNames[t]);
      std::replace(key.begin(), key.end(), ' ', '_');
      EXPECT_EQ(steps["rows"][key][i].get<int>(), step.rowCounts[t]) << key << " at step " << i + 1;
    }
    EXPECT_EQ(steps["total_rows"][i].get<int>(), step.totalRows());
    ASSERT_EQ(step.rmsDeltaLambda.size(), static_cast<size_t>(kIterations * kSubsteps));
    EXPECT_EQ(steps["rms_delta_lambda"][i].get<std::vector<double>>(), step.rmsDeltaLambda) << "step " << i + 1;
    EXPECT_EQ(steps["impact_zones"][i].get<int>(), step.impactZones);
    EXPECT_EQ(steps["impact_zone_nodes"][i].get<int>(), step.impactZoneNodes);
    EXPECT_EQ(steps["bullet_contact_manifolds"][i].get<int>(), step.bulletContactManifolds);
    EXPECT_EQ(steps["violations"][i].get<int>(), static_cast<int>(step.violations.size()));
    for (const RowViolation& v : step.violations) {
      ++violations;
      ASSERT_LT(listed, report["violations"]["listed"].size());
      const Json& logged = report["violations"]["listed"][listed++];
      EXPECT_EQ(logged["step"].get<int>(), i + 1);
      EXPECT_EQ(logged["time"].get<double>(), world.time());
      EXPECT_EQ(logged["kind"], v.kind == RowViolation::Kind::EdgeStretch ? "edge_stretch" : "anchor_gap");
      EXPECT_EQ(logged["index"].get<int>(), v.index);
      EXPECT_EQ(logged["value"].get<double>(), v.value);
      EXPECT_EQ(logged["message"].get<std::string>(), v.message);
    }
  }
  EXPECT_GT(violations, 10);  // the rope tears: the test looks at real violations
  EXPECT_EQ(report["violations"]["count"].get<int>(), violations);
  EXPECT_EQ(report["violations"]["edge_stretch_limit"].get<double>(), kEdgeStretchWarning);

  // The last step and the final state.
  const StepReport& last = world.lastReport();
  EXPECT_EQ(report["convergence"]["rms_delta_lambda_last_step"].get<std::vector<double>>(), last.rmsDeltaLambda);
  EXPECT_EQ(report["rows"]["total"]["last"].get<int>(), last.totalRows());
  EXPECT_EQ(report["bullet"]["joints"].get<int>(), last.bulletJoints);
  const RigidBodyId box = *world.findRigidBody("heavy box");
  const Json& body = report["rigid_bodies"][box.index];
  EXPECT_EQ(body["name"], "heavy box");
  EXPECT_EQ(body["mass"].get<double>(), 10.0);
  for (int axis = 0; axis < 3; ++axis) {
    EXPECT_EQ(body["position"][axis].get<double>(), world.rigidPosition(box)[axis]);
    EXPECT_EQ(body["linear_velocity"][axis].get<double>(), world.rigidLinearVelocity(box)[axis]);
  }
  EXPECT_EQ(body["orientation"][0].get<double>(), world.rigidOrientation(box).w());
  EXPECT_LT(body["position"][1].get<double>(), 0.9 - 0.1);  // it fell: the rope stretched
}

double mean(const std::vector<double>& values) {
  return std::accumulate(values.begin(), values.end(), 0.0) / static_cast<double>(values.size());
}

TEST_F(ReportJson, TheSummaryFollowsFromTheSteps) {
  const Json& steps = report["steps"];
  std::vector<double> wall = steps["wall_ms"].get<std::vector<double>>();
  ASSERT_EQ(wall.size(), static_cast<size_t>(kSteps));
  const Json& stepMs = report["step_ms"];
  EXPECT_NEAR(stepMs["mean"].get<double>(), mean(wall), 1e-12 * mean(wall));
  std::vector<double> sorted = wall;
  std::sort(sorted.begin(), sorted.end());
  EXPECT_EQ(stepMs["min"].get<double>(), sorted.front());
  EXPECT_EQ(stepMs["max"].get<double>(), sorted.back());
  EXPECT_EQ(stepMs["median"].get<double>(), sorted[static_cast<size_t>(0.5 * (kSteps - 1) + 0.5)]);
  EXPECT_EQ(stepMs["p95"].get<double>(), sorted[static_cast<size_t>(0.95 * (kSteps - 1) + 0.5)]);

  double shares = 0.0, stageMsSum = 0.0;
  std::vector<double> stageSumPerStep(kSteps, 0.0);
  for (const auto& [name, stage] : report["stages"].items()) {
    const std::vector<double> series = steps["stage_ms"][name].get<std::vector<double>>();
    ASSERT_EQ(series.size(), static_cast<size_t>(kSteps)) << name;
    EXPECT_NEAR(stage["mean_ms"].get<double>(), mean(series), 1e-9) << name;
    EXPECT_NEAR(stage["total_ms"].get<double>(), kSteps * mean(series), 1e-9) << name;
    shares += stage["share"].get<double>();
    stageMsSum += stage["total_ms"].get<double>();
    for (int i = 0; i < kSteps; ++i) stageSumPerStep[static_cast<size_t>(i)] += series[static_cast<size_t>(i)];
  }
  EXPECT_EQ(report["stages"].size(), 6u);
  EXPECT_NEAR(shares, 1.0, 1e-12);
  EXPECT_NEAR(report["stages"]["interleaved_solve"]["share"].get<double>(),
              report["stages"]["interleaved_solve"]["total_ms"].get<double>() / stageMsSum, 1e-12);
  for (int i = 0; i < kSteps; ++i)  // the stages are timed inside the step, which is timed whole
    EXPECT_LE(stageSumPerStep[static_cast<size_t>(i)], wall[static_cast<size_t>(i)] + 1e-3) << "step " << i + 1;

  int maxTotal = 0;
  for (const auto& [name, rows] : report["rows"].items()) {
    if (name == "total") continue;
    const std::vector<int> series = steps["rows"][name].get<std::vector<int>>();
    EXPECT_EQ(rows["max"].get<int>(), *std::max_element(series.begin(), series.end())) << name;
    EXPECT_EQ(rows["last"].get<int>(), series.back()) << name;
    EXPECT_NEAR(rows["mean"].get<double>(), std::accumulate(series.begin(), series.end(), 0.0) / kSteps, 1e-12) << name;
  }
  for (int total : steps["total_rows"].get<std::vector<int>>()) maxTotal = std::max(maxTotal, total);
  EXPECT_EQ(report["rows"]["total"]["max"].get<int>(), maxTotal);
  EXPECT_GT(report["rows"]["inextensibility"]["max"].get<int>(), 0);
  EXPECT_EQ(report["rows"]["anchor"]["max"].get<int>(), 3);  // three rows per anchor

  const std::vector<double> meanRms = report["convergence"]["rms_delta_lambda_mean"].get<std::vector<double>>();
  ASSERT_EQ(meanRms.size(), static_cast<size_t>(kIterations * kSubsteps));
  for (size_t k = 0; k < meanRms.size(); ++k) {
    double sum = 0.0;
    for (const Json& step : steps["rms_delta_lambda"]) sum += step[k].get<double>();
    EXPECT_NEAR(meanRms[k], sum / kSteps, 1e-12 * std::abs(sum)) << "iteration " << k + 1;
  }
}

// A run that diverges (a falling box past a divergence speed of 1 m/s, after about 0.1 s) still
// writes the report and the record of the steps before, and says why it stopped.
TEST(ReportJsonCommand, ARunThatFailsWritesTheStepsBeforeAndWhy) {
  const fs::path scene = tempDir() / "diverging.json";
  std::ofstream(scene) << R"({ "format": 1, "time_step": 0.02, "divergence_speed": 1,
    "rigid_bodies": [ { "name": "falling box", "shape": { "type": "box", "half_extents": [0.1, 0.1, 0.1] },
                        "position": [0, 5, 0] } ] })";
  const std::string reportPath = (tempDir() / "diverging_report.json").string();
  const std::string recordPath = (tempDir() / "diverging_record.npz").string();
  std::string output;
  const int status = runCommand("run " + scene.string() + " --steps 50 --quiet --report-json " + reportPath +
                                    " --record " + recordPath,
                                output);
  EXPECT_NE(status, 0);
  std::ifstream file(reportPath);
  const Json failed = Json::parse(file);
  const std::string error = failed["run"]["error"];
  EXPECT_NE(error.find("falling box"), std::string::npos) << error;
  EXPECT_NE(output.find(error), std::string::npos) << output;  // the message the command printed
  // Free fall reaches 1 m/s after 0.102 s: the sixth step fails, five are reported.
  EXPECT_EQ(failed["run"]["steps"].get<int>(), 5);
  EXPECT_EQ(failed["steps"]["time"].size(), 5u);
  EXPECT_GT(fs::file_size(recordPath), 0u);
}

TEST(ReportJsonCommand, AnUnwritableFileIsNamedBeforeTheRun) {
  std::string output;
  const int status = runCommand("run hanging_rope --steps 5 --report-json /no/such/folder/report.json", output);
  EXPECT_NE(status, 0);
  EXPECT_NE(output.find("report-json: cannot write '/no/such/folder/report.json'"), std::string::npos) << output;
  EXPECT_EQ(output.find("Simulated"), std::string::npos) << "refused before running: " << output;
}

}  // namespace
}  // namespace tandem
