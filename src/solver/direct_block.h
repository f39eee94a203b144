// A direct block: every bilateral, unbounded row of a group of deformables, solved exactly
// together in each sweep (block Gauss-Seidel with one large block per group). A group is the
// deformables that anchors tie to the same dynamic rigid bodies, with those bodies: a rod
// hung on two ropes with a curtain on it is one block, so one sweep solves all of it. Groups
// touching one dynamic body are one block as well, with the free-node bodies touching it
// (World::Impl::buildDirectBlocks): a box on two hammocks is held up by both in one solve.
//
// Why. Projected Gauss-Seidel converges at a rate that falls with the mass ratio across a
// chain of rows times the square of its length: a 10 g-per-node rope holding a 1 kg box needs
// thousands of sweeps to stop stretching, and warm starting an unconverged solution makes it
// oscillate and grow. Solving the rope's rows as one block removes both problems: one sweep
// gives the exact impulses whatever the masses.
//
// What. For the block's scalar rows (fixed points and anchors contribute three each,
// inextensibility one) with Jacobian J over the block's movable degrees of freedom (three per
// free node, six per dynamic rigid body the group is anchored to) and mass matrix M
// (m I per node; m I and the world inertia per rigid body), each sweep solves
//
//   [ H   Jᵀ ] [ Δv ]   [     0      ]       H = M + h² K_g + h² K_e
//   [ J  −E  ] [ −Δλ] = [ −(J v + b) ]       E = ε diag(J M⁻¹ Jᵀ), a tiny compliance that
//                                              keeps redundant rows solvable
//
// so that J (v + Δv) = −b for every row at once, with Δv = H⁻¹ Jᵀ Δλ. The compliance leaves
// a residual E·(−Δλ); one refinement solve per sweep removes it to O(ε²).
//
// Geometric stiffness. A taut rope of light nodes holding a heavy body has sideways modes of
// frequency √(T / m L); once h times that passes 2 the velocity-level linearisation, which
// takes J at the start of the step, pumps energy into them and the rope buckles and stretches
// (Tournier et al. 2015, "Stable constrained dynamics"). K_g is the stiffness of the rows'
// forces under sideways motion, h² K_g = h |λ| / L (I − n nᵀ) per taut edge (λ from the last
// step), coupling the edge's two nodes as [G −G; −G G]. Its columns sum to zero, so internal
// rows still conserve momentum exactly; edges in compression get none (theirs is negative).
//
// Elastic stiffness. An FEM body's v* comes from the implicit solve (M − h² K) Δv = …, so an
// impulse on it moves its nodes by (M − h² K)⁻¹ Jᵀ Δλ, not by M⁻¹ Jᵀ Δλ: a box set on a jelly is
// held by the whole jelly at once, not by the few light nodes under it. h² K_e = −h² K (from
// the FEM model, the same rotations as its solve) enters H when the body has a block (rows of
// its own, or set `direct`), and its contacts join it. Its columns sum to zero too. An FEM body
// without rows is swept: its own solve carries what rests on it (models/supports.h).
//
// Velocities are set from M Δv = Jᵀ Δλ − h² (K_g + K_e) Δv after the solve, so momentum is exact
// to rounding whatever the solve's own residual.
//
// Friction in the block's metric. A contact's friction competes with the block's rows: on a rope
// over a wheel, a tangential impulse on one 0.2 g node is passed along the whole rope to the
// loads at its ends. Swept as a PGS row with the node's own mass, each iteration moves the rope
// by m_node v_slip and the block spreads it over kilograms: the rope slid over the wheel as if
// frictionless. So the friction of (up to kMaxFrictionContacts of) a block's contacts with
// dynamic bodies, and in blocks of ropes all of them, is solved
// after the block in each sweep, on the block's constrained response: for each tangent t the
// KKT solve with the impulse Jₜᵀ gives the velocity change of every node and body with the
// block's rows kept (and their Δλ), W = Jₜ Δv is the exact 2×2 inverse effective mass, and
// Δλₜ = −W⁻¹ vₜ, clamped to the disc |λₜ| ≤ μ λₙ, moves the whole block at once (shortened so
// that no contact of the block is left pulling). A surface's contacts with still shapes keep
// their friction in the PGS sweep: applied to a cloth draped over a pyramid, the block's
// friction pressed nodes 2.6 mm past their thickness into the shape (Shapes/ClothDrop/hull).
// A contact the block lets go takes its friction back the way it was given, through the block (a
// known load, with its normal impulse), before the sweep owns it: taken back on its own light
// nodes, it threw a weight hung from a flag's face (addReleasedFriction).
//
// Warm start of the anchors to dynamic bodies. Each of K iterations is one Bullet iteration and
// then one sweep, so a body that both a block and Bullet's contacts hold is held in turns: a
// teapot standing on the floor held up at its knob by a rope (rope_wheel.json once the heavy one
// has landed: the rope carries 9.2 of its 12.75 N). With the block's rows starting every step at
// zero, Bullet's first iteration found the teapot unheld and its floor contacts took its whole
// weight, the block then pulled 9.2 N back off them, and the four turns never settled how the
// contacts share what is left: the teapot rocked on two of its contact points with an angular
// velocity changing sign every step (0.070 rad/s on average, walking 12 mm in 14 s; 0.002 rad/s
// at K = 32). So an anchor to a dynamic body keeps last step's impulse λ₀ (startImpulses): the
// body's share −λ₀ is applied before Bullet's first iteration, and the nodes' share Jₙᵀ λ₀ waits
// for the block's first solve as a known load f, H Δv = Jᵀ Δλ + f, so that the nodes answer it as
// the block does (geometric stiffness included; by m⁻¹ the 0.2 g nodes at a 1 kg body's knob took
// 100 m/s and the rope diverged). The block being exact, its answer is the same from either
// start (the Atwood machine's bodies and nodes agree to 10⁻⁷ m/s with warm starting on and off):
// only the turns with Bullet change (the teapot: 0.011 rad/s, 1 mm in 14 s;
// PaperScenes.RopeWheelLandedTeapotStandsStill). The load is not part of the scale the kept
// factorisation's residual is judged against (below): over a 0.2 g node's diagonal it reads as
// hundreds of m/s, and a tolerance of 10⁻⁴ of that let the kept factorisation release 17 of the
// Atwood machine's contacts in one sweep.
//
// The KKT matrix is symmetric quasi-definite, so a sparse LDLᵀ without pivoting (AMD ordering)
// factorises it; each sweep is one pair of triangular solves (plus a small dense solve for the
// contacts let go, which drops their equations without refactorising, up to 32 of them) and
// one step of iterative refinement against this step's matrix A₀ (z += F⁻¹ (rhs − A₀ z)). Rows
// with bounds (finite max force, one-sided modes) stay in the PGS sweep, which runs before the
// block in every iteration.
//
// Factorisations kept. A block whose rows and contacts are the same as last step's (its pattern
// unchanged), and that let no contact go last step, keeps last step's factorisation F instead of
// computing a new one: a jelly at rest under a bar changes its matrix by about a part in a
// thousand per step, and the factorisation was most of its step's cost. The refinement step
// above makes the solve exact for A₀ all the same, to the square of F's relative error (about
// 2·10⁻⁶ of the right-hand side for a one-step-old F, 10⁻¹⁵ for a fresh one); the first solve of
// every sweep measures what is left, and past a part in ten thousand of the step's largest
// right-hand side so far takes a second refinement step (in every solve from then on, until the
// next factorisation), and past that again the block is factorised afresh and solved again. (With
// one step only, jelly_dish was factorised in 120 of 500 steps, 104 of them for this check; with
// two, in 54.) Measured in each sweep, not only in the step's first: a step that starts from rest
// in a new pose can find a kept factorisation exact enough for its first right-hand side and not
// for the later sweeps', whose errors then grew about ninefold a sweep (rope_wheel.json stopped
// dead every step at K = 16 threw its rope off at 10 km/s:
// PaperScenes.RopeWheelStoppedDeadEveryStepStaysStillAtSixteenIterations). Momentum is untouched
// either way: velocities come from the impulses (below). A fresh factorisation's refinement is
// the compliance's alone, as it always was.
// The friction responses are not refined: with a kept factorisation they are the exact responses
// of the system it was made for, a few steps old, which conserves momentum as this step's does;
// the effective masses they give differ from this step's by the same part in a thousand or so,
// and what the friction pass leaves of this step's rows the next sweep's refined solve takes up.
// (Their refinement step was a second pass over the factor for every column: 2.3 of the jelly
// dish's 25 ms per step.) Nor are they solved again in every step a factorisation is kept: a
// response is linear in its right-hand side, which is a contact's impulse on its nodes' and its
// body's degrees of freedom, so F⁻¹ of a unit impulse on each of those (three per node, one per
// free direction of a body) is kept with F, and each step's responses, whatever their tangents
// and offsets, are sums of those columns (the same to rounding; jelly_dish 7 % fewer
// instructions over its first 3 s).
#pragma once

