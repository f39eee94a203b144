// The `tandem` command: run, check and list scenes (scene files or built-in scenes); view and
// render them when built with rendering (apps/render_command.cpp, apps/viewer.cpp).
#include <tandem/record.h>
#include <tandem/scene_file.h>
#include <tandem/scenes.h>
#include <tandem/version.h>
#include <tandem/world.h>

#include "exit_codes.h"
#include "report_json.h"
#include "run_log.h"
#include "scene_loading.h"
#ifdef TANDEM_HAS_RENDER
#include "render_command.h"
#endif
#ifdef TANDEM_HAS_EXPORT
#include "export_command.h"
#endif

#include <CLI/CLI.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include <unistd.h>

namespace {

using tandem::BuiltinScene;
using tandem::StepReport;
using namespace tandem::cli;  // exit codes
using tandem::cli::buildInto;
using tandem::cli::nodeCount;
using tandem::cli::overrideSolver;
using tandem::cli::RunLog;
using tandem::cli::SceneInfo;

constexpr long kMaxSteps = 10'000'000;  // 55 hours of a 20 ms step; each is timed and kept

struct RunOptions {
  std::string scene;
  std::string record;
  std::string recordFormat;  // "csv", "npz", or empty: by the file's extension
  bool recordNodes = false;
  std::string reportJson;
  long steps = 0;
  double seconds = 0.0;
  double timeStep = 0.0;
  int iterations = 0;
  int substeps = 0;
  bool report = false;
  bool quiet = false;
};

void printReport(const StepReport& report, const RunLog& log) {
  std::printf("\nTime per stage (mean per step):\n");
  double total = 0.0;
  for (double seconds : log.stageTotals()) total += seconds;
  const double steps = static_cast<double>(log.steps());
  for (size_t s = 0; s < log.stageTotals().size(); ++s)
    std::printf("  %-20s %8.3f ms  %5.1f %%\n", std::string(tandem::kStageNames[s]).c_str(),
                1e3 * log.stageTotals()[s] / steps, total > 0 ? 100.0 * log.stageTotals()[s] / total : 0.0);
  std::printf("Rows by type (last step / maximum):\n");
  for (size_t t = 0; t < report.rowCounts.size(); ++t)
    std::printf("  %-20s %8d / %d\n", std::string(tandem::kRowTypeNames[t]).c_str(), report.rowCounts[t], log.maxRows()[t]);
  std::printf("  %-20s %8d\n", "total", report.totalRows());
  std::printf("Bullet: %d contact manifolds, %d joints\n", report.bulletContactManifolds, report.bulletJoints);
  std::printf("Impact zones, last step: %d, holding %d nodes\n", report.impactZones, report.impactZoneNodes);
  std::printf("Direct-block factorisations: %lld in %lld steps\n", static_cast<long long>(log.blockFactorisations()),
              static_cast<long long>(log.steps()));
  std::printf("Implicit models' solves: at most %d conjugate-gradient iterations in a step; %lld steps short of "
              "their tolerance\n",
              log.maxModelIterations(), static_cast<long long>(log.unconvergedModelSteps()));
  std::printf("RMS of delta-lambda per iteration, last step (N s):");
  for (double rms : report.rmsDeltaLambda) std::printf(" %.3g", rms);
  std::printf("\n");
}

int run(const RunOptions& options) {
  tandem::World world;
  const std::optional<SceneInfo> scene = buildInto(world, options.scene);
  if (!scene) return kExitBadInput;
  if (!overrideSolver(world, options.iterations, options.substeps)) return kExitUsage;
  const double h = options.timeStep > 0 ? options.timeStep : scene->timeStep;
  const double seconds = options.seconds > 0 ? options.seconds : scene->duration;
  const double wanted = std::round(seconds / h);
  if (options.steps == 0 && wanted > static_cast<double>(kMaxSteps)) {
    std::fprintf(stderr, "tandem: %g s at h = %g s is %.3g steps; a run takes at most %ld (use a larger --dt or fewer --seconds)\n",
                 seconds, h, wanted, kMaxSteps);
    return kExitUsage;
  }
  const long steps = options.steps > 0 ? options.steps : std::max(1L, static_cast<long>(wanted));
  if (!options.reportJson.empty() && steps > tandem::cli::kMaxReportJsonSteps) {
    std::fprintf(stderr, "tandem: --report-json keeps every step's report; a run with it takes at most %lld steps, "
                 "this one would take %ld (use a larger --dt or fewer --seconds)\n",
                 static_cast<long long>(tandem::cli::kMaxReportJsonSteps), steps);
    return kExitUsage;
  }
  if (!options.reportJson.empty()) {
    if (tandem::Status s = tandem::cli::createReportJson(options.reportJson); !s) {
      std::fprintf(stderr, "tandem: %s\n", s.message().c_str());
      return kExitOutputFailed;
    }
  }
  std::optional<tandem::StepRecorder> recorder;
  if (!options.record.empty()) {
    const tandem::RecordFormat format = options.recordFormat == "csv"   ? tandem::RecordFormat::Csv
                                        : options.recordFormat == "npz" ? tandem::RecordFormat::Npz
                                                                        : tandem::recordFormatOf(options.record);
    tandem::Result<tandem::StepRecorder> opened = tandem::StepRecorder::open(options.record, options.recordNodes, format);
    tandem::Status written = opened ? opened->write(world) : opened.status();
    if (!written) {
      std::fprintf(stderr, "tandem: %s\n", written.message().c_str());
      return kExitOutputFailed;
    }
    recorder.emplace(std::move(opened).value());
  }

  const int nodes = nodeCount(world);
  if (!options.quiet)
    std::printf("Scene '%s': %s\n  %d deformable bodies (%d nodes), %d rigid bodies; h = %.4g s, %d iterations, %d substeps\n",
                scene->name.c_str(), scene->description.c_str(), world.deformableCount(),
                nodes, world.rigidBodyCount(), h, world.settings().solver.iterations,
                world.settings().solver.substeps);

  const tandem::SolverSettings& solver = world.settings().solver;
  RunLog log(!options.reportJson.empty(), steps, solver.iterations * solver.substeps);
  const bool progress = !options.quiet && isatty(fileno(stdout)) && steps >= 200;
  constexpr long kViolationsShown = 5;
  long violatedSteps = 0;  // violations reported, one per deformable, kind and step
  const auto start = std::chrono::steady_clock::now();
  for (long i = 0; i < steps; ++i) {
    const auto before = std::chrono::steady_clock::now();
    if (tandem::Status s = world.step(h); !s) {
      std::fprintf(stderr, "\ntandem: %s\n", s.message().c_str());
      // What was recorded and reported up to the failed step, for a look at it.
      if (recorder) (void)recorder->close();
      if (!options.reportJson.empty()) {
        const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        const tandem::cli::RunDescription description{options.scene, scene->name, scene->description, h, wall,
                                                      s.message()};
        (void)tandem::cli::writeReportJson(options.reportJson, description, log, world);
      }
      return kExitDiverged;
    }
    if (recorder) {
      if (tandem::Status s = recorder->write(world); !s) {
        std::fprintf(stderr, "\ntandem: %s\n", s.message().c_str());
        return kExitOutputFailed;
      }
    }
    const double stepMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - before).count();
    const StepReport& report = world.lastReport();
    log.add(report, stepMs, world.time());
    for (const tandem::RowViolation& violation : report.violations) {
      if (violatedSteps++ < kViolationsShown)
        std::fprintf(stderr, "%standem: warning: step %ld (t = %.3f s): %s\n", progress ? "\n" : "", i + 1,
                     world.time(), violation.message.c_str());
    }
    if (progress && (i % 50 == 0 || i + 1 == steps)) {
      std::printf("\r  [%-40s] %ld/%ld steps", std::string(40 * (i + 1) / steps, '#').c_str(), i + 1, steps);
      std::fflush(stdout);
    }
  }
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (progress) std::printf("\n");
  if (recorder) {
    if (tandem::Status s = recorder->close(); !s) {
      std::fprintf(stderr, "tandem: %s\n", s.message().c_str());
      return kExitOutputFailed;
    }
  }

