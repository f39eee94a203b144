// `tandem run --report-json FILE`: the whole report of a run as JSON (docs/report-format.md).
#pragma once

#include "run_log.h"

#include <tandem/world.h>

#include <string>

namespace tandem::cli {

// Per step, RunLog keeps about 150 bytes and the JSON about 250 characters: runs longer than
// this are refused up front rather than run out of memory at the end.
inline constexpr int64_t kMaxReportJsonSteps = 1'000'000;

// What the report says about the run besides its log and its world.
struct RunDescription {
  std::string scene;        // as given on the command line: a file or a built-in scene's name
  std::string name;         // the scene's name
  std::string description;  // the scene's one line
  double timeStep = 0.0;    // h, s
  double wallSeconds = 0.0;
  std::string error;        // why the run stopped early (a step failed), or empty
};

// Creates (truncates) the file, so that a path that cannot be written is named before the run.
Status createReportJson(const std::string& path);

// Writes the report (every step's series too when the log kept them); a file that cannot be
// written is an error naming it.
Status writeReportJson(const std::string& path, const RunDescription& run, const RunLog& log, const World& world);

}  // namespace tandem::cli
