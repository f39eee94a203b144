#include "models/implicit_solve.h"

#include <algorithm>

namespace tandem {
namespace {

constexpr int kMaxIterations = 100;
// ‖b − A Δv‖ ≤ 1e-4 ‖b‖: on the paper's jellies a velocity error of the order of 1e-5 m/s, far
// below what the contacts and the block change; 1e-6 took 94 iterations on average against 42
// and doubled the jelly scene's model stage (12.5 → 6.5 ms per step).
constexpr double kRelativeTolerance = 1e-4;
// Holds let go and solves started again, at most (models/supports.h); the residual at which a
// solve first looks for moving supports' holds that pull. The bar landing on jelly_dish's jellies
// lets several go at once: looked for only once converged, 6 of its 8 landing steps ended at 100
// iterations short of the tolerance; looked for early, they converge in 61–93. (Still supports'
// holds are judged converged only: let go early, on a tenth of the residual, they let a glued
// jelly's box creep down a 20° slope at 4 cm/s.)
constexpr int kMaxRounds = 4;
constexpr double kEarlyCheckTolerance = 1e-1;
// A sliding node's push is solved again when its c·n has changed it by more than this fraction.
constexpr double kSlidingPushTolerance = 0.05;

SpringBlocks springBlocks(const EdgeSpring& spring, std::span<const Vec3> position) {
  const Vec3 d = position[spring.nodeB] - position[spring.nodeA];
  const double length = d.norm();
  if (length < 1e-12) return {};
  const Vec3 n = d / length;
  const Mat3 along = n * n.transpose();
  const double sideways = std::max(0.0, 1.0 - spring.restLength / length);
  return {spring.stiffness * (along + sideways * (Mat3::Identity() - along)), spring.damping * along};
}

}  // namespace

ImplicitBody makeImplicitBody(int32_t firstNode, int32_t nodeCount, FemElements fem, std::vector<EdgeSpring> springs) {
  ImplicitBody body;
  body.firstNode = firstNode;
  body.nodeCount = nodeCount;
  body.fem = std::move(fem);
  body.springs = std::move(springs);
  body.previousStep.assign(nodeCount, Vec3::Zero());
  body.rotations.assign(body.fem.tetrahedra.size(), Mat3::Identity());
  return body;
}

void solveImplicitVelocities(std::span<ImplicitBody* const> bodies, std::span<Supports* const> supports,
                             std::span<MovingSupport> moving, NodeArrays& nodes, const Vec3& gravity, double h,
                             ImplicitSolveScratch& work) {
  // The bodies' nodes one after another: node i of body k at sliceStart[k] + i.
  std::vector<int32_t>& sliceStart = work.sliceStart;
  sliceStart.clear();
  int32_t count = 0;
  for (const ImplicitBody* body : bodies) {
    sliceStart.push_back(count);
    count += body->nodeCount;
  }
  // Per node in the solve's order: mass (0 for a pinned node), velocity and position.
  std::vector<double>& mass = work.mass;
  std::vector<Vec3>& velocity = work.velocity;
  std::vector<Vec3>& position = work.position;
  mass.resize(count);
  velocity.resize(count);
  position.resize(count);
  for (size_t k = 0; k < bodies.size(); ++k)
    for (int32_t i = 0; i < bodies[k]->nodeCount; ++i) {
      const int32_t node = bodies[k]->firstNode + i, g = sliceStart[k] + i;
      const bool free = nodes.inverseMass[node] > 0;
      mass[g] = free ? 1.0 / nodes.inverseMass[node] : 0.0;
      velocity[g] = free ? nodes.velocity[node] : Vec3::Zero();
      position[g] = nodes.position[node];
    }

  // Forces at (x, v): the elements' (with their rotations, which K keeps) and the springs'.
  std::vector<Vec3>& force = work.force;
  force.assign(count, Vec3::Zero());
  std::vector<EdgeSpring>& springs = work.springs;  // in the solve's indices
  std::vector<SpringBlocks>& blocks = work.springBlocks;
  springs.clear();
  blocks.clear();
  for (size_t k = 0; k < bodies.size(); ++k) {
    ImplicitBody& body = *bodies[k];
    body.rotations.resize(body.fem.tetrahedra.size(), Mat3::Identity());
    addFemForces(body.fem, std::span<const Vec3>(position.data() + sliceStart[k], body.nodeCount),
                 std::span<Vec3>(force.data() + sliceStart[k], body.nodeCount), body.firstNode, body.rotations);
    for (EdgeSpring spring : body.springs) {
      spring.nodeA += sliceStart[k] - body.firstNode;
      spring.nodeB += sliceStart[k] - body.firstNode;
      springs.push_back(spring);
    }
  }
  std::vector<Mat3>& dampedBlocks = work.dampedSpringBlocks;  // h² K_s + h D_s, per spring
  dampedBlocks.clear();
  for (const EdgeSpring& spring : springs) {
    blocks.push_back(springBlocks(spring, position));
    dampedBlocks.push_back(h * h * blocks.back().stiffness + h * blocks.back().damping);
  }
  addSpringForces(springs, position, velocity, force);

  // The elements' −K by node pair, with this step's rotations.
  for (ImplicitBody* body : bodies) {
    std::vector<NodePairStiffness>& pairs = body->stiffnessBlocks;
    pairs.clear();
    addFemStiffnessBlocks(body->fem, body->rotations, 1.0, pairs);  // each pair once (a ≤ b): −K is symmetric
  }
  // −K y (stiffness only) or −(h D + h² K) y (`damped`).
  auto negativeStiffness = [&](const std::vector<Vec3>& y, std::vector<Vec3>& out, bool damped) {
    out.assign(count, Vec3::Zero());
    for (size_t k = 0; k < bodies.size(); ++k) {
      const int32_t shift = sliceStart[k] - bodies[k]->firstNode;
      for (const NodePairStiffness& pair : bodies[k]->stiffnessBlocks) {
        out[pair.nodeA + shift] += pair.k * y[pair.nodeB + shift];
        if (pair.nodeA != pair.nodeB) out[pair.nodeB + shift] += pair.k.transpose() * y[pair.nodeA + shift];
      }
    }
    if (damped)
      for (Vec3& o : out) o *= h * h;
    for (size_t s = 0; s < springs.size(); ++s) {
      const Mat3& block = damped ? dampedBlocks[s] : blocks[s].stiffness;
      const Vec3 stretch = block * (y[springs[s].nodeB] - y[springs[s].nodeA]);
      out[springs[s].nodeB] += stretch;
      out[springs[s].nodeA] -= stretch;
    }
  };
  // A y = (M − h D − h² K) y, with pinned nodes held at zero.
  std::vector<Vec3>& scratch = work.product;
  auto apply = [&](const std::vector<Vec3>& y, std::vector<Vec3>& out) {
    negativeStiffness(y, scratch, true);
    out.resize(count);
    for (int32_t i = 0; i < count; ++i) out[i] = mass[i] > 0 ? Vec3(mass[i] * y[i] + scratch[i]) : Vec3::Zero();
  };

  // b = h (f + f_ext + m g) + h² K v
  std::vector<Vec3>& b = work.b;
  std::vector<Vec3>& kv = work.stiffnessTimesVelocity;
  b.resize(count);
  negativeStiffness(velocity, kv, false);
  for (size_t k = 0; k < bodies.size(); ++k)
    for (int32_t i = 0; i < bodies[k]->nodeCount; ++i) {
      const int32_t g = sliceStart[k] + i;
      b[g] = mass[g] > 0 ? Vec3(h * (force[g] + nodes.force[bodies[k]->firstNode + i] + mass[g] * gravity) - h * h * kv[g])
                         : Vec3::Zero();
    }

  // Block-Jacobi preconditioner: per node, its 3 × 3 diagonal block of A, P_i = m I + h² (−K_ii) +
  // h² K_s + h D_s (elements' and springs' blocks), inverted; the supports' blocks below take
  // their held nodes' scalar tr(P_i)/3. With the scalar per node for both (before the
  // twenty-sixth session) jelly_dish took 9,437 iterations in 500 steps (182 at most, 14.3 a step
  // at rest); with the blocks 8,233 (170, 12.4).
  std::vector<double>& preconditioner = work.preconditioner;
  std::vector<Mat3>& nodePreconditioner = work.nodePreconditioner;
  nodePreconditioner.assign(count, Mat3::Zero());
  for (int32_t i = 0; i < count; ++i) nodePreconditioner[i].diagonal().setConstant(mass[i]);
  for (size_t k = 0; k < bodies.size(); ++k) {
    const int32_t shift = sliceStart[k] - bodies[k]->firstNode;
    for (const NodePairStiffness& pair : bodies[k]->stiffnessBlocks)
      if (pair.nodeA == pair.nodeB) nodePreconditioner[pair.nodeA + shift] += h * h * pair.k;
  }
  for (size_t s = 0; s < springs.size(); ++s)
    for (int32_t node : {springs[s].nodeA, springs[s].nodeB}) nodePreconditioner[node] += dampedBlocks[s];
  preconditioner.resize(count);
  for (int32_t i = 0; i < count; ++i) {
    preconditioner[i] = mass[i] > 0 ? nodePreconditioner[i].trace() / 3.0 : 0.0;
    nodePreconditioner[i] = mass[i] > 0 ? Mat3(nodePreconditioner[i].inverse()) : Mat3::Zero();
  }

  // Held nodes, and the normal Δv each must take (see the header); a node on a moving support
  // takes its support's normal motion on top, which the solve finds with the nodes'.
  std::vector<Vec3>& held = work.held;
  std::vector<double>& heldChange = work.heldChange;
  std::vector<Vec3>& offset = work.offset;
  offset.assign(count, Vec3::Zero());
  std::vector<int32_t>& movingOf = work.movingOf;
  std::vector<double>& friction = work.friction;
  std::vector<Vec3>& stuckChange = work.stuckChange;
  std::vector<Vec3>& slidingPush = work.slidingPush;
  std::vector<char>& stuck = work.stuck;
  std::vector<char>& restuck = work.restuck;
  held.assign(count, Vec3::Zero());
  heldChange.assign(count, 0.0);
  movingOf.assign(count, -1);
  friction.assign(count, 0.0);
  stuckChange.assign(count, Vec3::Zero());
  slidingPush.assign(count, Vec3::Zero());
  stuck.assign(count, 0);
  restuck.assign(count, 0);
  for (size_t k = 0; k < bodies.size(); ++k) {
    const Supports& support = *supports[k];
    for (int32_t i = 0; i < bodies[k]->nodeCount; ++i) {
      const int32_t g = sliceStart[k] + i;
      const Vec3& n = support.normal[i];
      if (n.isZero() || mass[g] == 0.0) continue;
      const double target = support.targetSpeed(i, h);
      if (support.moves[i]) {
        for (size_t m = 0; m < moving.size(); ++m)
          if (moving[m].body == support.body[i]) movingOf[g] = static_cast<int32_t>(m);
        if (movingOf[g] < 0) continue;
        offset[g] = support.offset[i];
      } else if (n.dot(velocity[g] + h * gravity) >= target) {
        continue;
      }
      held[g] = n;
      heldChange[g] = target - n.dot(velocity[g]);
      friction[g] = support.friction[i];  // still supports only (models/supports.h)
      if (friction[g] == 0.0) continue;
      stuckChange[g] = target * n + support.slideVelocity[i] - velocity[g];
      slidingPush[g] = support.slideFriction[i];  // sliding since last step: pushed against the slip
      b[g] += slidingPush[g];
      stuck[g] = slidingPush[g].isZero();
    }
  }

  // Filtered conjugate gradients (Baraff and Witkin 1998), block-Jacobi-preconditioned, from last
  // step's Δv: S takes out the held normal components, and the whole of a stuck node's; a moving
  // support's motion (V, Ω) comes back in through them, n (n · (V + Ω × r)) at each of its held
  // nodes, and its mass and inertia are its own part of the system, with its gravity and the
  // impulse the rest of the world gives it.
  const auto supportCount = static_cast<int32_t>(moving.size());
  auto filter = [&](std::vector<Vec3>& y) {
    for (int32_t i = 0; i < count; ++i) y[i] = stuck[i] ? Vec3::Zero() : Vec3(y[i] - held[i].dot(y[i]) * held[i]);
  };
  auto movesWith = [&](int32_t i) { return held[i].isZero() ? -1 : movingOf[i]; };
  std::vector<Vec3>& full = work.full;
  auto expand = [&](const std::vector<Vec3>& y, const std::vector<Vec3>& Y) {  // Y: V then Ω per support
    full = y;
    for (int32_t i = 0; i < count; ++i)
      if (const int32_t m = movesWith(i); m >= 0)
        full[i] += held[i].dot(Y[2 * m] + Y[2 * m + 1].cross(offset[i])) * held[i];
  };
  auto gather = [&](const std::vector<Vec3>& g, std::vector<Vec3>& out) {
    out.assign(2 * supportCount, Vec3::Zero());
    for (int32_t i = 0; i < count; ++i)
      if (const int32_t m = movesWith(i); m >= 0) {
        const Vec3 along = held[i].dot(g[i]) * held[i];
        out[2 * m] += along;
        out[2 * m + 1] += offset[i].cross(along);
      }
  };
  auto addSupportInertia = [&](const std::vector<Vec3>& Y, double scale, std::vector<Vec3>& out) {
    for (int32_t m = 0; m < supportCount; ++m) {
      out[2 * m] += scale * moving[m].mass * Y[2 * m];
      out[2 * m + 1] += scale * (moving[m].inertia * Y[2 * m + 1]);
    }
  };
  std::vector<Vec3>& x = work.x;
  x.resize(count);
  for (size_t k = 0; k < bodies.size(); ++k)
    std::copy_n(bodies[k]->previousStep.begin(), bodies[k]->nodeCount, x.begin() + sliceStart[k]);
  for (int32_t i = 0; i < count; ++i)
    if (mass[i] == 0.0) x[i].setZero();
  std::vector<Vec3>& X = work.supportChange;
  X.assign(2 * supportCount, Vec3::Zero());
  std::vector<Vec3>& r = work.r;
  std::vector<Vec3>& z = work.z;
  std::vector<Vec3>& p = work.p;
  std::vector<Vec3>& ap = work.ap;
  std::vector<Vec3>& R = work.supportResidual;
  std::vector<Vec3>& Z = work.supportPreconditioned;
  std::vector<Vec3>& P = work.supportDirection;
  std::vector<Vec3>& AP = work.supportProduct;
  std::vector<Mat3>& supportPreconditioner = work.supportPreconditioner;
  r.resize(count);
  z.resize(count);
  Z.resize(2 * supportCount);
  double bNorm = 0.0;
  for (const Vec3& bi : b) bNorm += bi.squaredNorm();
  for (const MovingSupport& support : moving)
    bNorm += (h * support.mass * gravity + support.otherImpulse).squaredNorm() + support.otherAngularImpulse.squaredNorm();
  auto applyReduced = [&](const std::vector<Vec3>& y, const std::vector<Vec3>& Y, std::vector<Vec3>& out,
                          std::vector<Vec3>& Out) {
    expand(y, Y);
    apply(full, out);
    gather(out, Out);
    addSupportInertia(Y, 1.0, Out);
    filter(out);
  };
  // A sliding node's push, a load in b (zero: none).
  auto setPush = [&](int32_t i, const Vec3& push) {
    b[i] += push - slidingPush[i];
    slidingPush[i] = push;
  };
  auto release = [&](int32_t i) {
    setPush(i, Vec3::Zero());
    held[i].setZero();
    heldChange[i] = 0.0;
    stuck[i] = 0;
  };
  // Let go of moving supports' holds that pull (c = A Δv − b against the normal); whether any
  // did. Leaves A x in ap.
  auto releasePulling = [&]() {
    apply(x, ap);
    bool released = false;
    for (int32_t i = 0; i < count; ++i) {
      if (held[i].isZero() || movingOf[i] < 0 || held[i].dot(ap[i] - b[i]) >= 0) continue;
      release(i);
      released = true;
    }
    return released;
  };
  // After a round (ap = A x): let go of holds that pull; a stuck node whose c left the cone
  // slides, a sliding one's push follows its c·n, one whose push turned its slip back sticks.
  // Whether any changed.
  auto updateHolds = [&]() {
    bool changed = false;
    for (int32_t i = 0; i < count; ++i) {
      if (held[i].isZero()) continue;
      const Vec3 c = ap[i] - b[i];
      const double pushing = held[i].dot(c);
      const Vec3 along = c - pushing * held[i];
      const double mu = friction[i];
      if (pushing < 0) {
        release(i);
        changed = true;
      } else if (stuck[i] && along.norm() > mu * pushing) {
        setPush(i, (mu * pushing / along.norm()) * along);
        stuck[i] = 0;
        changed = true;
      } else if (!slidingPush[i].isZero() && (restuck[i] || slidingPush[i].dot(stuckChange[i] - x[i]) >= 0.0)) {
        const Vec3 push = (mu * pushing / slidingPush[i].norm()) * slidingPush[i];  // still sliding
        if ((push - slidingPush[i]).norm() > kSlidingPushTolerance * slidingPush[i].norm()) {
          setPush(i, push);
          changed = true;
        }
      } else if (!slidingPush[i].isZero()) {  // its push would turn the slip back: it sticks
        setPush(i, Vec3::Zero());
        stuck[i] = 1;
        restuck[i] = 1;
        changed = true;
      }
    }
    return changed;
  };
  int iteration = 0;
  bool converged = false;
  for (int round = 0; round < kMaxRounds; ++round) {
    bool checked = false, restart = false;  // this round's early look at the holds, and what it found
    for (int32_t i = 0; i < count; ++i) {
      const int32_t m = movesWith(i);
      const double normal = heldChange[i] + (m >= 0 ? held[i].dot(X[2 * m] + X[2 * m + 1].cross(offset[i])) : 0.0);
      x[i] = stuck[i] ? stuckChange[i] : Vec3(x[i] + (normal - held[i].dot(x[i])) * held[i]);
    }
    // Each support's block of the preconditioner: its inertia and its held nodes' diagonals.
    supportPreconditioner.assign(2 * supportCount, Mat3::Zero());
    for (int32_t m = 0; m < supportCount; ++m) {
      supportPreconditioner[2 * m] = moving[m].mass * Mat3::Identity();
      supportPreconditioner[2 * m + 1] = moving[m].inertia;
    }
    for (int32_t i = 0; i < count; ++i)
      if (const int32_t m = movesWith(i); m >= 0) {
        const Vec3 turn = offset[i].cross(held[i]);
        supportPreconditioner[2 * m] += preconditioner[i] * held[i] * held[i].transpose();
        supportPreconditioner[2 * m + 1] += preconditioner[i] * turn * turn.transpose();
      }
    for (Mat3& block : supportPreconditioner) block = block.inverse().eval();
    apply(x, ap);
    for (int32_t i = 0; i < count; ++i) r[i] = b[i] - ap[i];
    gather(r, R);
    for (int32_t m = 0; m < supportCount; ++m) {
      R[2 * m] += h * moving[m].mass * gravity + moving[m].otherImpulse;
      R[2 * m + 1] += moving[m].otherAngularImpulse;
    }
    addSupportInertia(X, -1.0, R);
    filter(r);
    auto precondition = [&]() {  // z = S P⁻¹ r, and returns r·z
      double rz = 0.0;
      for (int32_t i = 0; i < count; ++i) z[i] = nodePreconditioner[i] * r[i];
      filter(z);
      for (int32_t i = 0; i < count; ++i) rz += r[i].dot(z[i]);
      for (int32_t j = 0; j < 2 * supportCount; ++j) {
        Z[j] = supportPreconditioner[j] * R[j];
        rz += R[j].dot(Z[j]);
      }
      return rz;
    };
    double rr = 0.0;
    for (const Vec3& ri : r) rr += ri.squaredNorm();
    for (const Vec3& Ri : R) rr += Ri.squaredNorm();
    double rz = precondition();
    p = z;
    P = Z;
    for (int roundIteration = 0; roundIteration < kMaxIterations && rr > kRelativeTolerance * kRelativeTolerance * bNorm;
         ++roundIteration, ++iteration) {
      applyReduced(p, P, ap, AP);
      double pap = 0.0;
      for (int32_t i = 0; i < count; ++i) pap += p[i].dot(ap[i]);
      for (int32_t j = 0; j < 2 * supportCount; ++j) pap += P[j].dot(AP[j]);
      if (pap <= 0) break;  // not positive definite: should not happen, stop rather than diverge
      const double alpha = rz / pap;
      rr = 0.0;
      expand(p, P);
      for (int32_t i = 0; i < count; ++i) {
        x[i] += alpha * full[i];
        r[i] -= alpha * ap[i];
        rr += r[i].squaredNorm();
      }
      for (int32_t j = 0; j < 2 * supportCount; ++j) {
        X[j] += alpha * P[j];
        R[j] -= alpha * AP[j];
        rr += R[j].squaredNorm();
      }
      // Once the residual is down to kEarlyCheckTolerance, a moving support's hold that pulls
      // already shows: let it go and start again rather than converge a solve that keeps it (not
      // in the last round, which converges whatever it holds).
      if (!checked && round + 1 < kMaxRounds && rr <= kEarlyCheckTolerance * kEarlyCheckTolerance * bNorm) {
        checked = true;
        restart = releasePulling();
        if (restart) break;
      }
      const double next = precondition();
      const double beta = next / rz;
      rz = next;
      for (int32_t i = 0; i < count; ++i) p[i] = z[i] + beta * p[i];
      for (int32_t j = 0; j < 2 * supportCount; ++j) P[j] = Z[j] + beta * P[j];
    }
    converged = !restart && rr <= kRelativeTolerance * kRelativeTolerance * bNorm;
    if (restart) continue;              // holds let go early: solve again
    apply(x, ap);  // and solve again if holds changed at the end (not after the last round)
    if (round + 1 == kMaxRounds || !updateHolds()) break;
  }
  for (size_t k = 0; k < bodies.size(); ++k) {
    ImplicitBody& body = *bodies[k];
    Supports& support = *supports[k];
    body.lastIterations = iteration;
    body.lastConverged = converged;
    support.clearHolds();  // ap is A x: x has not moved since the last release check
    for (int32_t i = 0; i < body.nodeCount; ++i) {
      const int32_t g = sliceStart[k] + i;
      if (stuck[g])  // its c whole; a sliding node's, c·n and its push
        support.recordHold(i, Vec3(ap[g] - b[g]));
      else if (!held[g].isZero())
        support.recordHold(i, Vec3(held[g].dot(ap[g] - b[g]) * held[g] + slidingPush[g]), !slidingPush[g].isZero());
      if (mass[g] > 0) nodes.velocity[body.firstNode + i] += x[g];
    }
    std::copy_n(x.begin() + sliceStart[k], body.nodeCount, body.previousStep.begin());
  }
}

void addImplicitStiffness(const ImplicitBody& body, const NodeArrays& nodes, double h, std::vector<NodePairStiffness>& out) {
  // The elements' blocks, each pair once (a ≤ b), and the transposes of those off the diagonal:
  // the direct block wants every block of its matrix.
  const size_t first = out.size();
  addFemStiffnessBlocks(body.fem, body.rotations, h, out);
  const size_t once = out.size();
  for (size_t i = first; i < once; ++i)
    if (out[i].nodeA != out[i].nodeB) out.push_back({out[i].nodeB, out[i].nodeA, out[i].k.transpose()});
  if (body.springs.empty()) return;
  // Each node's diagonal block once, summed over its springs; each spring's two off-diagonal ones.
  const size_t diagonal = out.size();
  for (int32_t i = 0; i < body.nodeCount; ++i) out.push_back({body.firstNode + i, body.firstNode + i, Mat3::Zero()});
  for (const EdgeSpring& spring : body.springs) {
    const SpringBlocks blocks = springBlocks(spring, nodes.position);
    const Mat3 s = h * h * blocks.stiffness + h * blocks.damping;
    out[diagonal + static_cast<size_t>(spring.nodeA - body.firstNode)].k += s;
    out[diagonal + static_cast<size_t>(spring.nodeB - body.firstNode)].k += s;
    out.push_back({spring.nodeA, spring.nodeB, -s});
    out.push_back({spring.nodeB, spring.nodeA, -s});
  }
}

}  // namespace tandem