  const tandem::cli::Spread stepMs = log.wallMsSpread();
  std::printf("Simulated %.2f s in %ld steps (up to %d rows) in %.3f s of wall time: %.1fx real time\n",
              steps * h, steps, log.maxTotalRows(), wall, wall > 0 ? steps * h / wall : 0.0);
  std::printf("ms per step: mean %.3f, median %.3f, p95 %.3f, max %.3f\n", stepMs.mean, stepMs.median, stepMs.p95,
              stepMs.max);
  if (violatedSteps > 0)
    std::fprintf(stderr, "tandem: warning: %ld violated rows over the run (anchors more than %g m apart, inextensible "
                 "edges stretched more than %g %%); the first %ld are shown above\n", violatedSteps,
                 tandem::kAnchorGapWarning, 100 * tandem::kEdgeStretchWarning, std::min(violatedSteps, kViolationsShown));
  if (!options.quiet) {
    for (int b = 0; b < world.rigidBodyCount(); ++b) {
      const tandem::RigidBodyId id{b};
      if (world.rigidMass(id) == 0) continue;
      const tandem::Vec3 p = world.rigidPosition(id);
      std::printf("  rigid '%s' at (%.3f, %.3f, %.3f) m, speed %.3f m/s\n", world.rigidName(id).c_str(), p.x(), p.y(),
                  p.z(), world.rigidLinearVelocity(id).norm());
    }
  }
  if (options.report) printReport(world.lastReport(), log);
  if (!options.reportJson.empty()) {
    const tandem::cli::RunDescription description{options.scene, scene->name, scene->description, h, wall, ""};
    if (tandem::Status s = tandem::cli::writeReportJson(options.reportJson, description, log, world); !s) {
      std::fprintf(stderr, "tandem: %s\n", s.message().c_str());
      return kExitOutputFailed;
    }
  }
  return violatedSteps > 0 ? kExitViolated : kExitSuccess;
}

