#include "models/position_based.h"

#include "solver/graph_colouring.h"

#include <Eigen/SVD>

#include <algorithm>
#include <cmath>
#include <type_traits>

namespace tandem {
namespace {

void predict(const PositionBasedBody& body, const NodeArrays& nodes, double timeStep, PositionBasedScratch& scratch) {
  scratch.predicted.resize(static_cast<size_t>(body.nodeCount));
  scratch.goals.resize(static_cast<size_t>(body.nodeCount));
  for (int32_t i = 0; i < body.nodeCount; ++i)
    scratch.predicted[i] = nodes.position[body.firstNode + i] + timeStep * nodes.velocity[body.firstNode + i];
}

// Mass-weighted centre; pinned nodes (m⁻¹ = 0) count with a large mass.
Vec3 centre(std::span<const Vec3> x, std::span<const double> inverseMass, double& totalMass) {
  Vec3 sum = Vec3::Zero();
  totalMass = 0.0;
  for (size_t i = 0; i < x.size(); ++i) {
    const double m = inverseMass[i] > 0 ? 1.0 / inverseMass[i] : 1e12;
    sum += m * x[i];
    totalMass += m;
  }
  return sum / totalMass;
}

}  // namespace

PositionBasedRest positionBasedRest(std::span<const Vec3> restPositions, std::span<const std::array<int32_t, 2>> edges,
                                    std::span<const std::array<int32_t, 4>> tetrahedra) {
  PositionBasedRest rest;
  const auto& x = restPositions;
  ColouringScratch scratch;
  auto byColour = [&](const auto& rows, std::vector<int32_t>& order) {
    const std::vector<std::decay_t<decltype(rows[0])>> copied(rows.begin(), rows.end());
    colourIndices(
        copied, [](const auto&) { return true; }, x.size(),
        [](const auto& row, auto add) {
          for (int32_t node : row) add(static_cast<size_t>(node));
        },
        order, scratch);
  };
  std::vector<int32_t> order;
  byColour(edges, order);
  for (const int32_t i : order) {
    const auto& e = edges[static_cast<size_t>(i)];
    rest.edges.push_back({e, (x[e[1]] - x[e[0]]).norm()});
  }
  byColour(tetrahedra, order);
  for (const int32_t i : order) {
    const auto& t = tetrahedra[static_cast<size_t>(i)];
    rest.tetrahedra.push_back({t, (x[t[1]] - x[t[0]]).dot((x[t[2]] - x[t[0]]).cross(x[t[3]] - x[t[0]]))});
  }
  return rest;
}

void shapeMatchingGoals(const PositionBasedBody& body, std::span<const Vec3> predicted,
                        std::span<const double> inverseMass, std::span<Vec3> goals) {
  double mass = 0.0;
  const Vec3 c = centre(predicted, inverseMass, mass);
  const Vec3 c0 = centre(body.restPositions, inverseMass, mass);
  Mat3 a = Mat3::Zero();
  for (int32_t i = 0; i < body.nodeCount; ++i) {
    const double m = inverseMass[i] > 0 ? 1.0 / inverseMass[i] : 1e12;
    a += m * (predicted[i] - c) * (body.restPositions[i] - c0).transpose();
  }
  // The rotation nearest A: U Vᵀ from its SVD, with the reflection (if any) taken out.
  const Eigen::JacobiSVD<Mat3> svd(a, Eigen::ComputeFullU | Eigen::ComputeFullV);
  Mat3 u = svd.matrixU();
  if ((u * svd.matrixV().transpose()).determinant() < 0) u.col(2) = -u.col(2);
  const Mat3 rotation = u * svd.matrixV().transpose();
  for (int32_t i = 0; i < body.nodeCount; ++i) goals[i] = rotation * (body.restPositions[i] - c0) + c;
}

void positionBasedGoals(const PositionBasedBody& body, std::span<const Vec3> predicted,
                        std::span<const double> inverseMass, std::span<Vec3> x) {
  std::copy(predicted.begin(), predicted.end(), x.begin());
  const double k = 1.0 - std::pow(1.0 - body.stiffness, 1.0 / body.iterations);
  for (int iteration = 0; iteration < body.iterations; ++iteration) {
    for (const PositionBasedRest::Edge& edge : body.rest->edges) {
      const auto& e = edge.node;
      const double wi = inverseMass[e[0]], wj = inverseMass[e[1]];
      if (wi + wj == 0.0) continue;
      const Vec3 d = x[e[1]] - x[e[0]];
      const double length = d.norm();
      if (length < 1e-12) continue;
      const Vec3 correction = k * (length - edge.length) / (wi + wj) * (d / length);
      x[e[0]] += wi * correction;
      x[e[1]] -= wj * correction;
    }
    for (const PositionBasedRest::Tetrahedron& tetrahedron : body.rest->tetrahedra) {
      // C = 6V − 6V⁰ with 6V = (x₁ − x₀)·((x₂ − x₀) × (x₃ − x₀)).
      const auto& t = tetrahedron.node;
      const Vec3 e1 = x[t[1]] - x[t[0]], e2 = x[t[2]] - x[t[0]], e3 = x[t[3]] - x[t[0]];
      const double volume = e1.dot(e2.cross(e3));
      std::array<Vec3, 4> gradient{Vec3::Zero(), e2.cross(e3), e3.cross(e1), e1.cross(e2)};
      gradient[0] = -(gradient[1] + gradient[2] + gradient[3]);
      double denominator = 0.0;
      for (int n = 0; n < 4; ++n) denominator += inverseMass[t[n]] * gradient[n].squaredNorm();
      if (denominator < 1e-24) continue;
      const double scale = -k * (volume - tetrahedron.sixVolume) / denominator;
      for (int n = 0; n < 4; ++n) x[t[n]] += scale * inverseMass[t[n]] * gradient[n];
    }
    for (const SupportPlane& plane : body.supports) {  // hard, like the contacts they stand for
      const double below = plane.minimum - plane.normal.dot(x[plane.node]);
      if (below <= 0) continue;
      x[plane.node] += below * plane.normal;
      if (!body.supportPush.empty()) body.supportPush[plane.node] += below;
    }
  }
}

void applyShapeMatching(const PositionBasedBody& body, NodeArrays& nodes, double timeStep,
                        PositionBasedScratch& scratch) {
  predict(body, nodes, timeStep, scratch);
  const std::vector<Vec3>& predicted = scratch.predicted;
  const std::vector<Vec3>& goals = scratch.goals;
  const std::span<const double> inverseMass(nodes.inverseMass.data() + body.firstNode, body.nodeCount);
  shapeMatchingGoals(body, predicted, body.weightInverseMass.empty() ? inverseMass : body.weightInverseMass, scratch.goals);
  for (int32_t i = 0; i < body.nodeCount; ++i) {
    if (inverseMass[i] == 0.0) continue;
    Vec3& v = nodes.velocity[body.firstNode + i];
    v = (1.0 - body.damping) * (v + body.stiffness * (goals[i] - predicted[i]) / timeStep);
  }
}

void applyPositionBasedDynamics(const PositionBasedBody& body, NodeArrays& nodes, double timeStep,
                                PositionBasedScratch& scratch) {
  predict(body, nodes, timeStep, scratch);
  const std::vector<Vec3>& goals = scratch.goals;
  const std::span<const double> inverseMass(nodes.inverseMass.data() + body.firstNode, body.nodeCount);
  positionBasedGoals(body, scratch.predicted, body.weightInverseMass.empty() ? inverseMass : body.weightInverseMass,
                     scratch.goals);
  for (int32_t i = 0; i < body.nodeCount; ++i) {
    if (inverseMass[i] == 0.0) continue;
    Vec3& v = nodes.velocity[body.firstNode + i];
    v = body.damping * v + (1.0 - body.damping) * (goals[i] - nodes.position[body.firstNode + i]) / timeStep;
  }
}

}  // namespace tandem