#include <tandem/report.h>

#include "collision/contact_motion.h"
#include "solver/constraint_rows.h"
#include "solver/sparse_assembly.h"

#include <Eigen/Dense>
#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>

#include <cstdint>
#include <memory>
#include <utility>
#include <vector>

namespace tandem {

struct BlockRowRef {
  RowType type;
  int32_t index;    // into the row array of that type
  int32_t component;  // 0..2 for the three rows of a fixed point or anchor, 0 otherwise
};

class DirectBlock {
 public:
  // The nodes of the deformables in the block: ranges of global node indices.
  struct NodeRange {
    int32_t first;
    int32_t count;
    // A rope (no faces, no tetrahedra): a chain, with no redundant rows (see the geometric
    // stiffness), whose contacts' friction is always solved in the block's metric.
    bool chain = false;
    // Its nodes are tied together (rows, an elastic model), so their contacts' friction is solved
    // in the block's metric; a body with neither, there only for the rigid body it touches with
    // the rest, has free nodes, whose friction the sweep solves exactly and cheaply.
    bool tied = true;
  };
  explicit DirectBlock(std::vector<NodeRange> ranges);

  // Finds every bilateral unbounded row on the body's nodes. Call again when rows are added.
  void collectRows(const ConstraintRows& rows);
  // Takes the collected rows out of the PGS sweep: from now on this block solves them.
  void claimRows(ConstraintRows& rows) const;

