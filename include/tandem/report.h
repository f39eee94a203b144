// What one step did: stage times, row counts, and how the solver converged (paper §5, Fig. 1).
#pragma once

#include <array>
#include <string>
#include <string_view>
#include <vector>

namespace tandem {

enum class Stage { Models, RigidPrediction, CollisionDetection, Rows, Solve, Integrate, Count };
inline constexpr std::array<std::string_view, static_cast<size_t>(Stage::Count)> kStageNames{
    "models", "rigid prediction", "collision detection", "row setup", "interleaved solve", "integrate"};

enum class RowType { FixedPoint, Anchor, Inextensibility, Bending, Contact, Friction, Grab, Count };
inline constexpr std::array<std::string_view, static_cast<size_t>(RowType::Count)> kRowTypeNames{
    "fixed point", "anchor", "inextensibility", "bending", "contact", "friction", "grab"};

// A row the solve left violated beyond what a user would call holding, at the end of a step: an
// anchor whose two points are more than kAnchorGapWarning apart, an inextensible edge stretched
// more than kEdgeStretchWarning. The step still succeeds; the report (and `tandem run`) says so.
inline constexpr double kAnchorGapWarning = 0.01;  // m
inline constexpr double kEdgeStretchWarning = 0.10;
struct RowViolation {
  enum class Kind { AnchorGap, EdgeStretch };
  Kind kind = Kind::AnchorGap;
  int index = 0;        // the anchor's id, or the edge's index among the deformable's inextensible edges
  double value = 0.0;   // m apart (anchor), or strain (edge)
  std::string message;  // names the deformable, the body and the row
};

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
  // Sparse factorisations of the direct blocks' KKT matrices this step (a block whose pattern is
  // unchanged keeps last step's while it still solves this step's matrix to 1e-4).
  int blockFactorisations = 0;
  // Conjugate-gradient iterations of the implicit models' velocity solves this step (the most of
  // any one solve), and whether each met its tolerance, 10⁻⁴ of its right-hand side, within its
  // limit of 100 (models/implicit_solve.h).
  int modelIterations = 0;
  bool modelsConverged = true;
  // The worst violated row of each kind per deformable, at the step's end (empty when all hold).
  std::vector<RowViolation> violations;
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
