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
// A model that solves its velocities implicitly holds a node on a still surface along it too, at
// the surface's velocity there, while the hold's impulse stays within the friction cone,
// |c − (c·n) n| ≤ μ c·n, and else lets it slide pushed by the cone's edge
// (models/implicit_solve.h): friction in the model's own metric. What c spends of its cone along
// the surface, its contact's row does not spend again.
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

// Slower than this along its surface at the end of a step, a supported node counts as still.
constexpr double kStillAlongSupport = 1e-3;  // m/s

struct Supports {
  int32_t firstNode = 0;
  // Per node of the body (local indices): unit normal (zero for none), the gap left at the end of
  // last step, the surface's normal velocity and its rigid body.
  std::vector<Vec3> normal;
  std::vector<double> gap, speed;
  std::vector<int32_t> body;
  // Friction held by the model (still surfaces only; zero μ for none): the contact's μ, the
  // surface's velocity along itself at the node, and the friction impulse a node that ended last
  // step sliding starts this one with (zero for one that starts stuck; see addFriction).
  std::vector<double> friction;
  std::vector<Vec3> slideVelocity, slideFriction;
  // A dynamic body among them (a plate on a jelly) moves with the model's solve
  // (models/implicit_solve.h): per node whether its surface does, and the contact point's offset
  // from that body's centre of mass.
  std::vector<char> moves;
  std::vector<Vec3> offset;
  // This step's holds: the impulse each support gave its node (N·s), that support's body, and
  // whether the node slid on it (its friction at the cone's edge).
  std::vector<Vec3> holdImpulse;
  std::vector<int32_t> holdBody;
  std::vector<char> holdSlid;

  void reset(int32_t first, int32_t count) {
    firstNode = first;
    normal.assign(count, Vec3::Zero());
    gap.assign(count, 0.0);
    speed.assign(count, 0.0);
    body.assign(count, -1);
    friction.assign(count, 0.0);
    slideVelocity.assign(count, Vec3::Zero());
    slideFriction.assign(count, Vec3::Zero());
    moves.assign(count, 0);
    offset.assign(count, Vec3::Zero());
  }
  void clearHolds() {
    holdImpulse.assign(normal.size(), Vec3::Zero());
    holdBody.assign(normal.size(), -1);
    holdSlid.assign(normal.size(), 0);
  }
  void recordHold(size_t i, double impulse) { recordHold(i, Vec3(impulse * normal[i])); }
  void recordHold(size_t i, const Vec3& impulse, bool slid = false) {
    holdImpulse[i] = impulse;
    holdBody[i] = body[i];
    holdSlid[i] = slid;
  }
  // A surface by node `node` (global index); the nearest one wins. Whether the node took it.
  bool add(int32_t node, int32_t rigidBody, const Vec3& n, double gapAtEnd, double normalSpeed) {
    const auto i = static_cast<size_t>(node - firstNode);
    if (node < firstNode || i >= normal.size() || (!normal[i].isZero() && gap[i] <= gapAtEnd)) return false;
    normal[i] = n;
    gap[i] = gapAtEnd;
    speed[i] = normalSpeed;
    body[i] = rigidBody;
    friction[i] = 0.0;
    slideVelocity[i].setZero();
    slideFriction[i].setZero();
    moves[i] = 0;
    return true;
  }
  // The friction μ of the still surface the node just took (`add`), the surface's velocity along
  // itself there, and how the node ended last step on it: its slip along it, the normal impulse
  // the surface gave it, its hold's friction impulse (zero for none) and whether that slid. A
  // node that slipped, or whose hold slid, starts this step sliding.
  void addFriction(int32_t node, double mu, const Vec3& alongSurface, const Vec3& slip, double push,
                   const Vec3& holdFriction, bool slid) {
    const auto i = static_cast<size_t>(node - firstNode);
    friction[i] = mu;
    slideVelocity[i] = alongSurface;
    const double pushed = mu * std::max(push, 0.0);
    if (slip.norm() > kStillAlongSupport)
      slideFriction[i] = -pushed * slip.normalized();
    else if (slid && !holdFriction.isZero())
      slideFriction[i] = (pushed / holdFriction.norm()) * holdFriction;
    else
      slideFriction[i].setZero();
  }
  // A dynamic body's surface, moving with the solve, at `fromCentre` from its centre of mass.
  void addMoving(int32_t node, int32_t rigidBody, const Vec3& n, double gapAtEnd, double normalSpeed,
                 const Vec3& fromCentre) {
    const auto i = static_cast<size_t>(node - firstNode);
    if (!add(node, rigidBody, n, gapAtEnd, normalSpeed)) return;
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
