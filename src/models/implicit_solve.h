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
// The coupling solver's contacts come after this solve, which left to itself relieves a resting
// body's stress by driving its bottom nodes into the ground (at 1 m/s per step for a 0.2 m
// jelly; the contacts stop them, the stress stays, the jelly rests 12 % squashed), and at an
// impact lets the upper layers fall on through a step with nothing resisting (the energy they
// store launches the jelly higher than it fell). So the solve holds nodes on the static and
// kinematic surfaces they touched or were about to touch last step: along the surface normal n
// a held node gets the normal velocity the contact will give it, the surface's w·n less the gap
// closed in this step,
//   v*·n = w·n − max(gap, 0) / h,    held only if the free motion would go further,
// by filtered conjugate gradients (Baraff and Witkin 1998). The hold's impulse is
// c = (A Δv − b)·n; a hold that would pull (c < 0) is let go and the solve repeated, so bodies
// still lift off. The support carries c: it is kept per node (holdImpulse) and reported as part
// of the node's contact with that surface and of the surface's impulse from deformables.
//
// The same h D + h² K goes to the body's direct block (addImplicitStiffness), so that impulses
// from contacts and attachments move the body as this step would.
#pragma once

#include "models/corotational_fem.h"
#include "models/mass_spring.h"

#include <vector>

namespace tandem {

struct ImplicitBody {
  int32_t firstNode = 0;
  int32_t nodeCount = 0;
  FemElements fem;                  // none for a mass-spring body
  std::vector<EdgeSpring> springs;  // global indices
  std::vector<Vec3> previousStep;   // last step's Δv, the solve's starting guess (local indices)
  // Surfaces the nodes touched or neared last step (local indices): normal (zero for none), the
  // gap at the step's end, and the surface's normal velocity.
  std::vector<Vec3> supportNormal;
  std::vector<double> supportGap, supportSpeed;
  std::vector<int32_t> supportBody;  // the rigid body of each support
  std::vector<double> holdImpulse;   // this step's c per node (N·s along its support's normal), 0 if not held
  int lastIterations = 0;  // conjugate-gradient iterations of the last step
};

ImplicitBody makeImplicitBody(int32_t firstNode, int32_t nodeCount, FemElements fem, std::vector<EdgeSpring> springs);

// v ← v + Δv for the body's free nodes; gravity and the forces already in `nodes.force` are
// its external forces, taken explicitly.
void solveImplicitVelocities(ImplicitBody& body, NodeArrays& nodes, const Vec3& gravity, double timeStep);

// h D + h² (−K) at the current state, as node-pair blocks (global indices), for a direct block.
void addImplicitStiffness(const ImplicitBody& body, const NodeArrays& nodes, double timeStep,
                          std::vector<NodePairStiffness>& out);

// Records a static or kinematic surface by a node (global index) for the next solve: its normal,
// the gap at the step's end and its normal velocity. The caller clears the supports each step.
void addSupport(ImplicitBody& body, int32_t node, int32_t rigidBody, const Vec3& normal, double gap, double normalSpeed);
void clearSupports(ImplicitBody& body);

}  // namespace tandem