  // This step's contacts that touch (gap ≤ slop) and whose nodes are all the block's join it
  // as equality rows, so a heavy body resting on a light cloth is held by the whole cloth in
  // one solve; a contact that would pull is let go (and the block solved again without it). Call after the rows are
  // prepared, before prepare().
  void addContacts(ConstraintRows& rows, std::span<const RigidSolverState> rigid, double slop);
  int scalarRowCount() const { return static_cast<int>(m_rows.size()); }

  // Assembles and factorises the KKT matrix for this step. Rows must be prepared first;
  // their λ still hold the last step's impulses (for the geometric stiffness).
  // `elastic` is h² K_e, pairs on nodes outside the block ignored.
  void prepare(const ConstraintRows& rows, const NodeArrays& nodes, std::span<const RigidSolverState> rigid,
               double timeStep, std::span<const NodePairStiffness> elastic);

  // Starts the block's rows for this step (after prepare has read λ): from zero, except its
  // anchors to dynamic bodies, which keep last step's impulse (the header's "Warm start").
  void startImpulses(ConstraintRows& rows, SolverContext& ctx);

  // After integration: moves the block's nodes by Δx solving [H Jᵀ; J −E] [Δx; −μ] = [0; −C(x)]
  // with this step's factorisation (J from the start of the step), so that its fixed points and
  // inextensible edges hold by position too, and a block of ropes' anchors close (`poses`: every
  // rigid body's pose now, for their gaps); contact rows, and a surface's anchors, hold their
  // points as they are.
  // The dynamic bodies its anchors hold move by the same solve: their moves (translation and
  // rotation vector, about the centre of mass) are appended to `bodyMoves` for the caller to
  // apply. Returns false when it did not (no rows, no factorisation, a dynamic body that a
  // contact of the block touches, a sheet resting on itself or on another deformable, or a sheet
  // whose worst edge the step would have lengthened: then its nodes are left where they were,
  // for the strain-limiting passes).
  struct BodyMove {
    int32_t body;
    Vec3 translation, rotation;
  };
  bool projectPositions(const ConstraintRows& rows, NodeArrays& nodes, std::span<const RigidPose> poses,
                        std::vector<BodyMove>& bodyMoves);
  const std::vector<NodeRange>& ranges() const { return m_ranges; }

