// The implicit velocity step of the force-based models (co-rotational FEM, mass-spring).
//
// Explicit steps of jelly-like stiffness are unstable at h = 1/50 s (E = 50 kPa on a 2 cm
// element needs h < 1 ms), so the velocity is solved by linearised backward Euler:
//   (M − h D − h² K) Δv = h (f(x, v) + f_ext) + h² K v,   v* = v + Δv
// with K = ∂f/∂x and D = ∂f/∂v. K sums the FEM elements' (models/corotational_fem.h) and the
// springs': an edge of stiffness k, rest length L, length l and direction n gives the pair
// [S −S; −S S] with S = k (n nᵀ + max(0, 1 − L/l) (I − n nᵀ)) — the sideways term of a
// compressed spring is dropped so that −K stays positive semi-definite — and a damper c gives
// D the same pattern with c n nᵀ. M − h D − h² K is then symmetric positive definite: conjugate
// gradients, warm-started from last step's Δv, with pinned nodes held at Δv = 0. The elements' K
// is assembled once per solve as 3 × 3 blocks per node pair with this step's rotations (a
// product is then one block per pair: the paper's jelly scene's landing steps, 176 iterations,
// went from 21 to 15 ms); the springs' stay per spring.
//
// Supported nodes (models/supports.h) are held along their surface's normal at the normal
// velocity the contact will give them, by filtered conjugate gradients (Baraff and Witkin 1998):
// Δv·n is prescribed, the rest solved. The hold's impulse is c = (A Δv − b)·n; a hold that
// would pull (c < 0) is let go and the solve repeated, so bodies still lift off. Without the
// holds a resting jelly stays 12 % squashed, and a dropped one, whose upper layers fall on
// through the impact step with nothing resisting, is launched higher than it fell.
//
// Friction on a still support (models/supports.h) is solved here too. A held node whose surface
// has friction μ is first stuck: held along the surface as well, its whole Δv prescribed (the
// surface's velocity there), its hold's impulse c = A Δv − b then a vector. While c stays in
// the cone, |c − (c·n) n| ≤ μ c·n, static friction holds the whole body in this solve's metric;
// once outside, the node slides, pushed along the surface by the cone's edge, μ (c·n) in the
// direction of c's tangential part, a known load added to b, and the solve is repeated. A node
// that ended last step sliding starts sliding, pushed by μ times last step's push against its
// slip (or along its last friction, when it slipped less than 1 mm/s); if its push turns the slip
// back, it sticks (once per step). At most four rounds: a step that runs out of them keeps the
// last round's holds. The push is part of the support's impulse. Friction rows alone, each on
// one node's mass after this solve, could not hold an elastic body: a jelly with μ = 1 slid down
// a 30° slope at 2.7 m/s² (the rows stop its bottom layer in each step, the next solve drags it
// along with the rest), and at 6.0 m/s² down a 50° one instead of 1.2.
//
// A moving support (a dynamic body resting on the body, models/supports.h) adds its velocity
// change (ΔV, ΔΩ) to the unknowns: its held nodes take n (n · (ΔV + ΔΩ × r)) on top of their
// prescribed change, and the system solved is the one restricted to those motions,
//   [ Sᵀ A S     Sᵀ A N ] [ y  ]   [ Sᵀ b               ]
//   [ Nᵀ A S   M + Nᵀ A N ] [ ΔY ] = [ Nᵀ b + (h m g, 0) ],   M = diag(m I, I_world),
// (the prescribed part's product moved to the right), with S the filter and N the map from
// (ΔV, ΔΩ) to the held nodes' normal motion: still
// symmetric positive definite, so the same conjugate gradients solve it (a 3 × 3 Jacobi block per
// support and motion). Implicit bodies that share a moving support are solved as one system.
// A hold's impulse c = (A Δv − b) · n on a node is −c n on its support at r.
//
// The same h D + h² K goes to the body's direct block (addImplicitStiffness) when it has one
// (rows of its own: anchors, fixed points), so that impulses from contacts and attachments move
// the body as this step would.
#pragma once

#include "models/corotational_fem.h"
#include "models/mass_spring.h"
#include "models/supports.h"

#include <span>
#include <vector>

