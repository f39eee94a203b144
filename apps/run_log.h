// What `tandem run` keeps of a run, step by step: the wall time of each step and its report
// (stage times, rows by type, RMS Δλ per iteration, impact zones, violated rows). From it come
// the summary `--report` prints and the whole report `--report-json` writes (apps/report_json.cpp,
// documented in docs/report-format.md).
#pragma once

#include <tandem/report.h>

#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace tandem::cli {

inline constexpr size_t kStageCount = static_cast<size_t>(Stage::Count);
inline constexpr size_t kRowTypeCount = static_cast<size_t>(RowType::Count);

// A violated row at the end of a step, with the step it was found in.
struct LoggedViolation {
  int64_t step = 0;
  double time = 0.0;  // s, at the step's end
  RowViolation violation;
};

// Summary statistics of a series of numbers.
struct Spread {
  double mean = 0.0;
  double median = 0.0;
  double p95 = 0.0;
  double p99 = 0.0;
  double min = 0.0;
  double max = 0.0;
};
Spread spreadOf(std::vector<double> values);

class RunLog {
 public:
  // Every step's report is kept only when `keepSteps`; the summary (stage totals, maxima, ms per
  // step, violations) is kept in any case. `iterationsPerStep` (K·n) sizes the RMS series.
  RunLog(bool keepSteps, int64_t stepsExpected, int iterationsPerStep);

  // Takes the report of the step that just ended, its wall time and the world's time after it.
  void add(const StepReport& report, double wallMs, double time);

  int64_t steps() const { return static_cast<int64_t>(m_wallMs.size()); }
  bool keepsSteps() const { return m_keepSteps; }
  const std::vector<double>& wallMs() const { return m_wallMs; }
  Spread wallMsSpread() const { return spreadOf(m_wallMs); }
  // Seconds spent in each stage over the whole run.
  const std::array<double, kStageCount>& stageTotals() const { return m_stageTotals; }
  const std::array<int, kRowTypeCount>& maxRows() const { return m_maxRows; }
  const std::array<double, kRowTypeCount>& rowSums() const { return m_rowSums; }
  int maxTotalRows() const { return m_maxTotalRows; }
  int maxImpactZones() const { return m_maxImpactZones; }
  int maxImpactZoneNodes() const { return m_maxImpactZoneNodes; }
  int64_t stepsWithImpactZones() const { return m_stepsWithImpactZones; }
  int64_t blockFactorisations() const { return m_blockFactorisations; }  // over the run
  int maxModelIterations() const { return m_maxModelIterations; }          // in any one step
  int64_t unconvergedModelSteps() const { return m_unconvergedModelSteps; }
  // Every violated row reported over the run (the first kViolationsKept of them are kept).
  int64_t violationCount() const { return m_violationCount; }
  const std::vector<LoggedViolation>& violations() const { return m_violations; }
  static constexpr size_t kViolationsKept = 1000;
  // Mean RMS Δλ of each iteration index over the steps that had that iteration.
  std::vector<double> meanRmsDeltaLambda() const;

  // Per step (only when keepsSteps()).
  const std::vector<double>& times() const { return m_times; }
  const std::vector<std::array<double, kStageCount>>& stageSeconds() const { return m_stageSeconds; }
  const std::vector<std::array<int, kRowTypeCount>>& rowCounts() const { return m_rowCounts; }
  const std::vector<int>& impactZones() const { return m_impactZones; }
  const std::vector<int>& impactZoneNodes() const { return m_impactZoneNodes; }
  const std::vector<int>& contactManifolds() const { return m_contactManifolds; }
  const std::vector<int>& stepViolations() const { return m_stepViolations; }
  // Step i's RMS Δλ per iteration: rms()[rmsStart()[i] .. rmsStart()[i + 1]).
  const std::vector<double>& rms() const { return m_rms; }
  const std::vector<size_t>& rmsStart() const { return m_rmsStart; }

 private:
  bool m_keepSteps = false;
  std::vector<double> m_wallMs;
  std::array<double, kStageCount> m_stageTotals{};
  std::array<int, kRowTypeCount> m_maxRows{};
  std::array<double, kRowTypeCount> m_rowSums{};
  int m_maxTotalRows = 0;
  int m_maxImpactZones = 0;
  int m_maxImpactZoneNodes = 0;
  int64_t m_stepsWithImpactZones = 0;
  int64_t m_blockFactorisations = 0;
  int m_maxModelIterations = 0;
  int64_t m_unconvergedModelSteps = 0;
  int64_t m_violationCount = 0;
  std::vector<LoggedViolation> m_violations;
  std::vector<double> m_rmsSums;
  std::vector<int64_t> m_rmsCounts;

  std::vector<double> m_times;
  std::vector<std::array<double, kStageCount>> m_stageSeconds;
  std::vector<std::array<int, kRowTypeCount>> m_rowCounts;
  std::vector<int> m_impactZones, m_impactZoneNodes, m_contactManifolds, m_stepViolations;
  std::vector<double> m_rms;
  std::vector<size_t> m_rmsStart{0};
};

}  // namespace tandem::cli
