#include "models/implicit_solve.h"

#include <algorithm>

namespace tandem {
namespace {

constexpr int kMaxIterations = 100;
// ‖b − A Δv‖ ≤ 1e-4 ‖b‖: on the paper's jellies a velocity error of the order of 1e-5 m/s, far
// below what the contacts and the block change; 1e-6 took 94 iterations on average against 42
// and doubled the jelly scene's model stage (12.5 → 6.5 ms per step).
constexpr double kRelativeTolerance = 1e-4;

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
  return body;
}

void solveImplicitVelocities(ImplicitBody& body, Supports& supports, NodeArrays& nodes, const Vec3& gravity,
                             double h, ImplicitSolveScratch& work) {
  const int32_t count = body.nodeCount, first = body.firstNode;
  auto free = [&](int32_t i) { return nodes.inverseMass[first + i] > 0; };
  const std::span<const Vec3> position(nodes.position.data() + first, count);
  std::vector<Vec3>& velocity = work.velocity;
  velocity.assign(nodes.velocity.begin() + first, nodes.velocity.begin() + first + count);
  for (int32_t i = 0; i < count; ++i)
    if (!free(i)) velocity[i].setZero();

  // Forces at (x, v): the elements' (with their rotations, which K keeps) and the springs'.
  body.rotations.resize(body.fem.tetrahedra.size());
  const std::vector<Mat3>& rotations = body.rotations;
  std::vector<Vec3>& force = work.force;
  force.assign(count, Vec3::Zero());
  addFemForces(body.fem, position, force, first, body.rotations);
  std::vector<EdgeSpring>& springs = work.springs;  // local indices
  springs.assign(body.springs.begin(), body.springs.end());
  std::vector<SpringBlocks>& blocks = work.springBlocks;
  blocks.clear();
  for (EdgeSpring& spring : springs) {
    spring.nodeA -= first;
    spring.nodeB -= first;
    blocks.push_back(springBlocks(spring, position));
  }
  addSpringForces(springs, position, velocity, force);

  // −K y (stiffness only) or −(h D + h² K) y (`damped`), matrix-free.
  auto negativeStiffness = [&](const std::vector<Vec3>& y, std::vector<Vec3>& out, bool damped) {
    out.assign(count, Vec3::Zero());
    addFemStiffnessProduct(body.fem, rotations, y, out, first);
    const double scale = damped ? -h * h : -1.0;
    for (Vec3& o : out) o *= scale;
    for (size_t s = 0; s < springs.size(); ++s) {
      const Mat3 block = damped ? Mat3(h * h * blocks[s].stiffness + h * blocks[s].damping) : blocks[s].stiffness;
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
    for (int32_t i = 0; i < count; ++i)
      out[i] = free(i) ? Vec3(y[i] / nodes.inverseMass[first + i] + scratch[i]) : Vec3::Zero();
  };
  // Jacobi preconditioner: P = diag(m + h² tr(−K_ii)/3 + tr(h² K_s + h D_s)/3) per node, elements'
  // and springs' blocks.
  if (body.stiffnessDiagonal.size() != static_cast<size_t>(count)) {
    body.stiffnessDiagonal.assign(count, 0.0);
    std::vector<NodePairStiffness> pairs;
    addFemStiffnessBlocks(body.fem, rotations, 1.0, pairs);
    for (const NodePairStiffness& pair : pairs)
      if (pair.nodeA == pair.nodeB) body.stiffnessDiagonal[pair.nodeA - first] += pair.k.trace() / 3.0;
  }
  std::vector<double>& preconditioner = work.preconditioner;
  preconditioner.assign(count, 0.0);
  for (int32_t i = 0; i < count; ++i)
    if (free(i)) preconditioner[i] = 1.0 / nodes.inverseMass[first + i] + h * h * body.stiffnessDiagonal[i];
  for (size_t s = 0; s < springs.size(); ++s) {
    const double k = (h * h * blocks[s].stiffness + h * blocks[s].damping).trace() / 3.0;
    for (int32_t node : {springs[s].nodeA, springs[s].nodeB})
      if (free(node)) preconditioner[node] += k;
  }
  for (double& d : preconditioner) d = d > 0.0 ? 1.0 / d : 0.0;

  // b = h (f + f_ext + m g) + h² K v
  std::vector<Vec3>& b = work.b;
  std::vector<Vec3>& kv = work.stiffnessTimesVelocity;
  b.resize(count);
  negativeStiffness(velocity, kv, false);
  for (int32_t i = 0; i < count; ++i)
    b[i] = free(i) ? Vec3(h * (force[i] + nodes.force[first + i] + gravity / nodes.inverseMass[first + i]) - h * h * kv[i])
                   : Vec3::Zero();

  // Held nodes, and the normal Δv each must take (see the header).
  std::vector<Vec3>& held = work.held;
  std::vector<double>& heldChange = work.heldChange;
  held.assign(count, Vec3::Zero());
  heldChange.assign(count, 0.0);
  for (int32_t i = 0; i < count; ++i) {
    const Vec3& n = supports.normal[i];
    if (n.isZero() || !free(i)) continue;
    const double target = supports.targetSpeed(i, h);
    const double freeSpeed = n.dot(nodes.velocity[first + i] + h * gravity);
    if (freeSpeed >= target) continue;
    held[i] = n;
    heldChange[i] = target - n.dot(nodes.velocity[first + i]);
  }
  // Filtered conjugate gradients (Baraff and Witkin 1998), Jacobi-preconditioned, from last step's
  // Δv: S takes out the held normal components.
  auto filter = [&](std::vector<Vec3>& y) {
    for (int32_t i = 0; i < count; ++i) y[i] -= held[i].dot(y[i]) * held[i];
  };
  std::vector<Vec3>& x = body.previousStep;
  for (int32_t i = 0; i < count; ++i)
    if (!free(i)) x[i].setZero();
  std::vector<Vec3>& r = work.r;
  std::vector<Vec3>& z = work.z;
  std::vector<Vec3>& p = work.p;
  std::vector<Vec3>& ap = work.ap;
  r.resize(count);
  z.resize(count);
  double bNorm = 0.0;
  for (const Vec3& bi : b) bNorm += bi.squaredNorm();
  int iteration = 0;
  for (int round = 0; round < 3; ++round) {
    for (int32_t i = 0; i < count; ++i) x[i] += (heldChange[i] - held[i].dot(x[i])) * held[i];
    apply(x, ap);
    for (int32_t i = 0; i < count; ++i) r[i] = b[i] - ap[i];
    filter(r);
    auto precondition = [&]() {  // z = S P⁻¹ r, and returns r·z
      double rz = 0.0;
      for (int32_t i = 0; i < count; ++i) z[i] = preconditioner[i] * r[i];
      filter(z);
      for (int32_t i = 0; i < count; ++i) rz += r[i].dot(z[i]);
      return rz;
    };
    double rr = 0.0;
    for (const Vec3& ri : r) rr += ri.squaredNorm();
    double rz = precondition();
    p = z;
    for (; iteration < kMaxIterations && rr > kRelativeTolerance * kRelativeTolerance * bNorm; ++iteration) {
      apply(p, ap);
      filter(ap);
      double pap = 0.0;
      for (int32_t i = 0; i < count; ++i) pap += p[i].dot(ap[i]);
      if (pap <= 0) break;  // not positive definite: should not happen, stop rather than diverge
      const double alpha = rz / pap;
      rr = 0.0;
      for (int32_t i = 0; i < count; ++i) {
        x[i] += alpha * p[i];
        r[i] -= alpha * ap[i];
        rr += r[i].squaredNorm();
      }
      const double next = precondition();
      const double beta = next / rz;
      rz = next;
      for (int32_t i = 0; i < count; ++i) p[i] = z[i] + beta * p[i];
    }
    // Let go of holds that pull (c = A Δv − b against the normal), and solve again if any did.
    apply(x, ap);
    bool released = false;
    for (int32_t i = 0; i < count; ++i) {
      if (held[i].isZero() || held[i].dot(ap[i] - b[i]) >= 0) continue;
      held[i].setZero();
      heldChange[i] = 0.0;
      released = true;
    }
    if (!released) break;
  }
  body.lastIterations = iteration;
  supports.clearHolds();  // ap is A x: x has not moved since the last release check
  for (int32_t i = 0; i < count; ++i)
    if (!held[i].isZero()) supports.recordHold(i, held[i].dot(ap[i] - b[i]));
  for (int32_t i = 0; i < count; ++i)
    if (free(i)) nodes.velocity[first + i] += x[i];
}

void addImplicitStiffness(const ImplicitBody& body, const NodeArrays& nodes, double h, std::vector<NodePairStiffness>& out) {
  addFemStiffnessBlocks(body.fem, body.rotations, h, out);
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