  // One exact solve of the block against the current velocities.
  void solve(ConstraintRows& rows, SolverContext& ctx, SweepStats& stats);
  // Numeric factorisations since the last call (for the step report), and resets the count.
  int takeFactorisationCount() { return std::exchange(m_factorisations, 0); }
  // Then one pass over the friction of its contacts, in its metric (above), bounded by the
  // normal impulses that solve gave.
  void solveFriction(ConstraintRows& rows, SolverContext& ctx, FrictionModel model, SweepStats& stats);

 private:
  using SparseMatrix = Eigen::SparseMatrix<double>;
  // Right-hand sides side by side: a row per unknown, so one pass over the factor serves them all.
  using ColumnBlock = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

  std::vector<NodeRange> m_ranges;
  int32_t m_nodeCount = 0;  // over all ranges
  std::vector<BlockRowRef> m_rows;  // the persistent rows first, then this step's contacts
  std::vector<int32_t> m_bodies;     // rigid bodies of the block's anchors, then of its contacts
  size_t m_persistentRows = 0;
  size_t m_persistentBodies = 0;

  std::vector<int32_t> m_nodeDof;  // per node of the block: its first degree of freedom, or −1 if pinned
  std::vector<int32_t> m_bodyDof;  // per entry of m_bodies: first degree of freedom, or −1 if immovable
  bool m_movesBodies = false;      // has some, none in a contact with its nodes: projectPositions moves them
  int32_t m_dofCount = 0;
  Eigen::VectorXd m_bias;
  Eigen::VectorXd m_compliance;  // E, per row
  std::vector<bool> m_active;  // rows where nothing can move are left out of the solve
  // Eigen's factorisations cannot move; the block can.
  std::unique_ptr<Eigen::SimplicialLDLT<SparseMatrix>> m_factor = std::make_unique<Eigen::SimplicialLDLT<SparseMatrix>>();
  bool m_factorOk = false;
  Eigen::VectorXd m_inverseDiagonal;  // D⁻¹ of the factorisation
  // The factorisation is of this step's values (else of an earlier step's, with this pattern).
  bool m_factorFresh = false;
  // It was made by prepare(), with every row in: an earlier step's may be kept (a factorisation
  // after releases has their rows dropped, far from next step's matrix).
  bool m_factorReusable = false;
  int m_factorisations = 0;
  int m_keptRefinements = 1;  // refinement steps per solve with the kept factorisation
  double m_stepRhsScale = 0.0;  // the largest right-hand side of this step's solves, scaled
  std::vector<int> m_analysedOuter, m_analysedInner;  // the pattern the ordering was computed for
  Eigen::VectorXd m_rhs, m_solution, m_refinement, m_residual;
  std::vector<Vec3> m_positionsBefore;  // projectPositions' nodes, to undo a step that did not help
  // The low-rank correction for the rows let go since the last factorisation (release()), in
  // storage of at most kLowRankReleases, so that it never allocates.
  static constexpr Eigen::Index kLowRankReleases = 32;
  using ReleasedVector = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, kLowRankReleases, 1>;
  using ReleasedMatrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, kLowRankReleases, kLowRankReleases>;
  mutable ReleasedVector m_atReleased, m_releasedMultipliers;  // scratch of dropReleasedEquations
  // Scratch of solveWithFactor, for one right-hand side or many in turn: a std::vector keeps its
  // capacity when it shrinks, where an Eigen vector would allocate again.
  mutable std::vector<double> m_permuted, m_partialSums;
  mutable Eigen::VectorXd m_column;                    // scratch of solveKktColumns
  ColumnBlock m_columns;                 // right-hand sides of the friction responses
  Eigen::VectorXd m_velocityChange;    // scratch: of the block's degrees of freedom
  Eigen::VectorXd m_rowImpulseChange;  // scratch: Δλ of the block's rows
  SparseMatrix m_jacobianT;         // Jᵀ: dofs × rows
  std::vector<Eigen::Triplet<double>> m_jacobianTEntries;
  SparseAssembly m_jacobianTAssembly{SparseAssembly::Part::Whole};
  Eigen::VectorXd m_inverseMass;    // per node degree of freedom
  // Per entry of m_bodies: its free directions G (6 × k) and (Gᵀ 𝕄 G)⁻¹; for a free body
  // G = I and the inverse is diag(m⁻¹ I, I⁻¹).
  struct BodyMotion {
    int freedoms = 0;
    Mat6 basis = Mat6::Identity();
    Mat6 inverseMass = Mat6::Zero();
    // Gᵀ (P, r × P): an impulse P at offset r in the free directions (first k entries).
    Vec6 generalisedImpulse(const Vec3& p, const Vec3& offset) const {
      Vec6 f;
      f << p, offset.cross(p);
      return basis.transpose() * f;
    }
  };
  std::vector<BodyMotion> m_bodyMotion;
  SparseMatrix m_stiffness;         // h² (K_g + K_e): dofs × dofs
  SparseAssembly m_stiffnessAssembly{SparseAssembly::Part::Whole};
  std::vector<Eigen::Triplet<double>> m_entries;  // the KKT matrix, kept to release contacts
  SparseAssembly m_kktAssembly{SparseAssembly::Part::LowerTriangle};  // of m_entries into m_kkt
  SparseMatrix m_kkt;                                                 // its lower triangle, factorised
  std::vector<std::pair<size_t, size_t>> m_rowEntries;  // each row's entries; its diagonal last
  std::vector<bool> m_released;  // contacts let go this step
  std::vector<char> m_releasedHere;     // scratch of solve(): let go in this solve
  Eigen::VectorXd m_prescribed;         // scratch of solve(): their Δλ = −λ so far
  Eigen::VectorXd m_pendingLoad;       // the anchors' warm start on their nodes, until the first solve
  bool m_loadPending = false;
  std::vector<int32_t> m_releasedNow;   // scratch of solve(): let go in this round
  std::vector<Eigen::Index> m_releasedRows;  // KKT rows let go since the last factorisation
  Eigen::MatrixXd m_releasedColumns;  // A⁻¹ e_r for each of them: its first m_releasedRows.size() columns
  ReleasedMatrix m_releasedCouplingMatrix;                 // those columns' released rows
  Eigen::PartialPivLU<ReleasedMatrix> m_releasedCoupling;  // and its factorisation
  std::vector<double> m_releaseRhs;  // scratch of solveUnitColumns(): unit right-hand sides, row by row
  // A⁻¹ e_r of rows let go with this factorisation, kept while it is: a jelly at rest under a bar
  // keeps its factorisation for steps and lets the same contacts go in each (the first
  // m_cachedRows.size() columns, at most kLowRankReleases; cleared by a new factorisation).
  std::vector<Eigen::Index> m_cachedRows;
  Eigen::MatrixXd m_cachedColumns;
  std::vector<Eigen::Index> m_uncached;  // scratch of release(): its rows not in the cache

