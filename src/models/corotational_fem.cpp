#include "models/corotational_fem.h"

#include <Eigen/LU>
#include <Eigen/SVD>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <unordered_map>

namespace tandem {
namespace {

Mat3 edgeMatrix(std::span<const Vec3> x, const std::array<int32_t, 4>& n, int32_t offset) {
  Mat3 d;
  for (int k = 0; k < 3; ++k) d.col(k) = x[n[k + 1] - offset] - x[n[0] - offset];
  return d;
}

// The rotation R of F that maximises tr(Rᵀ F): U diag(1, 1, ±1) Vᵀ from F's SVD, the sign taking
// a reflection out of its smallest direction (the polar decomposition's rotation when det F > 0).
// For det F > 0 it is found by Newton's iteration for the polar factor, X ← ½ (γ X + X⁻ᵀ / γ)
// from X = F with Higham's scaling γ = (‖X⁻¹‖ / ‖X‖)^½ (Frobenius), which converges
// quadratically, to rounding in a few turns for a jelly's elements: the element forces took 9 % of
// jelly_dish's step (perf) where the JacobiSVD alone took 13 %. A flat or inverted element, or one it does not settle
// in ten turns, takes the SVD.
Mat3 rotationOf(const Mat3& f) {
  if (f.determinant() > 0) {
    Mat3 x = f;
    for (int turn = 0; turn < 10; ++turn) {
      const Mat3 inverse = x.inverse();
      const double gamma = std::sqrt(std::sqrt(inverse.squaredNorm() / x.squaredNorm()));
      const Mat3 next = 0.5 * (gamma * x + inverse.transpose() / gamma);
      const double change = (next - x).squaredNorm();
      x = next;
      if (change < 1e-26) return x;
    }
  }
  const Eigen::JacobiSVD<Mat3> svd(f, Eigen::ComputeFullU | Eigen::ComputeFullV);
  Mat3 u = svd.matrixU();
  if ((u * svd.matrixV().transpose()).determinant() < 0) u.col(2) = -u.col(2);
  return u * svd.matrixV().transpose();
}

// The stress of a strain in the rotated frame: 2μ ε + λ tr(ε) I.
Mat3 stress(const Mat3& strain, double mu, double lambda) {
  return 2 * mu * strain + lambda * strain.trace() * Mat3::Identity();
}

// The forces −V P D_m⁻ᵀ: columns for nodes 1–3, their negated sum for node 0.
Mat3 nodeForces(const FemTetrahedron& tet, const Mat3& p) { return -tet.volume * p * tet.restInverse.transpose(); }

void scatter(const FemTetrahedron& tet, const Mat3& forces, std::span<Vec3> out, int32_t offset) {
  for (int k = 0; k < 3; ++k) {
    out[tet.node[k + 1] - offset] += forces.col(k);
    out[tet.node[0] - offset] -= forces.col(k);
  }
}

}  // namespace

FemElements makeFemElements(int32_t firstNode, std::span<const Vec3> restPositions,
                            std::span<const std::array<int32_t, 4>> tetrahedra, double youngsModulus,
                            double poissonRatio) {
  FemElements elements;
  elements.mu = youngsModulus / (2 * (1 + poissonRatio));
  elements.lambda = youngsModulus * poissonRatio / ((1 + poissonRatio) * (1 - 2 * poissonRatio));
  for (const auto& t : tetrahedra) {
    FemTetrahedron tet;
    const Mat3 dm = edgeMatrix(restPositions, t, 0);
    tet.node = {firstNode + t[0], firstNode + t[1], firstNode + t[2], firstNode + t[3]};
    tet.restInverse = dm.inverse();
    tet.volume = dm.determinant() / 6.0;
    elements.tetrahedra.push_back(tet);
  }
  std::unordered_map<uint64_t, int32_t> pairIndex;
  pairIndex.reserve(4 * elements.tetrahedra.size());
  elements.pairOfBlock.reserve(elements.tetrahedra.size());
  for (const FemTetrahedron& tet : elements.tetrahedra) {
    std::array<int32_t, 10>& slots = elements.pairOfBlock.emplace_back();
    int slot = 0;
    for (int a = 0; a < 4; ++a)
      for (int b = a; b < 4; ++b) {
        const int32_t low = std::min(tet.node[a], tet.node[b]), high = std::max(tet.node[a], tet.node[b]);
        const uint64_t key = (uint64_t{static_cast<uint32_t>(low)} << 32) | static_cast<uint32_t>(high);
        const auto [it, added] = pairIndex.try_emplace(key, static_cast<int32_t>(elements.pairs.size()));
        if (added) elements.pairs.push_back({low, high});
        slots[slot++] = it->second;
      }
  }
  return elements;
}

void addFemForces(const FemElements& elements, std::span<const Vec3> position, std::span<Vec3> force,
                  int32_t offset, std::span<Mat3> rotations) {
  for (size_t t = 0; t < elements.tetrahedra.size(); ++t) {
    const FemTetrahedron& tet = elements.tetrahedra[t];
    const Mat3 f = edgeMatrix(position, tet.node, offset) * tet.restInverse;
    const Mat3 r = rotationOf(f);
    if (!rotations.empty()) rotations[t] = r;
    const Mat3 strain = 0.5 * (r.transpose() * f + f.transpose() * r) - Mat3::Identity();
    scatter(tet, nodeForces(tet, r * stress(strain, elements.mu, elements.lambda)), force, offset);
  }
}

void addFemStiffnessBlocks(const FemElements& elements, std::span<const Mat3> rotations, double h,
                           std::vector<NodePairStiffness>& out) {
  const size_t first = out.size();
  for (const auto& [a, b] : elements.pairs) out.push_back({a, b, Mat3::Zero()});
  for (size_t t = 0; t < elements.tetrahedra.size(); ++t) {
    const FemTetrahedron& tet = elements.tetrahedra[t];
    std::array<Vec3, 4> g, turned;  // the gradients g_a, and R g_a
    for (int k = 0; k < 3; ++k) g[k + 1] = tet.restInverse.row(k).transpose();
    g[0] = -(g[1] + g[2] + g[3]);
    for (int a = 0; a < 4; ++a) turned[a] = rotations[t] * g[a];
    const double scale = h * h * tet.volume;  // −h² K_ab = h² V (…), and K_ba = K_abᵀ
    const double mu = scale * elements.mu, lambda = scale * elements.lambda;
    int slot = 0;
    for (int a = 0; a < 4; ++a)
      for (int b = a; b < 4; ++b) {
        const Mat3 outer = turned[a] * turned[b].transpose();
        Mat3 k = mu * outer.transpose() + lambda * outer;  // the block of (node a, node b)
        k.diagonal().array() += mu * g[a].dot(g[b]);
        Mat3& pair = out[first + static_cast<size_t>(elements.pairOfBlock[t][slot++])].k;
        if (tet.node[a] <= tet.node[b])
          pair += k;
        else
          pair += k.transpose();
      }
  }
}

}  // namespace tandem