namespace tandem {

struct ImplicitBody {
  int32_t firstNode = 0;
  int32_t nodeCount = 0;
  FemElements fem;                  // none for a mass-spring body
  std::vector<EdgeSpring> springs;  // global indices
  std::vector<Vec3> previousStep;   // last step's Δv, the solve's starting guess (local indices)
  std::vector<Mat3> rotations;      // of each element at this step's positions, from the solve
  // The elements' −K by node pair (global indices) with this step's rotations, made once per
  // solve, each pair once (a ≤ b; (b, a) is its transpose): a product by it is a block and its
  // transpose per pair where the elements' own took four 3 × 3 products per element.
  std::vector<NodePairStiffness> stiffnessBlocks;
  int lastIterations = 0;      // conjugate-gradient iterations of the last step
  bool lastConverged = true;   // whether they met the tolerance within their limit
};

ImplicitBody makeImplicitBody(int32_t firstNode, int32_t nodeCount, FemElements fem, std::vector<EdgeSpring> springs);

// A spring's stiffness block k (n nᵀ + max(0, 1 − L/l) (I − n nᵀ)) and its damper's c n nᵀ.
struct SpringBlocks {
  Mat3 stiffness = Mat3::Zero();
  Mat3 damping = Mat3::Zero();
};

// A dynamic body that implicit bodies rest on, moving with their solve (models/supports.h): its
// mass and inertia (world frame, about its centre of mass), and the impulse and angular impulse
// the rest of the world gives it in the step besides gravity, taken as last step's (its other
// contacts and joints, the sweep's rows).
struct MovingSupport {
  int32_t body = -1;
  double mass = 0.0;
  Mat3 inertia = Mat3::Zero();
  Vec3 otherImpulse = Vec3::Zero(), otherAngularImpulse = Vec3::Zero();
};

// Working memory of solveImplicitVelocities (per node of the solved bodies, in their order),
// kept by the caller between steps so that the solve allocates nothing once grown.
struct ImplicitSolveScratch {
  std::vector<Vec3> velocity, position, force, product, b, stiffnessTimesVelocity, held, r, z, p, ap, full, x;
  std::vector<double> mass, preconditioner, heldChange;
  std::vector<Mat3> nodePreconditioner;  // per node: its 3 × 3 diagonal block of A, inverted
  // Per node held with friction: μ, the Δv that sticks it, its sliding push (zero while stuck),
  // and whether it is stuck, and has stuck after sliding in this step.
  std::vector<double> friction;
  std::vector<Vec3> stuckChange, slidingPush;
  std::vector<char> stuck, restuck;
  std::vector<Vec3> offset;         // per node on a moving support: from its centre of mass
  std::vector<int32_t> movingOf;    // per node: its moving support's index, or −1
  std::vector<int32_t> sliceStart;  // per body: its first node in these vectors
  std::vector<EdgeSpring> springs;  // the bodies', in these vectors' indices
  std::vector<SpringBlocks> springBlocks;
  std::vector<Mat3> dampedSpringBlocks;  // h² K_s + h D_s, what the products apply
  // Per moving support, linear then angular: Δ, residual, preconditioned residual, direction,
  // product, and the preconditioner's 3 × 3 blocks (inverted).
  std::vector<Vec3> supportChange, supportResidual, supportPreconditioned, supportDirection, supportProduct;
  std::vector<Mat3> supportPreconditioner;
};

// v ← v + Δv for the bodies' free nodes, solved together with the moving supports they share
// (one body alone when it has none); gravity and the forces already in `nodes.force` are their
// external forces, taken explicitly. Writes the holds' impulses to each body's supports.
void solveImplicitVelocities(std::span<ImplicitBody* const> bodies, std::span<Supports* const> supports,
                             std::span<MovingSupport> moving, NodeArrays& nodes, const Vec3& gravity, double timeStep,
                             ImplicitSolveScratch& scratch);

// h D + h² (−K) at the current state, as node-pair blocks (global indices), for a direct block;
// the elements' rotations are the solve's (the nodes have not moved since).
void addImplicitStiffness(const ImplicitBody& body, const NodeArrays& nodes, double timeStep,
                          std::vector<NodePairStiffness>& out);


}  // namespace tandem