  // Per contact with friction in the block (its row index r), per tangent (columns `column` and
  // `column` + 1 of the matrices below): the velocity change of the block's degrees of freedom
  // and the Δλ of its rows for a unit tangential impulse.
  struct FrictionResponse {
    int32_t row = 0;
    Eigen::Index column = 0;
    Eigen::Matrix2d effectiveMass = Eigen::Matrix2d::Zero();  // W⁻¹
  };
  std::vector<FrictionResponse> m_friction;
  ColumnBlock m_frictionVelocity;                     // dofs × 2 per contact: Δv
  ColumnBlock m_frictionImpulse;                      // rows × 2 per contact: Δλ
  bool m_frictionStale = true;  // the system changed since the responses were computed
  // With a kept factorisation F the friction responses are sums of F⁻¹ of unit impulses on the
  // degrees of freedom the contacts touch (three per node, one per free direction of a body),
  // kept while F is: the responses' right-hand sides change every step (the tangents follow the
  // slip, the offsets the body), those units do not. A jelly at rest under a bar then solves its
  // friction columns once per factorisation instead of once per step.
  static constexpr Eigen::Index kMaxUnitResponses = 96;
  int m_factorGeneration = 0;              // numeric factorisations so far
  int m_unitGeneration = -1;               // the one m_unitResponses are of
  std::vector<int32_t> m_unitColumnOfDof;  // per degree of freedom: its column there, or −1
  Eigen::Index m_unitCount = 0;
  ColumnBlock m_unitResponses;             // (dofs + rows) × kMaxUnitResponses, raw F⁻¹ (no releases)
  struct UnitWeight {
    int32_t unit;
    Eigen::Index column;
    double value;
  };
  std::vector<UnitWeight> m_unitWeights;   // how much of which unit each friction column is
  std::vector<Eigen::Index> m_unitMissing;  // scratch: degrees of freedom still without a unit column
  // The friction columns' right-hand sides in m_columns solved: from the unit responses when F
  // is kept and they fit, else directly.
  void solveFrictionColumns(const ConstraintRows& rows);

