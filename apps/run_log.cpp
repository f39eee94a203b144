#include "run_log.h"

#include <algorithm>

namespace tandem::cli {
namespace {

// The value at `fraction` of the sorted values, to the nearest rank (no interpolation).
double atFraction(const std::vector<double>& sorted, double fraction) {
  const size_t index = std::min(sorted.size() - 1, static_cast<size_t>(fraction * static_cast<double>(sorted.size() - 1) + 0.5));
  return sorted[index];
}

}  // namespace

Spread spreadOf(std::vector<double> values) {
  Spread spread;
  if (values.empty()) return spread;
  double sum = 0.0;
  for (double value : values) sum += value;
  std::sort(values.begin(), values.end());
  spread.mean = sum / static_cast<double>(values.size());
  spread.median = atFraction(values, 0.5);
  spread.p95 = atFraction(values, 0.95);
  spread.p99 = atFraction(values, 0.99);
  spread.min = values.front();
  spread.max = values.back();
  return spread;
}

RunLog::RunLog(bool keepSteps, int64_t stepsExpected, int iterationsPerStep) : m_keepSteps(keepSteps) {
  const auto steps = static_cast<size_t>(std::max<int64_t>(stepsExpected, 0));
  m_wallMs.reserve(steps);
  if (!keepSteps) return;
  m_times.reserve(steps);
  m_stageSeconds.reserve(steps);
  m_rowCounts.reserve(steps);
  for (std::vector<int>* series : {&m_impactZones, &m_impactZoneNodes, &m_contactManifolds, &m_stepViolations})
    series->reserve(steps);
  m_rms.reserve(steps * static_cast<size_t>(std::max(iterationsPerStep, 1)));
  m_rmsStart.reserve(steps + 1);
}

void RunLog::add(const StepReport& report, double wallMs, double time) {
  const int64_t step = steps() + 1;
  m_wallMs.push_back(wallMs);
  for (size_t s = 0; s < kStageCount; ++s) m_stageTotals[s] += report.stageSeconds[s];
  for (size_t t = 0; t < kRowTypeCount; ++t) {
    m_maxRows[t] = std::max(m_maxRows[t], report.rowCounts[t]);
    m_rowSums[t] += report.rowCounts[t];
  }
  m_maxTotalRows = std::max(m_maxTotalRows, report.totalRows());
  m_maxImpactZones = std::max(m_maxImpactZones, report.impactZones);
  m_maxImpactZoneNodes = std::max(m_maxImpactZoneNodes, report.impactZoneNodes);
  if (report.impactZones > 0) ++m_stepsWithImpactZones;
  m_blockFactorisations += report.blockFactorisations;
  m_maxModelIterations = std::max(m_maxModelIterations, report.modelIterations);
  if (!report.modelsConverged) ++m_unconvergedModelSteps;
  if (report.rmsDeltaLambda.size() > m_rmsSums.size()) {
    m_rmsSums.resize(report.rmsDeltaLambda.size(), 0.0);
    m_rmsCounts.resize(report.rmsDeltaLambda.size(), 0);
  }
  for (size_t k = 0; k < report.rmsDeltaLambda.size(); ++k) {
    m_rmsSums[k] += report.rmsDeltaLambda[k];
    ++m_rmsCounts[k];
  }
  for (const RowViolation& violation : report.violations) {
    if (m_violations.size() < kViolationsKept) m_violations.push_back({step, time, violation});
    ++m_violationCount;
  }
  if (!m_keepSteps) return;
  m_times.push_back(time);
  m_stageSeconds.push_back(report.stageSeconds);
  m_rowCounts.push_back(report.rowCounts);
  m_impactZones.push_back(report.impactZones);
  m_impactZoneNodes.push_back(report.impactZoneNodes);
  m_contactManifolds.push_back(report.bulletContactManifolds);
  m_stepViolations.push_back(static_cast<int>(report.violations.size()));
  m_rms.insert(m_rms.end(), report.rmsDeltaLambda.begin(), report.rmsDeltaLambda.end());
  m_rmsStart.push_back(m_rms.size());
}

std::vector<double> RunLog::meanRmsDeltaLambda() const {
  std::vector<double> mean(m_rmsSums.size(), 0.0);
  for (size_t k = 0; k < mean.size(); ++k)
    if (m_rmsCounts[k] > 0) mean[k] = m_rmsSums[k] / static_cast<double>(m_rmsCounts[k]);
  return mean;
}

}  // namespace tandem::cli
