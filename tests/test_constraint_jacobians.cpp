// Each row type's Jacobian against a central finite difference of its constraint function C,
// at random configurations; and each row's effective mass against J M⁻¹ Jᵀ built by hand. And a
// swept edge's geometric stiffness against the implicit response (M + h² K_g)⁻¹ it stands for.
#include "constraints/anchor.h"
#include "constraints/bending.h"
#include "constraints/fixed_point.h"
#include "constraints/inextensibility.h"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <random>

namespace tandem {
namespace {

constexpr double kStep = 1e-6;          // finite-difference step (m or rad)
constexpr double kRelativeTolerance = 1e-5;
constexpr int kConfigurations = 50;

Vec3 randomVector(std::mt19937& rng, double scale = 1.0) {
  std::uniform_real_distribution<double> u(-scale, scale);
  return {u(rng), u(rng), u(rng)};
}

NodeArrays randomNodes(std::mt19937& rng, int count) {
  NodeArrays nodes;
  std::uniform_real_distribution<double> mass(0.01, 2.0);
  for (int i = 0; i < count; ++i) {
    nodes.position.push_back(randomVector(rng));
    nodes.velocity.push_back(randomVector(rng));
    nodes.force.push_back(Vec3::Zero());
    nodes.inverseMass.push_back(1.0 / mass(rng));
  }
  return nodes;
}

// d/dx_i of a scalar function of the node positions, by central differences.
Vec3 finiteDifference(NodeArrays& nodes, int node, const std::function<double()>& c) {
  Vec3 gradient;
  for (int k = 0; k < 3; ++k) {
    const double saved = nodes.position[node][k];
    nodes.position[node][k] = saved + kStep;
    const double plus = c();
    nodes.position[node][k] = saved - kStep;
    const double minus = c();
    nodes.position[node][k] = saved;
    gradient[k] = (plus - minus) / (2 * kStep);
  }
  return gradient;
}

void expectClose(const Vec3& analytic, const Vec3& numeric) {
  const double scale = std::max(1.0, analytic.norm());
  EXPECT_LT((analytic - numeric).norm(), kRelativeTolerance * scale) << "analytic " << analytic.transpose()
                                                                      << " numeric " << numeric.transpose();
}

TEST(Jacobians, InextensibilityMatchesFiniteDifference) {
  std::mt19937 rng(1);
  for (int trial = 0; trial < kConfigurations; ++trial) {
    NodeArrays nodes = randomNodes(rng, 2);
    InextensibilityRow row;
    row.node = {0, 1};
    row.restLength = 0.7;
    prepareInextensibility(row, nodes, 0.01, 10.0);
    auto c = [&] { return inextensibilityError(nodes.position[0], nodes.position[1], row.restLength); };
    for (int k = 0; k < 2; ++k) expectClose(row.jacobian[k], finiteDifference(nodes, k, c));
    const double expectedMass = 1.0 / (nodes.inverseMass[0] + nodes.inverseMass[1]);
    EXPECT_NEAR(row.effectiveMass, expectedMass, 1e-12 * expectedMass);
    EXPECT_NEAR(row.bias, 10.0 * c(), 1e-12);
  }
}

// A bending row over nodes 0 to 3 (hinge 0-1, wings 2 and 3).
BendingRow bendingRowOverFourNodes() {
  BendingRow row;
  row.node = {0, 1, 2, 3};
  row.restDot = -0.3;
  row.restEdgeLength = 0.8;
  return row;
}

TEST(Jacobians, BendingMatchesFiniteDifference) {
  std::mt19937 rng(2);
  for (int trial = 0; trial < kConfigurations; ++trial) {
    NodeArrays nodes = randomNodes(rng, 4);
    BendingRow row = bendingRowOverFourNodes();
    prepareBending(row, nodes, 0.01, 10.0);
    auto c = [&] { return bendingError(row, nodes.position); };
    for (int k = 0; k < 4; ++k) expectClose(row.jacobian[k], finiteDifference(nodes, k, c));
    double inverseMass = 0.0;
    for (int k = 0; k < 4; ++k) inverseMass += nodes.inverseMass[k] * row.jacobian[k].squaredNorm();
    EXPECT_NEAR(row.effectiveMass, 1.0 / inverseMass, 1e-9 / inverseMass);
    // Σ J = 0: the row moves no momentum.
    EXPECT_LT((row.jacobian[0] + row.jacobian[1] + row.jacobian[2] + row.jacobian[3]).norm(), 1e-12);
  }
}

// The warm start carries last step's impulse onto the new Jacobian (constraints/bending.h): λ
// unchanged while J is, and otherwise the λ' whose velocity change W Jᵀ λ' is nearest, in the
// mass metric, to the old W J₀ᵀ λ: Σₖ wₖ Jₖ · (Jₖ λ' − J₀ₖ λ) = 0, bounded to ±F h.
TEST(Jacobians, BendingWarmStartCarriesTheImpulseOntoTheNewJacobian) {
  std::mt19937 rng(3);
  for (int trial = 0; trial < kConfigurations; ++trial) {
    NodeArrays nodes = randomNodes(rng, 4);
    BendingRow row = bendingRowOverFourNodes();
    row.maxForce = 1e6;  // no bound in the way
    prepareBending(row, nodes, 0.01, 10.0);
    row.lambda = 0.37;
    prepareBending(row, nodes, 0.01, 10.0);
    EXPECT_NEAR(row.lambda, 0.37, 1e-12);
    const std::array<Vec3, 4> before = row.jacobian;
    for (Vec3& x : nodes.position) x += randomVector(rng, 0.3);
    prepareBending(row, nodes, 0.01, 10.0);
    double gradient = 0.0, scale = 0.0;
    for (int k = 0; k < 4; ++k) {
      gradient += nodes.inverseMass[k] * row.jacobian[k].dot(row.jacobian[k] * row.lambda - before[k] * 0.37);
      scale += nodes.inverseMass[k] * row.jacobian[k].norm() * before[k].norm() * 0.37;
    }
    EXPECT_LT(std::abs(gradient), 1e-12 * scale);
    EXPECT_GT(std::abs(row.lambda - 0.37), 1e-6);  // the moves changed J
    row.maxForce = 1.0;  // |λ| ≤ F h = 0.01
    row.lambda = 5.0;
    prepareBending(row, nodes, 0.01, 10.0);
    EXPECT_NEAR(std::abs(row.lambda), 0.01, 1e-15);
  }
}

TEST(Jacobians, FixedPointMatchesFiniteDifference) {
  std::mt19937 rng(3);
  for (int trial = 0; trial < kConfigurations; ++trial) {
    NodeArrays nodes = randomNodes(rng, 1);
    const Vec3 target = randomVector(rng);
    for (int axis = 0; axis < 3; ++axis) {
      auto c = [&] { return fixedPointError(nodes.position[0], target)[axis]; };
      expectClose(Vec3::Unit(axis), finiteDifference(nodes, 0, c));  // J = I
    }
    FixedPointRow row;
    row.node = 0;
    row.target = row.previousTarget = target;
    row.maxForce = kUnbounded;
    prepareFixedPoint(row, nodes, 0.01, 10.0);
    EXPECT_NEAR(row.effectiveMass, 1.0 / nodes.inverseMass[0], 1e-12);
    // One solve makes Ċ + b vanish: the block is exact.
    std::vector<RigidSolverState> rigid;
    SolverContext ctx{nodes.velocity, nodes.inverseMass, rigid, 0.01, 10.0};
    SweepStats stats;
    solveFixedPoint(row, ctx, stats);
    EXPECT_LT((nodes.velocity[0] + row.bias).norm(), 1e-12);
  }
}

TEST(Jacobians, AnchorMatchesFiniteDifference) {
  std::mt19937 rng(4);
  for (int trial = 0; trial < kConfigurations; ++trial) {
    NodeArrays nodes = randomNodes(rng, 4);
    std::uniform_real_distribution<double> unit(0.05, 1.0);
    AnchorRow row;
    double sum = 0.0;
    for (int k = 0; k < 4; ++k) {
      row.node[k] = k;
      row.weight[k] = unit(rng);
      sum += row.weight[k];
    }
    for (double& w : row.weight) w /= sum;
    row.localPoint = randomVector(rng, 0.5);
    row.maxForce = kUnbounded;
    RigidSolverState body;
    body.centerOfMass = randomVector(rng);
    body.orientation = Quat(Eigen::AngleAxisd(unit(rng) * 3, randomVector(rng).normalized()));
    body.inverseMass = 1.0 / unit(rng);
    const Mat3 rotation = body.orientation.toRotationMatrix();
    body.inverseInertia = rotation * Vec3(1 / unit(rng), 1 / unit(rng), 1 / unit(rng)).asDiagonal() * rotation.transpose();
    prepareAnchor(row, nodes, body, 0.01, 10.0);

    for (int axis = 0; axis < 3; ++axis) {
      auto c = [&] { return anchorError(row, nodes.position, body.centerOfMass, body.orientation)[axis]; };
      // Node entries: wₖ eᵢ.
      for (int k = 0; k < 4; ++k) expectClose(row.weight[k] * Vec3::Unit(axis), finiteDifference(nodes, k, c));
      // Linear entry: −eᵢ; angular entry: eᵢ × a (perturbing the orientation by a world rotation).
      Vec3 linear, angular;
      for (int m = 0; m < 3; ++m) {
        const Vec3 saved = body.centerOfMass;
        body.centerOfMass[m] = saved[m] + kStep;
        const double plus = c();
        body.centerOfMass[m] = saved[m] - kStep;
        const double minus = c();
        body.centerOfMass = saved;
        linear[m] = (plus - minus) / (2 * kStep);

        const Quat savedQ = body.orientation;
        body.orientation = Quat(Eigen::AngleAxisd(kStep, Vec3::Unit(m))) * savedQ;
        const double turnPlus = c();
        body.orientation = Quat(Eigen::AngleAxisd(-kStep, Vec3::Unit(m))) * savedQ;
        const double turnMinus = c();
        body.orientation = savedQ;
        angular[m] = (turnPlus - turnMinus) / (2 * kStep);
      }
      expectClose(-Vec3::Unit(axis), linear);
      expectClose(Vec3::Unit(axis).cross(row.offset), angular);
    }

    // Effective mass: K = J M⁻¹ Jᵀ assembled from the 3×(12 + 6) Jacobian.
    Eigen::Matrix<double, 3, 18> j = Eigen::Matrix<double, 3, 18>::Zero();
    Eigen::Matrix<double, 18, 18> inverseMass = Eigen::Matrix<double, 18, 18>::Zero();
    for (int k = 0; k < 4; ++k) {
      j.block<3, 3>(0, 3 * k) = row.weight[k] * Mat3::Identity();
      inverseMass.block<3, 3>(3 * k, 3 * k) = nodes.inverseMass[k] * Mat3::Identity();
    }
    j.block<3, 3>(0, 12) = -Mat3::Identity();
    for (int axis = 0; axis < 3; ++axis) j.block<1, 3>(axis, 15) = Vec3::Unit(axis).cross(row.offset).transpose();
    inverseMass.block<3, 3>(12, 12) = body.inverseMass * Mat3::Identity();
    inverseMass.block<3, 3>(15, 15) = body.inverseInertia;
    const Mat3 k = j * inverseMass * j.transpose();
    EXPECT_LT((row.effectiveMass * k - Mat3::Identity()).norm(), 1e-9);
  }
}

// A taut edge (last step's tension T) whose end j is given a sideways impulse P by some other
// row: the edge's geometric stiffness h² K_g = s (I − n nᵀ) [I −I; −I I], s = h T / ℓ = |λ| / ℓ · h,
// makes the pair answer as the implicit system (M + h² K_g) Δv = (0, P) does, to rounding, with
// P shared between the nodes and their momentum exactly P; along the edge, and for an edge that
// was not taut, the row does nothing.
TEST(GeometricStiffness, ASweptEdgeAnswersASidewaysImpulseAsTheImplicitSystemDoes) {
  constexpr double h = 0.02, tension = 50.0, length = 0.5, mi = 0.2, mj = 0.05, impulse = 0.01;
  const Vec3 n = Vec3(1, 2, 2).normalized(), sideways = n.cross(Vec3::UnitZ()).normalized();
  auto run = [&](double lastLambda, const Vec3& direction) {
    NodeArrays nodes;
    nodes.position = {Vec3::Zero(), length * n};
    nodes.velocity = {Vec3::Zero(), Vec3::Zero()};
    nodes.force = {Vec3::Zero(), Vec3::Zero()};
    nodes.inverseMass = {1.0 / mi, 1.0 / mj};
    InextensibilityRow row;
    row.node = {0, 1};
    row.restLength = length;
    row.lambdaMin = -INFINITY;
    row.lambdaMax = INFINITY;
    row.lambda = lastLambda;
    prepareInextensibility(row, nodes, h, 0.0);
    const std::vector<Vec3> start = nodes.velocity;  // before the step's impulses
    nodes.velocity[1] += impulse / mj * direction;   // another row's
    std::vector<RigidSolverState> rigid;
    SolverContext ctx{nodes.velocity, nodes.inverseMass, rigid, h, 0.0, start};
    solveGeometricStiffness(row, ctx);
    return nodes.velocity;
  };
  // Taut: λ = −T h. The implicit response across the edge, per unit of P.
  const std::vector<Vec3> v = run(-tension * h, sideways);
  const double s = h * tension * h / length;
  const double denominator = mi * mj + s * (mi + mj);
  EXPECT_NEAR(v[0].dot(sideways), impulse * s / denominator, 1e-14);
  EXPECT_NEAR(v[1].dot(sideways), impulse * (mi + s) / denominator, 1e-14);
  EXPECT_LT((mi * v[0] + mj * v[1] - impulse * sideways).norm(), 1e-15);
  EXPECT_LT(std::abs(v[0].dot(n)) + std::abs(v[1].dot(n)), 1e-15);
  // Without it the struck node alone would move: here the stiffness passes 40 % of P to the other.
  EXPECT_GT(mi * v[0].dot(sideways), 0.3 * impulse);
  // Along the edge: nothing (that is the row's own Jacobian's).
  const std::vector<Vec3> along = run(-tension * h, n);
  EXPECT_EQ(along[0], Vec3::Zero());
  // An edge in compression or slack last step: nothing.
  const std::vector<Vec3> slack = run(tension * h, sideways);
  EXPECT_EQ(slack[0], Vec3::Zero());
}

}  // namespace
}  // namespace tandem
