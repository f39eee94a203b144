// What one step did: stage times, row counts, and how the solver converged (paper §5, Fig. 1).
#pragma once

#include <array>
#include <string_view>
#include <vector>

namespace tandem {

enum class Stage { Models, RigidPrediction, CollisionDetection, Rows, Solve, Integrate, Count };
inline constexpr std::array<std::string_view, static_cast<size_t>(Stage::Count)> kStageNames{
    "models", "rigid prediction", "collision detection", "row setup", "interleaved solve", "integrate"};

enum class RowType { FixedPoint, Anchor, Inextensibility, Bending, Contact, Friction, Grab, Count };
inline constexpr std::array<std::string_view, static_cast<size_t>(RowType::Count)> kRowTypeNames{
    "fixed point", "anchor", "inextensibility", "bending", "contact", "friction", "grab"};

struct StepReport {
  std::array<double, static_cast<size_t>(Stage::Count)> stageSeconds{};
  std::array<int, static_cast<size_t>(RowType::Count)> rowCounts{};  // scalar rows per type
  // Root mean square of Δλ over all of Tandem's scalar rows in each iteration's sweep (N·s).
  std::vector<double> rmsDeltaLambda;
  int bulletContactManifolds = 0;
  int bulletJoints = 0;
  // Groups of nodes moved rigidly at the step's end because their surfaces would have crossed.
  int impactZones = 0;
  int impactZoneNodes = 0;
  double totalSeconds = 0.0;

  int totalRows() const {
    int total = 0;
    for (int count : rowCounts) total += count;
    return total;
  }
  double seconds(Stage stage) const { return stageSeconds[static_cast<size_t>(stage)]; }
  int rows(RowType type) const { return rowCounts[static_cast<size_t>(type)]; }
};

}  // namespace tandem