// Loads and builds each scene file (without stepping it): every problem a run would meet.
int validate(const std::vector<std::string>& files) {
  int failures = 0;
  for (const std::string& file : files) {
    tandem::Result<tandem::Scene> scene = tandem::loadScene(file);
    tandem::World world;
    tandem::Status built = scene ? tandem::buildScene(*scene, world) : scene.status();
    if (!built) {
      std::fprintf(stderr, "tandem: %s\n", built.message().c_str());
      ++failures;
      continue;
    }
    std::printf("%s: ok (%d rigid bodies, %d deformables with %d nodes, %zu joints, %zu anchors)\n", file.c_str(),
                world.rigidBodyCount(), world.deformableCount(), nodeCount(world), scene->joints.size(), scene->anchors.size());
  }
  return failures ? kExitBadInput : kExitSuccess;
}

// The built-in scenes, then the scene files shipped in scenes/.
void list() {
  std::printf("Built-in scenes (tandem run NAME):\n");
  for (const BuiltinScene& scene : tandem::builtinScenes())
    std::printf("  %-18s %s\n", std::string(scene.name).c_str(), std::string(scene.description).c_str());
  const std::vector<std::filesystem::path> files = tandem::cli::shippedSceneFiles();
  if (files.empty()) return;
  std::printf("Scene files in %s (tandem run FILE):\n", tandem::cli::sceneDirectory().c_str());
  for (const auto& file : files) {
    tandem::Result<tandem::Scene> scene = tandem::loadScene(file.string());
    std::printf("  %-24s %s\n", file.filename().string().c_str(),
                scene ? scene->description.c_str() : "(does not load: see tandem validate)");
  }
}

}  // namespace

// A number that is finite and > 0 (CLI11's ranges let NaN through: every comparison with it is
// false).
const CLI::Validator kFinitePositive(
    [](std::string& text) {
      double value = 0.0;
      if (!CLI::detail::lexical_cast(text, value) || !std::isfinite(value) || value <= 0)
        return std::string("must be a finite number > 0, got ") + text;
      return std::string();
    },
    "POSITIVE");

