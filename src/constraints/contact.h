// Contact: non-penetration and Coulomb friction at a point of a deformable surface, against a
// rigid body or another deformable surface (or the same one, away from itself).
//
// Derivation (paper §4.3–4.4, exact linearisation). The contact point on side A is
// p_A = Σ wₖ xₖ over its nodes (a node, or a point of a face with barycentric weights); on
// side B it is a point fixed in a rigid body, p_B = c + R r, or Σ uₖ xₖ over the other
// surface's nodes. For a node against a shape, r is where the node's centre rests when
// touching (the surface moved out by the thickness), so friction holds the node to that
// point's velocity: a rope of thickness t rolls on a wheel at (r + t) ω, as its centre line
// does. (Along n this changes nothing: (r + t n) × n = r × n.) n is the unit normal pointing
// from B to A; g the gap at the start of the substep (found at the step's start and moved on by
// both sides' motion since; a node against a shape is measured again) minus both sides'
// thickness. Writing every node entry with a signed coefficient cₖ
// (+wₖ on side A, −uₖ on side B):
//
//   C  = n · (p_A − p_B) − thickness ≥ 0
//   Ċ  = n · (Σ cₖ vₖ − v_b − ω × r)
//   J  = [ c₁nᵀ … c₄nᵀ | −nᵀ | −(r × n)ᵀ ]     (nodes | rigid linear | rigid angular)
//   K  = J M⁻¹ Jᵀ = Σ cₖ² mₖ⁻¹ + m_b⁻¹ + (r × n)ᵀ I_b⁻¹ (r × n)
//
// No dummy node and no averaging: the face's three vertices enter with their barycentric
// weights, so the row's effective mass is exact and several contacts on one face or body add
// up correctly by construction.
//
// Bias (speculative contacts): a contact found with g > 0 lets the surfaces close the gap in
// this step but not pass, bias = g / h; one found penetrating pushes out beyond a slop,
// bias = β min(g + slop, 0). The normal impulse is one-sided, λₙ ≥ 0.
//
// Friction: two tangent rows on t₁, t₂ ⟂ n, solved as one 2×2 block on the tangential
// relative velocity (t₁ along it when it is not tiny, as in the paper's eq. 27–28), with the
// accumulated tangential impulse clamped to a disc (an isotropic cone):
//   Coulomb (default):  |λₜ| ≤ μ (λₙ + s)     — right for any contact, whatever pushes it
//   pressure (paper):   |λₜ| ≤ μ m |g · n| h  — the paper's eq. 32, m the contact's mass
// μ is the product of the two sides' friction coefficients, as in Bullet. s is the normal
// impulse the node's model already took from this surface in the substep (its support hold,
// models/supports.h): a jelly's models hold its resting nodes on the ground themselves, so the
// contact rows carry almost none of its weight, and bounded by λₙ alone the friction of a jelly
// on a 15° slope was nil (it slid at g sin θ); with s the surface's whole push bounds it.
//
// The impulse is a vector P = λₙ n + λₜ on side A: node k gets cₖ mₖ⁻¹ P, the rigid body −P
// at r. Equal and opposite by construction.
#pragma once

#include <tandem/world.h>  // FrictionModel

#include "solver/solver_state.h"

#include <Eigen/LU>

#include <array>
#include <cstdint>

