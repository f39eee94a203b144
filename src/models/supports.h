// Surfaces a deformable's nodes rest on: the bodies they touched or were about to touch last
// step, kept for the models stage of the next.
//
// The models stage runs before the coupling solver sees this step's contacts. A model that
// ignores them relieves a resting body's stress into the ground (an implicit FEM jelly rests
// 12 % squashed, a shape-matched one 22 %: the contacts stop only the bottom layer, after the
// model has moved the rest). So each model holds its supported nodes itself: along the
// surface's normal n a node gets the normal velocity the contact will give it, the surface's
// w·n less the gap to close in this step,
//   v*·n = w·n − max(gap, 0) / h,    held only if its free motion would go further.
// The support carries the hold's impulse c: it is kept per node (holdImpulse), reported as
// part of the node's contact with that surface and of the surface's impulse from deformables,
// and it bounds that contact's friction with the contact's own λₙ (constraints/contact.h).
//
// Moving supports. A dynamic body resting on an implicit (FEM, mass-spring) body is a surface
// that moves with the model's solve: its normal velocity at each held node is its own unknown,
//   v*·n = (w + Δw + (ω + Δω) × r)·n − max(gap, 0) / h,
// and the body (its whole mass and inertia, with gravity and what the rest of the world gave it
// over the last step) is solved together with the nodes (models/implicit_solve.h); the hold's
// impulse c on a node is −c on the body at r, so momentum is kept. Why: the contact rows see
// only the nodes' own masses, and the elastic forces act in the next step's model stage, so a
// body resting on a light jelly could be given at most m_nodes · (squash) / h per step: a 2 kg
// plate on a 0.5 kg jelly sank 15 mm into it in 3 s (its elastic answer is 3.1 mm), and a 1 kg
// bar across four 0.5 kg jellies went down to the plate under them. Held this way the jelly
// carries the plate with its whole stiffness in the step it is loaded. A body held by several
// implicit bodies (a bar on two jellies) is solved with all of them at once: solved apart, each
// with a share of the bar's mass and inertia by last step's load, they disagreed about its
// rotation and spun it up (0.7 rad/s within 2 steps, 80 in 35). The body's other supports
// (contacts with other bodies, deformables whose models are not implicit) act in the sweep as
// before. A node is held on a dynamic body that pressed on it last step (λₙ + c > 0), if the
// body is awake and not jointed to the world, and the node is not in a direct block (whose solve
// couples it already).
#pragma once

#include <tandem/types.h>

#include <algorithm>
#include <cstdint>
#include <span>
#include <vector>

namespace tandem {

struct Supports {
  int32_t firstNode = 0;
  // Per node of the body (local indices): unit normal (zero for none), the gap left at the end of
  // last step, the surface's normal velocity and its rigid body.
  std::vector<Vec3> normal;
  std::vector<double> gap, speed;
  std::vector<int32_t> body;
  // A dynamic body among them (a plate on a jelly) moves with the model's solve
  // (models/implicit_solve.h): per node whether its surface does, and the contact point's offset
  // from that body's centre of mass.
  std::vector<char> moves;
  std::vector<Vec3> offset;
  // This step's holds: the impulse each support gave its node (N·s), and that support's body.
  std::vector<Vec3> holdImpulse;
  std::vector<int32_t> holdBody;

  void reset(int32_t first, int32_t count) {
    firstNode = first;
    normal.assign(count, Vec3::Zero());
    gap.assign(count, 0.0);
    speed.assign(count, 0.0);
    body.assign(count, -1);
    moves.assign(count, 0);
    offset.assign(count, Vec3::Zero());
  }
  void clearHolds() {
    holdImpulse.assign(normal.size(), Vec3::Zero());
    holdBody.assign(normal.size(), -1);
  }
  void recordHold(size_t i, double impulse) {
    holdImpulse[i] = impulse * normal[i];
    holdBody[i] = body[i];
  }
  // A surface by node `node` (global index); the nearest one wins.
  void add(int32_t node, int32_t rigidBody, const Vec3& n, double gapAtEnd, double normalSpeed) {
    const auto i = static_cast<size_t>(node - firstNode);
    if (node < firstNode || i >= normal.size() || (!normal[i].isZero() && gap[i] <= gapAtEnd)) return;
    normal[i] = n;
    gap[i] = gapAtEnd;
    speed[i] = normalSpeed;
    body[i] = rigidBody;
    moves[i] = 0;
  }
  // A dynamic body's surface, moving with the solve, at `fromCentre` from its centre of mass.
  void addMoving(int32_t node, int32_t rigidBody, const Vec3& n, double gapAtEnd, double normalSpeed,
                 const Vec3& fromCentre) {
    const auto i = static_cast<size_t>(node - firstNode);
    if (node < firstNode || i >= normal.size() || (!normal[i].isZero() && gap[i] <= gapAtEnd)) return;
    add(node, rigidBody, n, gapAtEnd, normalSpeed);
    moves[i] = 1;
    offset[i] = fromCentre;
  }
  // The normal velocity a held node gets this step.
  double targetSpeed(size_t i, double timeStep) const { return speed[i] - std::max(gap[i], 0.0) / timeStep; }

  // For models that take v* as it is (shape matching; PBD projects its supports as planes
  // among its constraints, models/position_based.h): raises each
  // supported node's normal velocity to its target, recording the impulse. `velocity` and
  // `inverseMass` are the body's.
  void hold(std::span<Vec3> velocity, std::span<const double> inverseMass, double timeStep) {
    clearHolds();
    for (size_t i = 0; i < normal.size(); ++i) {
      if (normal[i].isZero() || moves[i] || inverseMass[i] == 0.0) continue;
      const double missing = targetSpeed(i, timeStep) - normal[i].dot(velocity[i]);
      if (missing <= 0) continue;
      velocity[i] += missing * normal[i];
      recordHold(i, missing / inverseMass[i]);
    }
  }
};

}  // namespace tandem