int main(int argc, char** argv) {
  CLI::App app{"Tandem: two-way coupled rigid and deformable bodies"};
  app.require_subcommand(1);
  app.set_version_flag("--version", std::string("tandem ") + tandem::version());

  RunOptions options;
  CLI::App* runCommand = app.add_subcommand("run", "Run a scene headless and print what it simulated and how fast");
  runCommand->add_option("scene", options.scene, "A scene file (.json) or a built-in scene's name (see `tandem list`)")
      ->required();
  auto* stepsOption =
      runCommand->add_option("--steps", options.steps, "Number of steps")->check(CLI::Range(1L, kMaxSteps));
  runCommand->add_option("--seconds", options.seconds, "Simulated seconds (instead of --steps)")
      ->check(kFinitePositive)
      ->excludes(stepsOption);
  runCommand->add_option("--dt", options.timeStep, "Time step in seconds")->check(kFinitePositive & CLI::Range(1e-6, 1.0));
  runCommand->add_option("--iterations", options.iterations, "Solver iterations K")->check(CLI::Range(1, 1000));
  runCommand->add_option("--substeps", options.substeps, "Solver substeps n per step")->check(CLI::Range(1, 1000));
  runCommand->add_flag("--report", options.report, "Print stage times, row counts and convergence");
  runCommand->add_flag("--quiet", options.quiet, "Print only the summary lines");
  runCommand->add_option("--report-json", options.reportJson,
                         "Write the whole report (settings, stages, rows, convergence, every step) to this JSON file");
  auto* recordOption = runCommand->add_option(
      "--record", options.record, "Write every step's rigid poses and velocities to this file (CSV, or NumPy .npz)");
  runCommand->add_flag("--record-nodes", options.recordNodes, "Also record every deformable node")->needs(recordOption);
  runCommand->add_option("--record-format", options.recordFormat, "csv or npz (default: npz for a .npz file, else csv)")
      ->check(CLI::IsMember({"csv", "npz"}))
      ->needs(recordOption);

  std::vector<std::string> validateFiles;
  CLI::App* validateCommand = app.add_subcommand("validate", "Check scene files: load and build them without running");
  validateCommand->add_option("files", validateFiles, "Scene files")->required();

  CLI::App* listCommand = app.add_subcommand("list", "List the built-in scenes and the shipped scene files");

#ifdef TANDEM_HAS_RENDER
  const std::function<int()> runRenderCommand = tandem::cli::addRenderCommands(app);
#else
  for (const char* name : {"render", "view"})
    app.add_subcommand(name, "(not built: needs GLFW, EGL, OpenGL and Dear ImGui)")->allow_extras()->callback([] {
      std::fprintf(stderr, "tandem: this build has no rendering; install libglfw3-dev libegl-dev libgl-dev "
                           "libimgui-dev and build again (scripts/setup.sh does)\n");
      std::exit(kExitOther);
    });
#endif

#ifdef TANDEM_HAS_EXPORT
  const std::function<int()> runExportCommand = tandem::cli::addExportCommand(app);
#else
  app.add_subcommand("export", "(not built: needs tinygltf)")->allow_extras()->callback([] {
    std::fprintf(stderr, "tandem: this build has no export; install libtinygltf-dev and build again (scripts/setup.sh does)\n");
    std::exit(1);
  });
#endif

  // A first word that is no command gets its own message (CLI11 says "A subcommand is required").
  if (argc > 1 && argv[1][0] != '-') {
    std::string commands;
    bool known = false;
    for (CLI::App* command : app.get_subcommands([](CLI::App*) { return true; })) {
      known |= command->check_name(argv[1]);
      commands += (commands.empty() ? "" : ", ") + command->get_name();
    }
    if (!known) {
      std::fprintf(stderr, "tandem: unknown command '%s' (commands: %s; see tandem --help)\n", argv[1], commands.c_str());
      return kExitUsage;
    }
  }
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& error) {  // CLI11's own codes are 100 and up; --help is 0
    return app.exit(error) == 0 ? kExitSuccess : kExitUsage;
  }
#ifdef TANDEM_HAS_RENDER
  if (const int status = runRenderCommand(); status >= 0) return status;
#endif
#ifdef TANDEM_HAS_EXPORT
  if (const int status = runExportCommand(); status >= 0) return status;
#endif
  if (listCommand->parsed()) {
    list();
    return 0;
  }
  if (validateCommand->parsed()) return validate(validateFiles);
  return run(options);
}