  void computeFrictionResponses(const ConstraintRows& rows);
  void addRowImpulses(ConstraintRows& rows, const Eigen::VectorXd& deltaLambda, SolverContext& ctx) const;
  // −λₜ Jₜᵀ of each contact let go in this solve whose friction the block solved, added to `onDofs`.
  void addReleasedFriction(const ConstraintRows& rows, Eigen::VectorXd& onDofs) const;
  void toVelocityChange(Eigen::VectorXd& impulses) const;
  void applyVelocityChange(const Eigen::VectorXd& change, SolverContext& ctx) const;
  void applyPendingLoad(SolverContext& ctx);  // by m⁻¹, when there is no factorisation to solve with
  // Jᵀ of a row along `axis` written into a column of `target` (zero there before).
  void writeImpulseOnDofs(const ContactRow& row, const Vec3& axis, ColumnBlock& target, Eigen::Index column) const;
  // The same entries handed to visit(first degree of freedom, values).
  template <typename Visit>
  void visitImpulseOnDofs(const ContactRow& row, const Vec3& axis, Visit&& visit) const;
  int32_t localNode(int32_t node) const;  // index among the block's nodes, or −1
  // Whether a contact among deformables on the block's nodes pushed in this step.
  bool restsOnDeformable(const ConstraintRows& rows) const;
  size_t blockBody(int32_t body) const;   // index in m_bodies, or m_bodies.size()
  double worstEdgeError(const ConstraintRows& rows, const NodeArrays& nodes) const;
  int32_t globalNode(int32_t local) const;
  const NodeRange& rangeOf(int32_t node) const;  // of one of the block's nodes
  // `mayKeep`: an earlier factorisation of the same pattern is kept instead (see the header);
  // `reusable`: this one may be kept in later steps (every row of the step in it).
  void factorise(bool mayKeep, bool reusable);
  // rhs − A₀ z, A₀ this step's KKT matrix without the active rows' compliance, released rows' 0.
  void residual(const Eigen::VectorXd& rhs, const Eigen::VectorXd& z, Eigen::VectorXd& out) const;
  // z += F⁻¹ (rhs − A₀ z): the refinement step a kept factorisation F needs (see the header).
  void refineWithKeptFactor(const Eigen::VectorXd& rhs, Eigen::VectorXd& z);
  double scaledNorm(const Eigen::VectorXd& v) const;  // max |v_i|, a degree of freedom's over H_ii
  void release(const std::vector<int32_t>& rows);
  // out = F⁻¹ in for `width` right-hand sides stored row by row (in and out may be the same).
  void solveWithFactor(const double* in, double* out, Eigen::Index width) const;
  // z, solved with the factorisation, corrected to have the released rows' equations dropped.
  void dropReleasedEquations(Eigen::VectorXd& z) const;
  // z = A⁻¹ rhs, with the released rows' equations dropped; z must not alias rhs.
  void solveKkt(const Eigen::VectorXd& rhs, Eigen::VectorXd& z) const;
  // The same for many right-hand sides at once, in place: the columns of `x` in, A⁻¹ of them out
  // (`withReleased`: the released rows' equations dropped, else the factorised system's).
  void solveKktColumns(ColumnBlock& x, bool withReleased) const;
  // F⁻¹ e_i for each KKT index i in `at`, into the columns of `target` from `first` on.
  template <typename Target>
  void solveUnitColumns(const std::vector<Eigen::Index>& at, Target& target, Eigen::Index first);
  void dropReleasedEquations(ColumnBlock& x) const;  // solveKktColumns' second half
  double rowVelocity(const ConstraintRows& rows, const BlockRowRef& ref, const SolverContext& ctx) const;
};

}  // namespace tandem
