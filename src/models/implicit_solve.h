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
// gradients, matrix-free, warm-started from last step's Δv, with pinned nodes held at Δv = 0.
//
// Supported nodes (models/supports.h) are held along their surface's normal at the normal
// velocity the contact will give them, by filtered conjugate gradients (Baraff and Witkin 1998):
// Δv·n is prescribed, the rest solved. The hold's impulse is c = (A Δv − b)·n; a hold that
// would pull (c < 0) is let go and the solve repeated, so bodies still lift off. Without the
// holds a resting jelly stays 12 % squashed, and a dropped one, whose upper layers fall on
// through the impact step with nothing resisting, is launched higher than it fell.
//
// The same h D + h² K goes to the body's direct block (addImplicitStiffness), so that impulses
// from contacts and attachments move the body as this step would.
#pragma once

#include "models/corotational_fem.h"
#include "models/mass_spring.h"
#include "models/supports.h"

#include <vector>

namespace tandem {

struct ImplicitBody {
  int32_t firstNode = 0;
  int32_t nodeCount = 0;
  FemElements fem;                  // none for a mass-spring body
  std::vector<EdgeSpring> springs;  // global indices
  std::vector<Vec3> previousStep;   // last step's Δv, the solve's starting guess (local indices)
  std::vector<Mat3> rotations;      // of each element at this step's positions, from the solve
  // Per node (local): a third of the trace of its diagonal block of −K from the elements (a
  // rotation leaves it unchanged), for the solve's Jacobi preconditioner; made at the first solve.
  std::vector<double> stiffnessDiagonal;
  int lastIterations = 0;  // conjugate-gradient iterations of the last step
};

ImplicitBody makeImplicitBody(int32_t firstNode, int32_t nodeCount, FemElements fem, std::vector<EdgeSpring> springs);

// A spring's stiffness block k (n nᵀ + max(0, 1 − L/l) (I − n nᵀ)) and its damper's c n nᵀ.
struct SpringBlocks {
  Mat3 stiffness = Mat3::Zero();
  Mat3 damping = Mat3::Zero();
};

// Working memory of solveImplicitVelocities (per node of the body, local), kept by the caller
// between steps so that the solve allocates nothing once grown.
struct ImplicitSolveScratch {
  std::vector<Vec3> velocity, force, product, b, stiffnessTimesVelocity, held, r, z, p, ap;
  std::vector<double> preconditioner, heldChange;
  std::vector<EdgeSpring> springs;  // the body's, local indices
  std::vector<SpringBlocks> springBlocks;
};

// v ← v + Δv for the body's free nodes; gravity and the forces already in `nodes.force` are
// its external forces, taken explicitly. Writes the holds' impulses to `supports`.
void solveImplicitVelocities(ImplicitBody& body, Supports& supports, NodeArrays& nodes, const Vec3& gravity,
                             double timeStep, ImplicitSolveScratch& scratch);

// h D + h² (−K) at the current state, as node-pair blocks (global indices), for a direct block;
// the elements' rotations are the solve's (the nodes have not moved since).
void addImplicitStiffness(const ImplicitBody& body, const NodeArrays& nodes, double timeStep,
                          std::vector<NodePairStiffness>& out);


}  // namespace tandem