namespace tandem {

struct ContactRow {
  // From collision detection
  std::array<int32_t, 4> node{};           // unused entries have coefficient 0 and repeat node[0]
  std::array<double, 4> coefficient{};     // +w on side A, −u on side B
  int32_t body = -1;                       // rigid body on side B, or −1
  Vec3 offset = Vec3::Zero();              // r: rigid contact point minus centre of mass
  Vec3 normal = Vec3::UnitY();             // from B to A
  double gap = 0.0;                        // m, start of the substep, thickness already taken off
  double startGap = 0.0;                   // m, as detected at the start of the step
  Vec3 startOffset = Vec3::Zero();         // r at the start of the step
  double friction = 0.0;                   // combined μ
  double contactMass = 0.0;                // kg, for the pressure friction model
  uint64_t key = 0;                        // feature, for warm starting across steps
  Vec3 warmFriction = Vec3::Zero();        // last step's friction impulse on this feature
  // Per step
  Vec3 tangent1 = Vec3::UnitX(), tangent2 = Vec3::UnitZ();
  double normalMass = 0.0;                 // 1 / K
  Eigen::Matrix2d tangentMass = Eigen::Matrix2d::Zero();  // (T K Tᵀ)⁻¹
  double bias = 0.0;
  double pressureBound = 0.0;              // μ m |g·n| h, for the pressure model
  double lambdaNormal = 0.0;               // N·s, ≥ 0
  // The part of the node's normal load its model's support hold already carried in this
  // substep (models/supports.h): the surface pushes with it too, so it bounds friction as λₙ does.
  double supportImpulse = 0.0;
  Eigen::Vector2d lambdaTangent = Eigen::Vector2d::Zero();
  double stepNormalImpulse = 0.0;          // summed over the step's substeps: what is reported
  Vec3 stepFrictionImpulse = Vec3::Zero();
  bool inDirectBlock = false;  // its normal row is solved by a direct block
  bool frictionInBlock = false;  // and its friction too, in the block's metric (solver/direct_block.h)
  bool releasedFromBlock = false;  // a block let it go this step (it would have pulled)
  bool releasedLastStep = false;   // the same feature was let go last step

