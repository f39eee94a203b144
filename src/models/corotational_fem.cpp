#include "models/corotational_fem.h"

#include <Eigen/LU>
#include <Eigen/SVD>

#include <cmath>

namespace tandem {
namespace {

constexpr int kMaxIterations = 100;
constexpr double kRelativeTolerance = 1e-6;

Mat3 edgeMatrix(std::span<const Vec3> x, const std::array<int32_t, 4>& n, int32_t offset) {
  Mat3 d;
  for (int k = 0; k < 3; ++k) d.col(k) = x[n[k + 1] - offset] - x[n[0] - offset];
  return d;
}

Mat3 rotationOf(const Mat3& f) {
  const Eigen::JacobiSVD<Mat3> svd(f, Eigen::ComputeFullU | Eigen::ComputeFullV);
  Mat3 u = svd.matrixU();
  if ((u * svd.matrixV().transpose()).determinant() < 0) u.col(2) = -u.col(2);
  return u * svd.matrixV().transpose();
}

// The stress of a strain in the rotated frame: 2μ ε + λ tr(ε) I.
Mat3 stress(const Mat3& strain, double mu, double lambda) {
  return 2 * mu * strain + lambda * strain.trace() * Mat3::Identity();
}

// Adds the forces −V P D_m⁻ᵀ (columns for nodes 1–3, their negated sum for node 0).
void scatter(const FemTetrahedron& tet, const Mat3& p, std::span<Vec3> out, int32_t offset) {
  const Mat3 h = -tet.volume * p * tet.restInverse.transpose();
  for (int k = 0; k < 3; ++k) {
    out[tet.node[k + 1] - offset] += h.col(k);
    out[tet.node[0] - offset] -= h.col(k);
  }
}

// P = R (2μ ε + λ tr(ε) I) at positions x; `rotation` gets R.
Mat3 firstPiolaStress(const FemBody& body, const FemTetrahedron& tet, std::span<const Vec3> x, Mat3& rotation) {
  const Mat3 f = edgeMatrix(x, tet.node, 0) * tet.restInverse;
  rotation = rotationOf(f);
  const Mat3 strain = 0.5 * (rotation.transpose() * f + f.transpose() * rotation) - Mat3::Identity();
  return rotation * stress(strain, body.mu, body.lambda);
}

}  // namespace

FemBody makeFemBody(int32_t firstNode, std::span<const Vec3> restPositions,
                    std::span<const std::array<int32_t, 4>> tetrahedra, double youngsModulus, double poissonRatio) {
  FemBody body;
  body.firstNode = firstNode;
  body.nodeCount = static_cast<int32_t>(restPositions.size());
  body.mu = youngsModulus / (2 * (1 + poissonRatio));
  body.lambda = youngsModulus * poissonRatio / ((1 + poissonRatio) * (1 - 2 * poissonRatio));
  for (const auto& t : tetrahedra) {
    FemTetrahedron tet;
    const Mat3 dm = edgeMatrix(restPositions, t, 0);
    tet.node = {firstNode + t[0], firstNode + t[1], firstNode + t[2], firstNode + t[3]};
    tet.restInverse = dm.inverse();
    tet.volume = dm.determinant() / 6.0;
    body.tetrahedra.push_back(tet);
  }
  body.previousStep.assign(restPositions.size(), Vec3::Zero());
  clearSupports(body);
  return body;
}

void addFemForces(const FemBody& body, NodeArrays& nodes) {
  Mat3 rotation;
  for (const FemTetrahedron& tet : body.tetrahedra)
    scatter(tet, firstPiolaStress(body, tet, nodes.position, rotation), nodes.force, 0);
}

void solveFemVelocities(FemBody& body, NodeArrays& nodes, const Vec3& gravity, double h) {
  const int32_t count = body.nodeCount, first = body.firstNode;
  // Forces at x, and the rotations the stiffness is taken with.
  std::vector<Mat3> rotations(body.tetrahedra.size());
  std::vector<Vec3> force(count, Vec3::Zero());
  for (size_t t = 0; t < body.tetrahedra.size(); ++t)
    scatter(body.tetrahedra[t], firstPiolaStress(body, body.tetrahedra[t], nodes.position, rotations[t]), force, first);
  auto free = [&](int32_t i) { return nodes.inverseMass[first + i] > 0; };
  // K δx, matrix-free, with R held.
  auto stiffness = [&](const std::vector<Vec3>& dx, std::vector<Vec3>& out) {
    out.assign(count, Vec3::Zero());
    for (size_t t = 0; t < body.tetrahedra.size(); ++t) {
      const FemTetrahedron& tet = body.tetrahedra[t];
      const Mat3& r = rotations[t];
      const Mat3 df = edgeMatrix(dx, tet.node, first) * tet.restInverse;
      const Mat3 rotated = r.transpose() * df;
      scatter(tet, r * stress(0.5 * (rotated + rotated.transpose()), body.mu, body.lambda), out, first);
    }
  };
  // A y = (M − h² K) y, with pinned nodes held at zero.
  std::vector<Vec3> scratch;
  auto apply = [&](const std::vector<Vec3>& y, std::vector<Vec3>& out) {
    stiffness(y, scratch);
    out.resize(count);
    for (int32_t i = 0; i < count; ++i)
      out[i] = free(i) ? Vec3(y[i] / nodes.inverseMass[first + i] - h * h * scratch[i]) : Vec3::Zero();
  };
  // b = h (f + m g) + h² K v
  std::vector<Vec3> velocity(nodes.velocity.begin() + first, nodes.velocity.begin() + first + count);
  for (int32_t i = 0; i < count; ++i)
    if (!free(i)) velocity[i].setZero();
  std::vector<Vec3> b, kv;
  stiffness(velocity, kv);
  b.resize(count);
  for (int32_t i = 0; i < count; ++i)
    b[i] = free(i) ? Vec3(h * (force[i] + nodes.force[first + i] + gravity / nodes.inverseMass[first + i]) + h * h * kv[i])
                   : Vec3::Zero();

  // Held nodes, and the normal Δv each must take (see the header).
  std::vector<Vec3> held(count, Vec3::Zero());
  std::vector<double> heldChange(count, 0.0);
  for (int32_t i = 0; i < count; ++i) {
    const Vec3& n = body.supportNormal[i];
    if (n.isZero() || !free(i)) continue;
    const double target = body.supportSpeed[i] - std::max(body.supportGap[i], 0.0) / h;
    const double freeSpeed = n.dot(nodes.velocity[first + i] + h * gravity);
    if (freeSpeed >= target) continue;
    held[i] = n;
    heldChange[i] = target - n.dot(nodes.velocity[first + i]);
  }
  // Filtered conjugate gradients from last step's Δv: S takes out the held normal components.
  auto filter = [&](std::vector<Vec3>& y) {
    for (int32_t i = 0; i < count; ++i) y[i] -= held[i].dot(y[i]) * held[i];
  };
  std::vector<Vec3>& x = body.previousStep;
  for (int32_t i = 0; i < count; ++i)
    if (!free(i)) x[i].setZero();
  std::vector<Vec3> r(count), p, ap;
  double bNorm = 0.0;
  for (const Vec3& bi : b) bNorm += bi.squaredNorm();
  int iteration = 0;
  for (int round = 0; round < 3; ++round) {
    for (int32_t i = 0; i < count; ++i) x[i] += (heldChange[i] - held[i].dot(x[i])) * held[i];
    apply(x, ap);
    for (int32_t i = 0; i < count; ++i) r[i] = b[i] - ap[i];
    filter(r);
    double rr = 0.0;
    for (const Vec3& ri : r) rr += ri.squaredNorm();
    p = r;
    for (; iteration < kMaxIterations && rr > kRelativeTolerance * kRelativeTolerance * bNorm; ++iteration) {
      apply(p, ap);
      filter(ap);
      double pap = 0.0;
      for (int32_t i = 0; i < count; ++i) pap += p[i].dot(ap[i]);
      if (pap <= 0) break;  // not positive definite: should not happen, stop rather than diverge
      const double alpha = rr / pap;
      double next = 0.0;
      for (int32_t i = 0; i < count; ++i) {
        x[i] += alpha * p[i];
        r[i] -= alpha * ap[i];
        next += r[i].squaredNorm();
      }
      const double beta = next / rr;
      rr = next;
      for (int32_t i = 0; i < count; ++i) p[i] = r[i] + beta * p[i];
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
  for (int32_t i = 0; i < count; ++i)
    if (free(i)) nodes.velocity[first + i] += x[i];
}

void addFemStiffness(const FemBody& body, const NodeArrays& nodes, double h, std::vector<NodePairStiffness>& out) {
  for (const FemTetrahedron& tet : body.tetrahedra) {
    Mat3 r;
    firstPiolaStress(body, tet, nodes.position, r);
    std::array<std::array<Mat3, 4>, 4> block;  // block[a][b]: −h² ∂f_a / ∂x_b
    for (auto& row : block) row.fill(Mat3::Zero());
    for (int b = 0; b < 4; ++b)
      for (int c = 0; c < 3; ++c) {
        Mat3 ds = Mat3::Zero();  // δD_s for a unit move of node b along axis c
        for (int k = 0; k < 3; ++k)
          if (b == 0)
            ds(c, k) = -1.0;
          else if (b == k + 1)
            ds(c, k) = 1.0;
        const Mat3 rotated = r.transpose() * ds * tet.restInverse;
        const Mat3 forces = -tet.volume * r * stress(0.5 * (rotated + rotated.transpose()), body.mu, body.lambda) *
                            tet.restInverse.transpose();
        for (int k = 0; k < 3; ++k) {
          block[k + 1][b].col(c) = -h * h * forces.col(k);
          block[0][b].col(c) += h * h * forces.col(k);
        }
      }
    for (int a = 0; a < 4; ++a)
      for (int b = 0; b < 4; ++b) out.push_back({tet.node[a], tet.node[b], block[a][b]});
  }
}

void addSupport(FemBody& body, int32_t node, const Vec3& normal, double gap, double normalSpeed) {
  const int32_t i = node - body.firstNode;
  if (i < 0 || i >= body.nodeCount || (!body.supportNormal[i].isZero() && body.supportGap[i] <= gap)) return;
  body.supportNormal[i] = normal;  // the nearest surface wins
  body.supportGap[i] = gap;
  body.supportSpeed[i] = normalSpeed;
}

void clearSupports(FemBody& body) {
  body.supportNormal.assign(body.nodeCount, Vec3::Zero());
  body.supportGap.assign(body.nodeCount, 0.0);
  body.supportSpeed.assign(body.nodeCount, 0.0);
}

}  // namespace tandem