  Vec3 impulse() const { return lambdaNormal * normal + lambdaTangent[0] * tangent1 + lambdaTangent[1] * tangent2; }
  // A node against a rigid shape (not a face, edge or another body's surface).
  bool isNodeOnRigid() const {
    return body >= 0 && coefficient[0] == 1.0 && coefficient[1] == 0.0 && coefficient[2] == 0.0 && coefficient[3] == 0.0;
  }
};

// (The unused entries, coefficient 0 on node[0] again, are skipped: most contacts are a node on a
// rigid shape, and three updates of the same node's velocity chained each of their impulses.)
inline Vec3 contactRelativeVelocity(const ContactRow& row, const SolverContext& ctx) {
  Vec3 v = Vec3::Zero();
  for (int k = 0; k < 4; ++k)
    if (row.coefficient[k] != 0.0) v += row.coefficient[k] * ctx.velocity[row.node[k]];
  if (row.body >= 0) v -= ctx.rigid[row.body].velocityAt(row.offset);
  return v;
}

// The 3×3 inverse effective mass of the contact point: Δv_rel = K P.
inline Mat3 contactPointCompliance(const ContactRow& row, std::span<const double> inverseMass,
                                   std::span<const RigidSolverState> rigid) {
  double nodes = 0.0;
  for (int k = 0; k < 4; ++k) nodes += row.coefficient[k] * row.coefficient[k] * inverseMass[row.node[k]];
  Mat3 k = nodes * Mat3::Identity();
  if (row.body >= 0) k += rigid[row.body].pointCompliance(row.offset);
  return k;
}

inline void prepareContact(ContactRow& row, std::span<const Vec3> velocity, std::span<const double> inverseMass,
                           std::span<const RigidSolverState> rigid, const Vec3& gravity, double timeStep,
                           double biasRate, double slop) {
  // Tangents: along the tangential relative velocity when it is not tiny, else any pair.
  Vec3 v = Vec3::Zero();
  for (int k = 0; k < 4; ++k) v += row.coefficient[k] * velocity[row.node[k]];
  if (row.body >= 0) v -= rigid[row.body].velocityAt(row.offset);
  const Vec3 tangential = v - v.dot(row.normal) * row.normal;
  if (tangential.norm() > 1e-6)
    row.tangent1 = tangential.normalized();
  else
    row.tangent1 = (std::abs(row.normal.x()) < 0.9 ? Vec3::UnitX() : Vec3::UnitY()).cross(row.normal).normalized();
  row.tangent2 = row.normal.cross(row.tangent1);
  row.lambdaTangent = {row.warmFriction.dot(row.tangent1), row.warmFriction.dot(row.tangent2)};

  const Mat3 k = contactPointCompliance(row, inverseMass, rigid);
  const double normal = row.normal.dot(k * row.normal);
  row.normalMass = normal > 1e-12 ? 1.0 / normal : 0.0;
  Eigen::Matrix<double, 3, 2> basis;
  basis << row.tangent1, row.tangent2;
  const Eigen::Matrix2d tangent = basis.transpose() * k * basis;
  row.tangentMass = tangent.determinant() > 1e-18 ? Eigen::Matrix2d(tangent.inverse()) : Eigen::Matrix2d::Zero();
  // Speculative only: penetration is pushed out by position (see pushOutOfContacts), not by a
  // velocity that would make a resting node bounce.
  (void)biasRate;
  (void)slop;
  row.bias = row.gap > 0 ? row.gap / timeStep : 0.0;
  row.pressureBound = row.friction * row.contactMass * std::abs(gravity.dot(row.normal)) * timeStep;
}

inline void applyContactImpulse(const ContactRow& row, const Vec3& impulse, SolverContext& ctx) {
  for (int k = 0; k < 4; ++k)
    if (row.coefficient[k] != 0.0) ctx.velocity[row.node[k]] += (row.coefficient[k] * ctx.inverseMass[row.node[k]]) * impulse;
  if (row.body >= 0) ctx.rigid[row.body].applyImpulse(-impulse, row.offset);
}

inline void warmStartContact(const ContactRow& row, SolverContext& ctx) { applyContactImpulse(row, row.impulse(), ctx); }

inline void solveContactNormal(ContactRow& row, SolverContext& ctx, SweepStats& stats) {
  if (row.normalMass == 0.0) return;
  const double velocity = row.normal.dot(contactRelativeVelocity(row, ctx));
  const double previous = row.lambdaNormal;
  row.lambdaNormal = std::max(0.0, previous - row.normalMass * (velocity + row.bias));
  const double delta = row.lambdaNormal - previous;
  applyContactImpulse(row, delta * row.normal, ctx);
  stats.add(delta);
}

// The accumulated tangential impulse that stops the sliding, Δλ = −W⁻¹ vₜ for the 2×2
// `tangentMass` W⁻¹ (the point's own, or a direct block's), clamped to the friction disc.
inline Eigen::Vector2d frictionImpulse(const ContactRow& row, FrictionModel model, const Eigen::Matrix2d& tangentMass,
                                       const SolverContext& ctx) {
  const Vec3 v = contactRelativeVelocity(row, ctx);
  const Eigen::Vector2d tangential(v.dot(row.tangent1), v.dot(row.tangent2));
  Eigen::Vector2d lambda = row.lambdaTangent - tangentMass * tangential;
  const double bound =
      model == FrictionModel::Coulomb ? row.friction * (row.lambdaNormal + row.supportImpulse) : row.pressureBound;
  if (lambda.norm() > bound) lambda *= bound / lambda.norm();
  return lambda;
}

inline void solveContactFriction(ContactRow& row, FrictionModel model, SolverContext& ctx, SweepStats& stats) {
  if (row.friction == 0.0 || row.tangentMass.isZero()) return;
  const Eigen::Vector2d previous = row.lambdaTangent;
  row.lambdaTangent = frictionImpulse(row, model, row.tangentMass, ctx);
  const Eigen::Vector2d delta = row.lambdaTangent - previous;
  applyContactImpulse(row, delta[0] * row.tangent1 + delta[1] * row.tangent2, ctx);
  stats.add(delta[0]);
  stats.add(delta[1]);
}

}  // namespace tandem
