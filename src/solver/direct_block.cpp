#include "solver/direct_block.h"

#include <algorithm>
#include <cmath>

namespace tandem {
namespace {

// E = ε · diag(J M⁻¹ Jᵀ). Just enough for redundant rows (nodes anchored to one rigid body and
// joined by edges too) to stay solvable; any larger and it softens long chains, whose
// smallest eigenvalue falls like 1/n² (a 1,000-node rope stretches by 390 % at ε = 1e-4).
constexpr double kRelativeCompliance = 1e-9;
// Rounds of releasing pulling contacts per solve; each is solved again with a low-rank
// correction, until this many contacts are let go since the last factorisation, then refactorised.
constexpr int kMaxReleaseRounds = 3;
// h² K_g per edge is at most this multiple of its lighter node's mass.
constexpr double kMaxStiffnessToMass = 100;
// Contacts whose friction a block solves in its own metric (two KKT right-hand sides each per
// factorisation, solved together).
constexpr size_t kMaxFrictionContacts = 32;
// A kept factorisation is used while its refinement steps leave at most this fraction of the
// right-hand side (in velocities: a degree of freedom's residual impulse over its H_ii) unsolved.
constexpr double kKeptFactorTolerance = 1e-4;
// At most this many refinement steps per solve with a kept factorisation; past them, it is made afresh.
constexpr int kMaxKeptRefinements = 2;
// Stretch (of each edge's rest length) a block that moves bodies leaves to its rows' bias
// (projectPositions): half the 1 % the strain-limiting passes allow, the rest for the linearised
// solve's own error (a heavy pendulum's rope: 0.68 % at worst, with one solve per step).
constexpr double kProjectionBand = 0.005;

bool isUnbounded(double maxForce) { return std::isinf(maxForce); }

// Σ_k L_ki x_k over the strictly lower column [first, last) of L, for one right-hand side, in
// four interleaved partial sums (DirectBlock::solveWithFactor): one running sum is a chain of
// dependent adds.
double backwardSum(const double* value, const int* rowOf, int first, int last, const double* x) {
  double sum[4] = {};
  int k = first;
  for (; k + 3 < last; k += 4)
    for (int j = 0; j < 4; ++j) sum[j] += value[k + j] * x[rowOf[k + j]];
  for (int j = 0; k < last; ++k, ++j) sum[j] += value[k] * x[rowOf[k]];
  return (sum[0] + sum[1]) + (sum[2] + sum[3]);
}

}  // namespace

DirectBlock::DirectBlock(std::vector<NodeRange> ranges) : m_ranges(std::move(ranges)) {
  for (const NodeRange& range : m_ranges) m_nodeCount += range.count;
}

size_t DirectBlock::blockBody(int32_t body) const {
  return static_cast<size_t>(std::find(m_bodies.begin(), m_bodies.end(), body) - m_bodies.begin());
}

int32_t DirectBlock::localNode(int32_t node) const {
  int32_t offset = 0;
  for (const NodeRange& range : m_ranges) {
    if (node >= range.first && node < range.first + range.count) return offset + node - range.first;
    offset += range.count;
  }
  return -1;
}

const DirectBlock::NodeRange& DirectBlock::rangeOf(int32_t node) const {
  for (const NodeRange& range : m_ranges)
    if (node >= range.first && node < range.first + range.count) return range;
  return m_ranges.front();
}

int32_t DirectBlock::globalNode(int32_t local) const {
  for (const NodeRange& range : m_ranges) {
    if (local < range.count) return range.first + local;
    local -= range.count;
  }
  return -1;
}

void DirectBlock::collectRows(const ConstraintRows& rows) {
  m_rows.clear();
  m_bodies.clear();
  auto ownsNode = [this](int32_t node) { return localNode(node) >= 0; };
  for (size_t i = 0; i < rows.fixedPoints.size(); ++i) {
    const FixedPointRow& row = rows.fixedPoints[i];
    if (!ownsNode(row.node) || !isUnbounded(row.maxForce)) continue;
    for (int32_t k = 0; k < 3; ++k) m_rows.push_back({RowType::FixedPoint, static_cast<int32_t>(i), k});
  }
  for (size_t i = 0; i < rows.anchors.size(); ++i) {
    const AnchorRow& row = rows.anchors[i];
    if (!ownsNode(row.node[0]) || !isUnbounded(row.maxForce)) continue;
    if (std::find(m_bodies.begin(), m_bodies.end(), row.body) == m_bodies.end()) m_bodies.push_back(row.body);
    for (int32_t k = 0; k < 3; ++k) m_rows.push_back({RowType::Anchor, static_cast<int32_t>(i), k});
  }
  for (size_t i = 0; i < rows.inextensibility.size(); ++i) {
    const InextensibilityRow& row = rows.inextensibility[i];
    const bool bilateral = std::isinf(row.lambdaMin) && std::isinf(row.lambdaMax) && row.lambdaMin < 0;
    if (!ownsNode(row.node[0]) || !bilateral) continue;
    m_rows.push_back({RowType::Inextensibility, static_cast<int32_t>(i), 0});
  }
  m_persistentRows = m_rows.size();
  m_persistentBodies = m_bodies.size();
}

void DirectBlock::addContacts(ConstraintRows& rows, std::span<const RigidSolverState> rigid, double slop) {
  m_rows.resize(m_persistentRows);
  m_bodies.resize(m_persistentBodies);
  // Contacts with rigid bodies only: two surfaces of deformables (or one folded on itself)
  // can be pressed into shapes their own rows do not allow, an infeasible set for a direct
  // solve; the PGS sweep handles those, with the last word in each iteration.
  // Touching, or pushing last step (its warm-start impulse): hysteresis, so a resting contact
  // whose gap hovers around the slop does not flip between the block and the sweep.
  auto joins = [&](const ContactRow& row) {
    const bool touching = row.gap <= slop || row.lambdaNormal > 0.0;
    if (row.body < 0 || !touching || row.normalMass == 0.0) return false;
    bool owned = true;
    for (int k = 0; k < 4; ++k) owned &= row.coefficient[k] == 0.0 || localNode(row.node[k]) >= 0;
    return owned;
  };
  // A block with no rows of its own (an FEM body alone) takes its contacts only while a dynamic
  // body rests on it: the FEM solve already holds its nodes on still surfaces, and the block
  // then costs nothing.
  if (m_persistentRows == 0 && std::none_of(rows.contacts.begin(), rows.contacts.end(), [&](const ContactRow& row) {
        return joins(row) && rigid[row.body].inverseMass > 0.0;
      }))
    return;
  size_t frictionContacts = 0;
  for (size_t i = 0; i < rows.contacts.size(); ++i) {
    ContactRow& row = rows.contacts[i];
    if (!joins(row)) continue;
    // A contact with a still surface let go before, and not sunk in since, stays with the sweep
    // (else a resting jelly's same contacts with its dish joined and were let go every step,
    // each refactorising the block). One with a moving body joins again: a box on a hammock
    // must be carried by the whole cloth. So does a rope's: a rope's block is cheap to factorise,
    // and with its wrap's contacts in the sweep and its edges in the block the two took the wrap
    // in turns, the contacts' warm starts kicking 0.2 g nodes at 5–12 m/s; a rope sliding round
    // a post at K = 4 then drove its nodes into the post at up to 51 m/s and tore (the gauntlet's
    // sliding capstan; docs/solver.md, thirty-second session).
    if (row.releasedLastStep && row.gap > -slop && rigid[row.body].inverseMass == 0.0 && !rangeOf(row.node[0]).chain) {
      row.releasedFromBlock = true;
      continue;
    }
    row.inDirectBlock = true;
    row.lambdaNormal = 0.0;
    const NodeRange& range = rangeOf(row.node[0]);
    const bool frictionInMetric = (range.chain || rigid[row.body].inverseMass > 0.0) && range.tied;  // see the header
    if (frictionInMetric && row.friction > 0.0 && frictionContacts < kMaxFrictionContacts) {
      row.frictionInBlock = true;
      row.lambdaTangent.setZero();  // solved afresh each step in the block's metric, like its rows
      ++frictionContacts;
    }
    if (std::find(m_bodies.begin(), m_bodies.end(), row.body) == m_bodies.end()) m_bodies.push_back(row.body);
    m_rows.push_back({RowType::Contact, static_cast<int32_t>(i), 0});
  }
}

void DirectBlock::claimRows(ConstraintRows& rows) const {
  for (const BlockRowRef& ref : m_rows) {
    switch (ref.type) {
      case RowType::FixedPoint: rows.fixedPoints[ref.index].inDirectBlock = true; break;
      case RowType::Anchor: rows.anchors[ref.index].inDirectBlock = true; break;
      case RowType::Inextensibility: rows.inextensibility[ref.index].inDirectBlock = true; break;
      default: break;
    }
  }
}

void DirectBlock::prepare(const ConstraintRows& rows, const NodeArrays& nodes,
                          std::span<const RigidSolverState> rigid, double timeStep,
                          std::span<const NodePairStiffness> elastic) {
  const bool factorKept = m_factorOk && m_factorReusable;
  m_stepRhsScale = 0.0;
  m_factorOk = false;
  if (m_rows.empty()) return;  // nothing to solve this step
  // Degrees of freedom: free nodes, then dynamic awake bodies.
  m_nodeDof.assign(m_nodeCount, -1);
  m_dofCount = 0;
  for (int32_t n = 0; n < m_nodeCount; ++n)
    if (nodes.inverseMass[globalNode(n)] > 0) {
      m_nodeDof[n] = m_dofCount;
      m_dofCount += 3;
    }
  // A body's degrees of freedom are the directions its joints to the world leave free: six for
  // a free body, one for a wheel on an axle (see RigidSolverState), with velocity G q̇.
  m_bodyDof.assign(m_bodies.size(), -1);
  m_bodyMotion.resize(m_bodies.size());
  for (size_t b = 0; b < m_bodies.size(); ++b) {
    const RigidSolverState& body = rigid[m_bodies[b]];
    BodyMotion& motion = m_bodyMotion[b];
    motion.freedoms = body.inverseMass > 0 ? body.freedoms : 0;
    if (motion.freedoms == 0) continue;
    if (body.isJointed()) {
      motion.basis = body.motionBasis;
      motion.inverseMass = body.reducedInverseMass;
    } else {
      motion.basis.setIdentity();
      motion.inverseMass.setZero();
      motion.inverseMass.topLeftCorner<3, 3>() = body.inverseMass * Mat3::Identity();
      motion.inverseMass.bottomRightCorner<3, 3>() = body.inverseInertia;
    }
    m_bodyDof[b] = m_dofCount;
    m_dofCount += motion.freedoms;
  }
  auto nodeDof = [&](int32_t node) { return m_nodeDof[localNode(node)]; };

  const int32_t rowCount = scalarRowCount();
  // The KKT matrix's entries, built in place (the vectors keep their capacity from step to step).
  std::vector<Eigen::Triplet<double>>& entries = m_entries;
  entries.clear();

  // H = M + h² K_g + h² K_e
  for (int32_t n = 0; n < m_nodeCount; ++n) {
    if (m_nodeDof[n] < 0) continue;
    const double mass = 1.0 / nodes.inverseMass[globalNode(n)];
    for (int32_t c = 0; c < 3; ++c) entries.emplace_back(m_nodeDof[n] + c, m_nodeDof[n] + c, mass);
  }
  for (size_t b = 0; b < m_bodies.size(); ++b) {
    if (m_bodyDof[b] < 0) continue;
    const int k = m_bodyMotion[b].freedoms;
    const Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, 6, 6> mass =
        m_bodyMotion[b].inverseMass.topLeftCorner(k, k).inverse();  // Gᵀ 𝕄 G
    for (int r = 0; r < k; ++r)
      for (int c = 0; c < k; ++c)
        if (mass(r, c) != 0.0) entries.emplace_back(m_bodyDof[b] + r, m_bodyDof[b] + c, mass(r, c));
  }
  const size_t stiffnessBegin = entries.size();
  auto addStiffness = [&](int32_t dofA, int32_t dofB, const Mat3& k) {
    if (dofA < 0 || dofB < 0) return;
    for (int32_t r = 0; r < 3; ++r)
      for (int32_t c = 0; c < 3; ++c) entries.emplace_back(dofA + r, dofB + c, k(r, c));
  };
  // Every edge gets its entries, zero when slack, so the sparsity pattern stays the same from
  // step to step and the ordering and symbolic analysis are done once.
  for (const BlockRowRef& ref : m_rows) {
    if (ref.type != RowType::Inextensibility) continue;
    const InextensibilityRow& row = rows.inextensibility[ref.index];
    const bool taut = row.lambda < 0 && row.effectiveMass != 0.0;
    const Vec3 n = row.jacobian[1];
    // In surfaces and solids, bounded at kMaxStiffnessToMass times the lighter node's mass:
    // enough to hold the sideways modes still, and it keeps the huge impulses redundant rows can
    // carry (a cloth's over-determined rows absorb small inconsistencies in their errors as a
    // null-space impulse that moves nothing) from turning into a huge stiffness. A chain's rows
    // are not redundant, and its stiffness must be whole: a 500 kg box on 1 g nodes needs
    // 3,000 times the bound, or the rope's nodes, free to move sideways to first order on a
    // straight rope, whip round and tear it (heavy pendulum, docs/solver.md).
    const double lighter = 1.0 / std::max(nodes.inverseMass[row.node[0]], nodes.inverseMass[row.node[1]]);
    const double tension = timeStep * -row.lambda / row.restLength;
    const double stiffness = rangeOf(row.node[0]).chain ? tension : std::min(tension, kMaxStiffnessToMass * lighter);
    const Mat3 g = taut ? Mat3(stiffness * (Mat3::Identity() - n * n.transpose())) : Mat3::Zero();
    const std::array<int32_t, 2> dof{nodeDof(row.node[0]), nodeDof(row.node[1])};
    for (int a = 0; a < 2; ++a)
      for (int b = 0; b < 2; ++b) addStiffness(dof[a], dof[b], a == b ? g : Mat3(-g));
  }
  for (const NodePairStiffness& pair : elastic) {
    const int32_t a = localNode(pair.nodeA), b = localNode(pair.nodeB);
    if (a >= 0 && b >= 0) addStiffness(m_nodeDof[a], m_nodeDof[b], pair.k);
  }
  m_stiffnessAssembly.assemble(std::span(entries).subspan(stiffnessBegin), m_dofCount, m_dofCount, m_stiffness);

  // J and Jᵀ, and the compliance −E. Row r of the KKT system is m_dofCount + r.
  std::vector<Eigen::Triplet<double>>& transposed = m_jacobianTEntries;
  transposed.clear();
  m_bias.resize(rowCount);
  m_compliance.resize(rowCount);
  m_active.assign(rowCount, false);
  m_rowEntries.assign(rowCount, {0, 0});
  m_released.assign(rowCount, false);
  m_releasedRows.clear();
  for (int32_t r = 0; r < rowCount; ++r) {
    const int32_t kktRow = m_dofCount + r;
    m_rowEntries[r].first = entries.size();
    double inverseMassSum = 0.0;
    auto add = [&](int32_t dof, const Vec3& j, double inverseMass) {
      if (dof < 0) return;
      for (int32_t c = 0; c < 3; ++c) {
        entries.emplace_back(kktRow, dof + c, j[c]);
        entries.emplace_back(dof + c, kktRow, j[c]);
        transposed.emplace_back(dof + c, r, j[c]);
      }
      inverseMassSum += inverseMass * j.squaredNorm();
    };
    // The rigid entry of a row along `axis` at `offset`: −axis linear, axis × offset angular,
    // in the body's free directions, Gᵀ (−axis, axis × offset).
    auto addRigid = [&](int32_t body, const Vec3& axis, const Vec3& offset) {
      const size_t b = blockBody(body);
      inverseMassSum += axis.dot(rigid[body].pointCompliance(offset) * axis);
      if (m_bodyDof[b] < 0) return;
      const Vec6 entry = m_bodyMotion[b].generalisedImpulse(-axis, offset);
      for (int c = 0; c < m_bodyMotion[b].freedoms; ++c) {
        if (entry[c] == 0.0) continue;
        entries.emplace_back(kktRow, m_bodyDof[b] + c, entry[c]);
        entries.emplace_back(m_bodyDof[b] + c, kktRow, entry[c]);
        transposed.emplace_back(m_bodyDof[b] + c, r, entry[c]);
      }
    };
    const BlockRowRef& ref = m_rows[r];
    switch (ref.type) {
      case RowType::FixedPoint: {
        const FixedPointRow& row = rows.fixedPoints[ref.index];
        add(nodeDof(row.node), Vec3::Unit(ref.component), nodes.inverseMass[row.node]);
        m_bias[r] = row.bias[ref.component];
        break;
      }
      case RowType::Anchor: {
        const AnchorRow& row = rows.anchors[ref.index];
        const Vec3 axis = Vec3::Unit(ref.component);
        for (int k = 0; k < 4; ++k)
          if (row.weight[k] != 0.0) add(nodeDof(row.node[k]), row.weight[k] * axis, nodes.inverseMass[row.node[k]]);
        addRigid(row.body, axis, row.offset);
        m_bias[r] = row.bias[ref.component];
        break;
      }
      case RowType::Contact: {
        const ContactRow& row = rows.contacts[ref.index];
        const Vec3& axis = row.normal;
        for (int k = 0; k < 4; ++k)
          if (row.coefficient[k] != 0.0)
            add(nodeDof(row.node[k]), row.coefficient[k] * axis, nodes.inverseMass[row.node[k]]);
        if (row.body >= 0) addRigid(row.body, axis, row.offset);
        m_bias[r] = row.bias;
        break;
      }
      case RowType::Inextensibility: {
        const InextensibilityRow& row = rows.inextensibility[ref.index];
        if (row.effectiveMass != 0.0) {
          add(nodeDof(row.node[0]), row.jacobian[0], nodes.inverseMass[row.node[0]]);
          add(nodeDof(row.node[1]), row.jacobian[1], nodes.inverseMass[row.node[1]]);
        }
        m_bias[r] = row.bias;
        break;
      }
      default: break;
    }
    // A row that touches nothing movable is left out: unit compliance, zero right-hand side.
    m_active[r] = inverseMassSum > 0.0;
    m_compliance[r] = m_active[r] ? kRelativeCompliance * inverseMassSum : 1.0;
    entries.emplace_back(kktRow, kktRow, -m_compliance[r]);
    m_rowEntries[r].second = entries.size();  // the diagonal is the last
  }

  m_jacobianTAssembly.assemble(transposed, m_dofCount, rowCount, m_jacobianT);
  m_inverseMass.resize(m_dofCount);
  for (int32_t n = 0; n < m_nodeCount; ++n)
    if (m_nodeDof[n] >= 0) m_inverseMass.segment<3>(m_nodeDof[n]).setConstant(nodes.inverseMass[globalNode(n)]);

  // Its projection moves the bodies its anchors hold (projectPositions) unless some body it
  // touches moves: a contact row of the block, or any of this step's contacts between its nodes
  // and a dynamic body (a body moved by position would drag the rope along that body's surface,
  // which the contact holds by velocity only: the rope over the wheel's light load crept 1.5 mm/s
  // instead of 0.4, its soak test).
  // A block that moves bodies by position is factorised afresh in every step:
  // its body turns the chain a little each step, and a kept factorisation refined against the
  // current matrix passed the residual test (in velocities, over each diagonal: small where the
  // chain's tension dominates H) while its solution kinked a heavy pendulum's rope at the body
  // (its end node turned 0.6 m/s across the rope in one step, then the step diverged;
  // docs/solver.md, twenty-seventh session). Such a block is a rope and a few bodies: cheap.
  m_movesBodies = std::any_of(m_bodyDof.begin(), m_bodyDof.end(), [](int32_t dof) { return dof >= 0; }) &&
                  std::none_of(m_rows.begin(), m_rows.end(), [](const BlockRowRef& ref) { return ref.type == RowType::Contact; }) &&
                  std::none_of(rows.contacts.begin(), rows.contacts.end(), [&](const ContactRow& contact) {
                    return contact.body >= 0 && rigid[contact.body].inverseMass > 0.0 && localNode(contact.node[0]) >= 0;
                  });
  m_factorOk = factorKept;
  factorise(!m_movesBodies, true);
  // The unit responses' storage, so that a step with a kept factorisation allocates nothing: it
  // changes size only with the pattern, in a step that factorises anyway.
  if (std::any_of(m_rows.begin(), m_rows.end(), [&](const BlockRowRef& ref) {
        return ref.type == RowType::Contact && rows.contacts[ref.index].frictionInBlock;
      })) {
    const Eigen::Index size = m_dofCount + rowCount;
    m_unitResponses.resize(size, kMaxUnitResponses);
    m_releaseRhs.reserve(static_cast<size_t>(size * kMaxUnitResponses));
    m_unitColumnOfDof.reserve(static_cast<size_t>(m_dofCount));
    m_unitMissing.reserve(static_cast<size_t>(kMaxUnitResponses));
    m_unitWeights.reserve(2 * kMaxFrictionContacts * 18);  // two tangents, four nodes and six body freedoms
  }
}

void DirectBlock::factorise(bool mayKeep, bool reusable) {
  const Eigen::Index size = m_dofCount + scalarRowCount();
  const bool placed = m_kktAssembly.assemble(m_entries, size, size, m_kkt);
  m_releasedRows.clear();  // in the matrix now
  m_frictionStale = true;
  // The ordering and symbolic factorisation are redone only when the sparsity pattern changes
  // (pinned nodes, movable bodies, the contacts in the block).
  const std::span<const int> outer(m_kkt.outerIndexPtr(), static_cast<size_t>(m_kkt.outerSize()) + 1);
  const std::span<const int> inner(m_kkt.innerIndexPtr(), static_cast<size_t>(m_kkt.nonZeros()));
  const bool newPattern = placed && (!std::ranges::equal(outer, m_analysedOuter) || !std::ranges::equal(inner, m_analysedInner));
  if (newPattern) {
    m_factor->analyzePattern(m_kkt);
    m_analysedOuter.assign(outer.begin(), outer.end());
    m_analysedInner.assign(inner.begin(), inner.end());
  }
  if (mayKeep && m_factorOk && !newPattern) {
    m_factorFresh = false;
    return;
  }
  m_factor->factorize(m_kkt);
  ++m_factorGeneration;
  m_cachedRows.clear();
  m_keptRefinements = 1;
  m_factorOk = m_factor->info() == Eigen::Success;
  m_inverseDiagonal = m_factor->vectorD().cwiseInverse();  // vectorD() returns a copy
  m_factorFresh = true;
  m_factorReusable = reusable;
  ++m_factorisations;
}

void DirectBlock::residual(const Eigen::VectorXd& rhs, const Eigen::VectorXd& z, Eigen::VectorXd& out) const {
  out.noalias() = m_kkt.selfadjointView<Eigen::Lower>() * z;
  out = rhs - out;
  for (int32_t r = 0; r < scalarRowCount(); ++r) {
    const Eigen::Index k = m_dofCount + r;
    if (m_released[r]) out[k] = 0.0;
    else if (m_active[r]) out[k] -= m_compliance[r] * z[k];
  }
}

void DirectBlock::refineWithKeptFactor(const Eigen::VectorXd& rhs, Eigen::VectorXd& z) {
  for (int step = 0; step < m_keptRefinements; ++step) {
    residual(rhs, z, m_residual);
    solveKkt(m_residual, m_refinement);
    z += m_refinement;
  }
}

// Residuals in velocities: a degree of freedom's over its diagonal H_ii (the first entry of its
// column in the lower triangle), a row's as it is.
double DirectBlock::scaledNorm(const Eigen::VectorXd& v) const {
  const int* outer = m_kkt.outerIndexPtr();
  const int* inner = m_kkt.innerIndexPtr();
  const double* value = m_kkt.valuePtr();
  double largest = 0.0;
  for (Eigen::Index j = 0; j < v.size(); ++j) {
    const bool scaled = j < m_dofCount && outer[j] < outer[j + 1] && inner[outer[j]] == j && value[outer[j]] > 0.0;
    largest = std::max(largest, std::abs(scaled ? v[j] * (1.0 / value[outer[j]]) : v[j]));
  }
  return largest;
}

// A released row's equation is dropped. In the matrix, it keeps its place in the pattern with
// zero entries and a unit diagonal, for the next factorisation. Until then, the system solved is
// the factorised one, A z = b + Σ_R μ_r e_r, with the multipliers μ chosen so that z_r = 0 on the
// released rows R (its λ then stays as prescribed, its column carries nothing): with
// C = A⁻¹ E_R (one solve per released row, kept), z = A⁻¹ b + C μ and (C_RR) μ = −(A⁻¹ b)_R,
// a small dense solve per solve instead of a refactorisation per round of releases. Past
// kLowRankReleases rows the columns would cost more than a factorisation, which is redone.
void DirectBlock::release(const std::vector<int32_t>& released) {
  m_frictionStale = true;
  for (int32_t row : released) {
    m_released[row] = true;
    for (size_t e = m_rowEntries[row].first; e + 1 < m_rowEntries[row].second; ++e)
      m_entries[e] = Eigen::Triplet<double>(m_entries[e].row(), m_entries[e].col(), 0.0);
    const size_t diagonal = m_rowEntries[row].second - 1;
    m_entries[diagonal] = Eigen::Triplet<double>(m_entries[diagonal].row(), m_entries[diagonal].col(), -1.0);
  }
  const auto count = static_cast<Eigen::Index>(m_releasedRows.size() + released.size());
  if (count > kLowRankReleases) {
    factorise(false, false);
    return;
  }
  const Eigen::Index size = m_dofCount + scalarRowCount();
  if (m_releasedColumns.rows() != size) m_releasedColumns.resize(size, kLowRankReleases);
  if (m_cachedColumns.rows() != size) {
    m_cachedColumns.resize(size, kLowRankReleases);
    m_cachedRows.clear();
  }
  // The columns not cached, solved together (each comes out as it would alone) and cached.
  auto cachedColumn = [&](Eigen::Index row) {
    return static_cast<Eigen::Index>(std::find(m_cachedRows.begin(), m_cachedRows.end(), row) - m_cachedRows.begin());
  };
  m_uncached.clear();
  for (int32_t row : released)
    if (cachedColumn(m_dofCount + row) == static_cast<Eigen::Index>(m_cachedRows.size())) m_uncached.push_back(m_dofCount + row);
  if (m_cachedRows.size() + m_uncached.size() > static_cast<size_t>(kLowRankReleases)) {  // full: start it again
    m_cachedRows.clear();
    m_uncached.clear();
    for (int32_t row : released) m_uncached.push_back(m_dofCount + row);
  }
  solveUnitColumns(m_uncached, m_cachedColumns, static_cast<Eigen::Index>(m_cachedRows.size()));
  m_cachedRows.insert(m_cachedRows.end(), m_uncached.begin(), m_uncached.end());
  for (int32_t row : released) {
    m_releasedColumns.col(static_cast<Eigen::Index>(m_releasedRows.size())) = m_cachedColumns.col(cachedColumn(m_dofCount + row));
    m_releasedRows.push_back(m_dofCount + row);
  }
  m_releasedCouplingMatrix.resize(count, count);
  for (Eigen::Index i = 0; i < count; ++i)
    m_releasedCouplingMatrix.row(i) = m_releasedColumns.row(m_releasedRows[i]).head(count);
  m_releasedCoupling.compute(m_releasedCouplingMatrix);
}

void DirectBlock::solveKkt(const Eigen::VectorXd& rhs, Eigen::VectorXd& z) const {
  z.resize(rhs.size());
  solveWithFactor(rhs.data(), z.data(), 1);
  dropReleasedEquations(z);
}

// z + C μ with C_RR μ = −z_R: the released rows' equations dropped (see release()).
void DirectBlock::dropReleasedEquations(Eigen::VectorXd& z) const {
  if (m_releasedRows.empty()) return;
  const auto count = static_cast<Eigen::Index>(m_releasedRows.size());
  m_atReleased.resize(count);
  for (Eigen::Index i = 0; i < count; ++i) m_atReleased[i] = -z[m_releasedRows[static_cast<size_t>(i)]];
  m_releasedMultipliers = m_releasedCoupling.solve(m_atReleased);
  z.noalias() += m_releasedColumns.leftCols(count) * m_releasedMultipliers;
}

// The factorisation P A Pᵀ = L D Lᵀ solved as Eigen's SimplicialLDLT::solve does (x ← P x,
// L y = x, D⁻¹, Lᵀ, Pᵀ), for `width` right-hand sides side by side (row-major), row by row
// across them so that each entry of the factor is read once for all. A row of the forward pass
// that is zero in every column (a unit or a contact's impulse touches a few) is skipped. The
// backward pass sums each row's products in four interleaved partial sums: one running sum is a
// chain of dependent adds, which made that pass, not memory, the solve's cost.
void DirectBlock::solveWithFactor(const double* in, double* out, Eigen::Index width) const {
  const Eigen::Index size = m_inverseDiagonal.size();
  const auto& permutation = m_factor->permutationP().indices();
  const auto& inverse = m_factor->permutationPinv().indices();
  const SparseMatrix& lower = m_factor->matrixL().nestedExpression();  // strictly lower, by columns
  const int* columnStart = lower.outerIndexPtr();
  const int* rowOf = lower.innerIndexPtr();
  const double* value = lower.valuePtr();
  m_permuted.resize(static_cast<size_t>(size * width));
  double* const data = m_permuted.data();
  for (Eigen::Index i = 0; i < size; ++i) std::copy_n(in + i * width, width, data + Eigen::Index{permutation[i]} * width);
  for (Eigen::Index i = 0; i < size; ++i) {
    const double* const xi = data + i * width;
    if (std::all_of(xi, xi + width, [](double v) { return v == 0.0; })) continue;
    for (int k = columnStart[i]; k < columnStart[i + 1]; ++k) {
      double* const xk = data + Eigen::Index{rowOf[k]} * width;
      for (Eigen::Index c = 0; c < width; ++c) xk[c] -= value[k] * xi[c];
    }
  }
  for (Eigen::Index i = 0; i < size; ++i)
    for (Eigen::Index c = 0; c < width; ++c) data[i * width + c] *= m_inverseDiagonal[i];
  // Backward. One right-hand side: its four partial sums in registers. Many: one pass over each
  // row's entries for all of them, the four partial sums per column in memory (a pass per group
  // of columns read the factor again for each group and was slower on the rope's wide blocks).
  // Every column sums its products in the same order either way.
  if (width == 1) {
    for (Eigen::Index i = size - 1; i >= 0; --i)
      data[i] -= backwardSum(value, rowOf, columnStart[i], columnStart[i + 1], data);
  } else {
    m_partialSums.resize(static_cast<size_t>(4 * width));
    double* const sums = m_partialSums.data();
    for (Eigen::Index i = size - 1; i >= 0; --i) {
      std::fill_n(sums, 4 * width, 0.0);
      for (int k = columnStart[i]; k < columnStart[i + 1]; ++k) {
        const double* const xk = data + Eigen::Index{rowOf[k]} * width;
        double* const sum = sums + ((k - columnStart[i]) & 3) * width;
        for (Eigen::Index c = 0; c < width; ++c) sum[c] += value[k] * xk[c];
      }
      double* const xi = data + i * width;
      for (Eigen::Index c = 0; c < width; ++c)
        xi[c] -= (sums[c] + sums[width + c]) + (sums[2 * width + c] + sums[3 * width + c]);
    }
  }
  for (Eigen::Index i = 0; i < size; ++i) std::copy_n(data + i * width, width, out + Eigen::Index{inverse[i]} * width);
}

// F⁻¹ e_i for each KKT index i in `at`, solved together (each comes out as it would alone), into
// the columns of `target` from `first` on.
template <typename Target>
void DirectBlock::solveUnitColumns(const std::vector<Eigen::Index>& at, Target& target, Eigen::Index first) {
  const Eigen::Index size = m_dofCount + scalarRowCount();
  const auto width = static_cast<Eigen::Index>(at.size());
  if (width == 0) return;
  m_releaseRhs.assign(static_cast<size_t>(size * width), 0.0);
  for (Eigen::Index i = 0; i < width; ++i) m_releaseRhs[static_cast<size_t>(at[i] * width + i)] = 1.0;
  solveWithFactor(m_releaseRhs.data(), m_releaseRhs.data(), width);
  for (Eigen::Index i = 0; i < width; ++i)
    for (Eigen::Index k = 0; k < size; ++k) target(k, first + i) = m_releaseRhs[static_cast<size_t>(k * width + i)];
}

// The same for many right-hand sides at once, in place; each column comes out as solveKkt's to
// the bit.
void DirectBlock::solveKktColumns(ColumnBlock& x, bool withReleased) const {
  solveWithFactor(x.data(), x.data(), x.cols());
  if (withReleased) dropReleasedEquations(x);
}

void DirectBlock::dropReleasedEquations(ColumnBlock& x) const {
  if (m_releasedRows.empty()) return;
  for (Eigen::Index c = 0; c < x.cols(); ++c) {  // as solveKkt, a column at a time
    m_column = x.col(c);
    dropReleasedEquations(m_column);
    x.col(c) = m_column;
  }
}

// The largest relative length error of the block's inextensible edges.
double DirectBlock::worstEdgeError(const ConstraintRows& rows, const NodeArrays& nodes) const {
  double worst = 0.0;
  for (const BlockRowRef& ref : m_rows) {
    if (ref.type != RowType::Inextensibility) continue;
    const InextensibilityRow& row = rows.inextensibility[ref.index];
    const double error = inextensibilityError(nodes.position[row.node[0]], nodes.position[row.node[1]], row.restLength);
    worst = std::max(worst, std::abs(error) / row.restLength);
  }
  return worst;
}

bool DirectBlock::restsOnDeformable(const ConstraintRows& rows) const {
  return std::any_of(rows.contacts.begin(), rows.contacts.end(), [&](const ContactRow& row) {
    if (row.body >= 0 || !(row.stepNormalImpulse > 0.0)) return false;
    for (int k = 0; k < 4; ++k)
      if (row.coefficient[k] != 0.0 && localNode(row.node[k]) >= 0) return true;
    return false;
  });
}

bool DirectBlock::projectPositions(const ConstraintRows& rows, NodeArrays& nodes, std::span<const RigidPose> poses,
                                   std::vector<BodyMove>& bodyMoves) {
  if (m_rows.empty() || !m_factorOk) return false;
  // The solve moves the block's dynamic bodies too: held by anchors, they move with the nodes, and
  // a heavy body on a light rope is put back where the rope reaches, which the rope's nodes alone
  // cannot do (the strain-limiting passes hold a body's anchored node, so a rope between a pin and
  // a 500 kg body swinging at 3 m/s stayed 1.66 % long). A block touching a moving body through
  // contacts is left to the velocity-level correction and the passes (m_movesBodies, prepare).
  if (!m_movesBodies && std::any_of(m_bodyDof.begin(), m_bodyDof.end(), [](int32_t dof) { return dof >= 0; })) return false;
  // Where it moves bodies, an edge is brought back only to within kProjectionBand of its length,
  // and edges inside the band keep theirs. The velocity rows, taking J at the step's start, turn
  // kinetic energy into stretch each step (h² v² / 2L of it for a pendulum: their projection
  // removes the centripetal part of the velocity); the rows' Baumgarte bias gives most of it back
  // in the next steps, and a projection of the whole stretch throws it away: a free rope
  // pendulum kept 0.914 of its energy at n = 4 instead of 0.987, 0.694 instead of 0.854 at n = 1
  // (a point pendulum stepped the same two ways measures 0.903 and 0.696: docs/solver.md).
  const double band = m_movesBodies ? kProjectionBand : 0.0;
  // A block of ropes closes its anchors' gaps too (a rope on a swinging hinged bar kept its
  // anchor to the bar 2.5 cm open, left to the bias). A surface's stay as they are: a sheet
  // anchored along a rod is nearly singular for its linearised rows, and closing them by position
  // crumpled the curtain scene (1,691 rows violated over 10 s, five times its contacts, where
  // there were none).
  const bool closesAnchors = std::all_of(m_ranges.begin(), m_ranges.end(), [](const NodeRange& range) { return range.chain; });
  const bool kept = m_movesBodies || closesAnchors;
  // Nor is a sheet projected while it rests on itself or on another deformable: the projection
  // does not see those contacts (they are not the block's rows), and its Newton step pulled a
  // fold's nodes through the faces they lay on, every step: a strip folded on the ground ended
  // with an edge 16 % long and three impact zones moving 36 of its 119 nodes rigidly at rest
  // (scenes/self_collision.json). The strain-limiting passes take such a sheet, a pass at a time.
  if (!kept && restsOnDeformable(rows)) return false;
  const int32_t rowCount = scalarRowCount();
  m_rhs.setZero(m_dofCount + rowCount);
  for (int32_t r = 0; r < rowCount; ++r) {
    if (!m_active[r] || m_released[r]) continue;
    const BlockRowRef& ref = m_rows[r];
    if (ref.type == RowType::FixedPoint) {
      const FixedPointRow& row = rows.fixedPoints[ref.index];
      m_rhs[m_dofCount + r] = -fixedPointError(nodes.position[row.node], row.target)[ref.component];
    } else if (ref.type == RowType::Inextensibility) {
      const InextensibilityRow& row = rows.inextensibility[ref.index];
      if (row.effectiveMass == 0.0) continue;
      const double error = inextensibilityError(nodes.position[row.node[0]], nodes.position[row.node[1]], row.restLength);
      const double allowed = band * row.restLength;
      m_rhs[m_dofCount + r] = -(error - std::clamp(error, -allowed, allowed));
    } else if (ref.type == RowType::Anchor && closesAnchors) {
      const AnchorRow& row = rows.anchors[ref.index];
      const RigidPose& pose = poses[row.body];
      m_rhs[m_dofCount + r] = -anchorError(row, nodes.position, pose.centerOfMass, pose.orientation)[ref.component];
    }
  }
  if (m_rhs.tail(rowCount).isZero(0.0)) return true;  // nothing outside the band
  solveKkt(m_rhs, m_solution);
  if (!m_factorFresh) refineWithKeptFactor(m_rhs, m_solution);  // as in solve()
  // Near a singular configuration (a taut flat sheet pinned at its corners) the linearised
  // rows are nearly redundant and a small error asks for a large step: no node moves further
  // than twice the largest error it is correcting. (Not where the block moves a body: a rope's
  // nodes near its body move by the sum of its edges' errors, as the body does.)
  const double largest = m_movesBodies ? INFINITY : 2.0 * m_rhs.tail(rowCount).cwiseAbs().maxCoeff();
  // A sheet's step is kept only if it leaves its worst edge better than it found it. One Newton
  // step with the step's start J is exact for a draped sheet, but where the sheet is nearly
  // singular it overshoots: on a 21 × 21 cloth pinned along its sides and sagging under its own
  // weight one step took the worst edge from 1.3 % to 2.0 %, and a cloth of grid edges hung by
  // its four corners (its hems straight between pins at their rest length) tore under such steps
  // at K = 2 (its worst edge 726 % long, nodes at 0.87 m/s RMS;
  // World.ClothHungByItsCornersKeepsItsEdges). A step that does not help
  // is undone and the sheet left to the strain-limiting passes, which converge there. (Ropes'
  // blocks keep every step: their chains are not singular, and a step that moves a body is not
  // undone by moving the nodes back.)
  const double worstBefore = kept ? 0.0 : worstEdgeError(rows, nodes);
  if (!kept) {
    m_positionsBefore.resize(static_cast<size_t>(m_nodeCount));
    for (int32_t n = 0; n < m_nodeCount; ++n) m_positionsBefore[n] = nodes.position[globalNode(n)];
  }
  for (int32_t n = 0; n < m_nodeCount; ++n) {
    if (m_nodeDof[n] < 0) continue;
    Vec3 step = m_solution.segment<3>(m_nodeDof[n]);
    if (step.norm() > largest) step *= largest / step.norm();
    nodes.position[globalNode(n)] += step;
  }
  if (!kept && worstEdgeError(rows, nodes) > worstBefore) {
    for (int32_t n = 0; n < m_nodeCount; ++n) nodes.position[globalNode(n)] = m_positionsBefore[n];
    return false;
  }
  for (size_t b = 0; b < m_bodies.size(); ++b) {
    if (m_bodyDof[b] < 0) continue;
    const int k = m_bodyMotion[b].freedoms;
    const Vec6 move = m_bodyMotion[b].basis.leftCols(k) * m_solution.segment(m_bodyDof[b], k);
    bodyMoves.push_back({m_bodies[b], move.head<3>(), move.tail<3>()});
  }
  return true;
}

// The anchors that hold a dynamic body keep last step's impulse: its body's share is applied now,
// before Bullet's first iteration, and its nodes' share waits for the block's first solve as a
// known load (H Δv = Jᵀ Δλ + f: their response is the block's, geometric stiffness included, not
// m⁻¹). Every other row of the block starts from zero, as the block is exact in one sweep.
void DirectBlock::startImpulses(ConstraintRows& rows, SolverContext& ctx) {
  m_pendingLoad.setZero(m_dofCount);
  m_loadPending = false;
  for (const BlockRowRef& ref : m_rows) {
    switch (ref.type) {
      case RowType::FixedPoint: rows.fixedPoints[ref.index].lambda[ref.component] = 0.0; break;
      case RowType::Anchor: {
        AnchorRow& row = rows.anchors[ref.index];
        const size_t b = blockBody(row.body);
        if (!m_factorOk || m_bodyDof[b] < 0) {
          row.lambda[ref.component] = 0.0;
          break;
        }
        const Vec3 impulse = row.lambda[ref.component] * Vec3::Unit(ref.component);
        ctx.rigid[row.body].applyImpulse(-impulse, row.offset);
        for (int k = 0; k < 4; ++k) {
          const int32_t dof = row.weight[k] != 0.0 ? m_nodeDof[localNode(row.node[k])] : -1;
          if (dof >= 0) m_pendingLoad.segment<3>(dof) += row.weight[k] * impulse;
        }
        m_loadPending = true;
        break;
      }
      case RowType::Inextensibility: rows.inextensibility[ref.index].lambda = 0.0; break;
      case RowType::Contact: rows.contacts[ref.index].lambdaNormal = 0.0; break;
      default: break;
    }
  }
}

double DirectBlock::rowVelocity(const ConstraintRows& rows, const BlockRowRef& ref, const SolverContext& ctx) const {
  switch (ref.type) {
    case RowType::FixedPoint: return ctx.velocity[rows.fixedPoints[ref.index].node][ref.component];
    case RowType::Anchor: {
      const AnchorRow& row = rows.anchors[ref.index];
      return (row.deformableVelocity(ctx.velocity) - ctx.rigid[row.body].velocityAt(row.offset))[ref.component];
    }
    case RowType::Inextensibility: {
      const InextensibilityRow& row = rows.inextensibility[ref.index];
      return row.jacobian[0].dot(ctx.velocity[row.node[0]]) + row.jacobian[1].dot(ctx.velocity[row.node[1]]);
    }
    case RowType::Contact: {
      const ContactRow& row = rows.contacts[ref.index];
      return row.normal.dot(contactRelativeVelocity(row, ctx));
    }
    default: return 0.0;
  }
}

void DirectBlock::solve(ConstraintRows& rows, SolverContext& ctx, SweepStats& stats) {
  if (m_rows.empty()) return;
  if (!m_factorOk) {  // the warm start's load still reaches the nodes, each by its own mass
    applyPendingLoad(ctx);
    return;
  }
  const int32_t rowCount = scalarRowCount();
  // Active set over the contacts: solve; a contact that would end up pulling is released (its
  // impulse so far taken back as a known load on the block) and the block solved again.
  // Rows released in an earlier sweep belong to the PGS sweep now and are left alone.
  std::vector<char>& releasedHere = m_releasedHere;
  releasedHere.assign(static_cast<size_t>(rowCount), 0);
  Eigen::VectorXd& prescribed = m_prescribed;  // Δλ = −λ so far, per row released here
  prescribed.setZero(rowCount);
  for (int round = 0;; ++round) {
    for (int32_t r = 0; r < rowCount; ++r)
      if (releasedHere[r]) prescribed[r] = -rows.contacts[m_rows[r].index].lambdaNormal;
    m_rhs.resize(m_dofCount + rowCount);
    m_rhs.head(m_dofCount).noalias() = m_jacobianT * prescribed;
    addReleasedFriction(rows, m_rhs);
    for (int32_t r = 0; r < rowCount; ++r)
      m_rhs[m_dofCount + r] = m_active[r] && !m_released[r] ? -(rowVelocity(rows, m_rows[r], ctx) + m_bias[r]) : 0.0;
    const double rhsScale = !m_factorFresh && round == 0 ? scaledNorm(m_rhs) : 0.0;  // the load is known: not in it
    if (m_loadPending) m_rhs.head(m_dofCount) += m_pendingLoad;
    // One step of iterative refinement: with this step's factorisation the first solve leaves
    // J(v + Δv) + b = E y, a residual of the compliance alone, and solving for it again removes
    // all but O(ε²) of it; with a kept one, the change of the matrix since as well (the header).
    auto refinedSolve = [&] {
      solveKkt(m_rhs, m_solution);
      if (!m_factorFresh) {
        refineWithKeptFactor(m_rhs, m_solution);
        return;
      }
      m_residual.setZero(m_rhs.size());
      for (int32_t r = 0; r < rowCount; ++r)
        if (m_active[r] && !m_released[r]) m_residual[m_dofCount + r] = -m_compliance[r] * m_solution[m_dofCount + r];
      solveKkt(m_residual, m_refinement);
      m_solution += m_refinement;
    };
    refinedSolve();
    if (!m_factorFresh && round == 0) {
      residual(m_rhs, m_solution, m_residual);
      // Measured against the step's largest right-hand side so far: a later sweep's is the small
      // error the sweeps in between left, and a residual small for the step is small enough.
      m_stepRhsScale = std::max(m_stepRhsScale, rhsScale);
      const double tolerance = kKeptFactorTolerance * m_stepRhsScale;
      // Still short: a second refinement step in each solve from here on (one solve; a
      // factorisation of the jelly dish's block costs about forty), else a new factorisation.
      double left = scaledNorm(m_residual);
      while (left > tolerance && m_keptRefinements < kMaxKeptRefinements) {
        ++m_keptRefinements;
        solveKkt(m_residual, m_refinement);
        m_solution += m_refinement;
        residual(m_rhs, m_solution, m_residual);
        left = scaledNorm(m_residual);
      }
      if (left > tolerance) {
        // Too far from this step's matrix: factorised afresh (kept next step only if no contact
        // has been let go yet) and solved again.
        factorise(false, std::none_of(m_released.begin(), m_released.end(), [](bool released) { return released; }));
        if (!m_factorOk) {
          applyPendingLoad(ctx);
          return;
        }
        refinedSolve();
      }
    }

    std::vector<int32_t>& released = m_releasedNow;
    released.clear();
    for (size_t r = m_persistentRows; r < m_rows.size(); ++r) {
      const double total = rows.contacts[m_rows[r].index].lambdaNormal - m_solution[m_dofCount + r];
      if (!m_released[r] && total < 0.0) released.push_back(static_cast<int32_t>(r));
    }
    // The last round's pulling contacts hold on through this solve (the next sweep's solve finds
    // them again): the impulses of every other row were solved with them holding, and letting
    // them go without solving again left those impulses unbalanced. In a box stack on a hammock
    // that threw 0.45 g nodes at 51 m/s and the boxes at 11 rad/s in one sweep.
    if (released.empty() || round == kMaxReleaseRounds) break;
    for (int32_t r : released) releasedHere[r] = 1;
    release(released);
  }
  // A released contact goes back to the PGS sweep, which may still push with it.
  m_velocityChange.setZero(m_dofCount);
  if (m_loadPending) m_velocityChange += m_pendingLoad;
  m_loadPending = false;
  addReleasedFriction(rows, m_velocityChange);  // before its friction is the sweep's (below)
  for (size_t r = m_persistentRows; r < m_rows.size(); ++r)
    if (releasedHere[r] && rows.contacts[m_rows[r].index].frictionInBlock) {
      ContactRow& row = rows.contacts[m_rows[r].index];
      if (row.body >= 0) {  // the taken-back friction's share of the body's impulse, for the report
        const Vec3 onBody = row.lambdaTangent[0] * row.tangent1 + row.lambdaTangent[1] * row.tangent2;
        ctx.rigid[row.body].impulse += onBody;
        ctx.rigid[row.body].angularImpulse += row.offset.cross(onBody);
      }
      row.lambdaTangent.setZero();
    }
  for (size_t r = m_persistentRows; r < m_rows.size(); ++r)
    if (m_released[r]) {
      rows.contacts[m_rows[r].index].inDirectBlock = false;
      rows.contacts[m_rows[r].index].frictionInBlock = false;
      rows.contacts[m_rows[r].index].releasedFromBlock = true;
    }
  for (int32_t r = 0; r < rowCount; ++r)
    if (m_released[r]) m_solution[m_dofCount + r] = releasedHere[r] ? -prescribed[r] : 0.0;

  // Velocities from the impulses, M Δv = Jᵀ Δλ − h² (K_g + K_e) Δv, with Δv in the stiffness
  // term taken from the solve: the stiffness forces cancel within each edge and element, so
  // momentum changes by exactly Jᵀ Δλ whatever the solve's rounding.
  Eigen::VectorXd& deltaLambda = m_rowImpulseChange;
  deltaLambda = -m_solution.tail(rowCount);
  m_velocityChange.noalias() += m_jacobianT * deltaLambda;
  m_velocityChange.noalias() -= m_stiffness * m_solution.head(m_dofCount);
  toVelocityChange(m_velocityChange);
  applyVelocityChange(m_velocityChange, ctx);
  addRowImpulses(rows, deltaLambda, ctx);
  for (int32_t r = 0; r < rowCount; ++r) stats.add(deltaLambda[r]);
}

// A contact let go in this solve whose friction the block solved takes that friction back in the
// block's metric, as a known load with its normal impulse: the block's friction pass moved the
// whole block with it, and the sweep, which owns the contact's friction from here on, would take
// it back on the contact's own nodes. On a 0.3 kg weight hung from one face of a 0.04 kg flag
// that was 0.55 N s off a 0.4 g node: 114 m/s in one sweep, the weight thrown up at 40 m/s
// (tests/data/flag_weight.json; docs/solver.md, twenty-eighth session).
void DirectBlock::addReleasedFriction(const ConstraintRows& rows, Eigen::VectorXd& onDofs) const {
  for (size_t r = m_persistentRows; r < m_rows.size(); ++r) {
    const ContactRow& row = rows.contacts[m_rows[r].index];
    if (!m_releasedHere[r] || !row.frictionInBlock || row.lambdaTangent.isZero()) continue;
    const Vec3 takenBack = -(row.lambdaTangent[0] * row.tangent1 + row.lambdaTangent[1] * row.tangent2);
    visitImpulseOnDofs(row, takenBack, [&](int32_t dof, const auto& entries) { onDofs.segment(dof, entries.size()) += entries; });
  }
}

void DirectBlock::applyPendingLoad(SolverContext& ctx) {
  if (!m_loadPending) return;
  m_velocityChange = m_pendingLoad;
  toVelocityChange(m_velocityChange);
  applyVelocityChange(m_velocityChange, ctx);
  m_loadPending = false;
}

// Impulses on the block's degrees of freedom turned, in place, into the velocity changes they
// make: m⁻¹ per node, (Gᵀ 𝕄 G)⁻¹ per body.
void DirectBlock::toVelocityChange(Eigen::VectorXd& impulses) const {
  for (int32_t n = 0; n < m_nodeCount; ++n)
    if (m_nodeDof[n] >= 0) impulses.segment<3>(m_nodeDof[n]) *= m_inverseMass[m_nodeDof[n]];
  for (size_t b = 0; b < m_bodies.size(); ++b) {
    if (m_bodyDof[b] < 0) continue;
    const int k = m_bodyMotion[b].freedoms;
    const Eigen::Matrix<double, Eigen::Dynamic, 1, 0, 6, 1> generalised = impulses.segment(m_bodyDof[b], k);
    impulses.segment(m_bodyDof[b], k) = m_bodyMotion[b].inverseMass.topLeftCorner(k, k) * generalised;
  }
}

// A velocity change of the block's degrees of freedom added to its nodes and bodies.
void DirectBlock::applyVelocityChange(const Eigen::VectorXd& change, SolverContext& ctx) const {
  for (int32_t n = 0; n < m_nodeCount; ++n)
    if (m_nodeDof[n] >= 0) ctx.velocity[globalNode(n)] += change.segment<3>(m_nodeDof[n]);
  for (size_t b = 0; b < m_bodies.size(); ++b) {
    if (m_bodyDof[b] < 0) continue;
    RigidSolverState& body = ctx.rigid[m_bodies[b]];
    const int k = m_bodyMotion[b].freedoms;
    const Vec6 velocity = m_bodyMotion[b].basis.leftCols(k) * change.segment(m_bodyDof[b], k);
    body.linearVelocity += velocity.head<3>();
    body.angularVelocity += velocity.tail<3>();
  }
}

// Δλ added to the block's rows, and their rigid bodies' share to the per-body impulse report.
void DirectBlock::addRowImpulses(ConstraintRows& rows, const Eigen::VectorXd& deltaLambda, SolverContext& ctx) const {
  for (int32_t r = 0; r < scalarRowCount(); ++r) {
    const double delta = deltaLambda[r];
    const BlockRowRef& ref = m_rows[r];
    switch (ref.type) {
      case RowType::FixedPoint: rows.fixedPoints[ref.index].lambda[ref.component] += delta; break;
      case RowType::Anchor: {
        AnchorRow& row = rows.anchors[ref.index];
        row.lambda[ref.component] += delta;
        // The body's share of this row, for the per-body impulse report.
        RigidSolverState& body = ctx.rigid[row.body];
        const Vec3 impulse = -delta * Vec3::Unit(ref.component);
        body.impulse += impulse;
        body.angularImpulse += row.offset.cross(impulse);
        break;
      }
      case RowType::Inextensibility: rows.inextensibility[ref.index].lambda += delta; break;
      case RowType::Contact: {
        ContactRow& row = rows.contacts[ref.index];
        row.lambdaNormal += delta;
        if (row.body >= 0) {
          RigidSolverState& body = ctx.rigid[row.body];
          const Vec3 impulse = -delta * row.normal;
          body.impulse += impulse;
          body.angularImpulse += row.offset.cross(impulse);
        }
        break;
      }
      default: break;
    }
  }
}

template <typename Visit>
void DirectBlock::visitImpulseOnDofs(const ContactRow& row, const Vec3& axis, Visit&& visit) const {
  for (int k = 0; k < 4; ++k) {
    const int32_t local = localNode(row.node[k]);
    if (row.coefficient[k] != 0.0 && local >= 0 && m_nodeDof[local] >= 0)
      visit(m_nodeDof[local], Vec3(row.coefficient[k] * axis));
  }
  const size_t body = blockBody(row.body);
  if (row.body >= 0 && body < m_bodies.size() && m_bodyDof[body] >= 0) {
    const BodyMotion& motion = m_bodyMotion[body];
    const Eigen::Matrix<double, Eigen::Dynamic, 1, 0, 6, 1> generalised =
        motion.generalisedImpulse(-axis, row.offset).head(motion.freedoms);
    visit(m_bodyDof[body], generalised);
  }
}

void DirectBlock::writeImpulseOnDofs(const ContactRow& row, const Vec3& axis, ColumnBlock& target, Eigen::Index column) const {
  visitImpulseOnDofs(row, axis, [&](int32_t dof, const auto& entries) {
    target.col(column).segment(dof, entries.size()) += entries;
  });
}

void DirectBlock::computeFrictionResponses(const ConstraintRows& rows) {
  m_friction.clear();
  m_frictionStale = false;
  const int32_t rowCount = scalarRowCount();
  for (size_t r = m_persistentRows; r < m_rows.size(); ++r)
    if (rows.contacts[m_rows[r].index].frictionInBlock && !m_released[r]) {
      FrictionResponse& response = m_friction.emplace_back();
      response.row = static_cast<int32_t>(r);
      response.column = 2 * static_cast<Eigen::Index>(m_friction.size() - 1);
    }
  // The KKT solves with each contact's two unit tangential impulses f, all at once.
  const auto columns = 2 * static_cast<Eigen::Index>(m_friction.size());
  m_columns.setZero(m_dofCount + rowCount, columns);
  for (const FrictionResponse& response : m_friction) {
    const ContactRow& row = rows.contacts[m_rows[response.row].index];
    writeImpulseOnDofs(row, row.tangent1, m_columns, response.column);
    writeImpulseOnDofs(row, row.tangent2, m_columns, response.column + 1);
  }
  // With a kept factorisation these are the exact responses of the system it was made for, a few
  // steps old: no refinement step (see the header, "Friction in the block's metric").
  solveFrictionColumns(rows);
  // The solution's top is the velocity change Δv of the block's degrees of freedom (in a body's
  // free directions), its bottom −Δλ of the rows (a released row's, none).
  m_frictionImpulse = -m_columns.bottomRows(rowCount);
  for (int32_t q = 0; q < rowCount; ++q)
    if (m_released[q]) m_frictionImpulse.row(q).setZero();
  m_frictionVelocity = m_columns.topRows(m_dofCount);
  size_t kept = 0;
  for (const FrictionResponse& response : m_friction) {
    const ContactRow& row = rows.contacts[m_rows[response.row].index];
    Eigen::Matrix2d w = Eigen::Matrix2d::Zero();  // W = fₐᵀ Δv_b, fₐ the unit tangential impulses
    for (int a = 0; a < 2; ++a)
      visitImpulseOnDofs(row, a == 0 ? row.tangent1 : row.tangent2, [&](int32_t dof, const auto& entries) {
        for (int b = 0; b < 2; ++b)
          w(a, b) += entries.dot(m_frictionVelocity.col(response.column + b).segment(dof, entries.size()));
      });
    // A contact point that cannot slide relative to anything movable has no friction to solve.
    if (w.determinant() <= 1e-18 * std::max(1.0, w.squaredNorm())) continue;
    m_friction[kept] = response;
    m_friction[kept++].effectiveMass = w.inverse();
  }
  m_friction.resize(kept);
}

void DirectBlock::solveFriction(ConstraintRows& rows, SolverContext& ctx, FrictionModel model, SweepStats& stats) {
  if (m_rows.empty() || !m_factorOk) return;
  if (m_frictionStale) computeFrictionResponses(rows);
  for (const FrictionResponse& response : m_friction) {
    ContactRow& row = rows.contacts[m_rows[response.row].index];
    const Eigen::Vector2d previous = row.lambdaTangent;
    Eigen::Vector2d delta = frictionImpulse(row, model, response.effectiveMass, ctx) - previous;
    if (delta.isZero()) continue;
    // The block's contacts react to the friction impulse through their normal rows; none may be
    // left pulling (the block's active set only runs before this pass), so the step is shortened
    // to the largest that keeps every contact's λₙ ≥ 0.
    double fraction = 1.0;
    for (size_t q = m_persistentRows; q < m_rows.size(); ++q) {
      const double lambdaNormal = rows.contacts[m_rows[q].index].lambdaNormal;
      const auto k = static_cast<Eigen::Index>(q);
      const double change = delta[0] * m_frictionImpulse(k, response.column) + delta[1] * m_frictionImpulse(k, response.column + 1);
      if (change < 0.0 && lambdaNormal + fraction * change < 0.0) fraction = std::max(0.0, -lambdaNormal / change);
    }
    delta *= fraction;
    row.lambdaTangent = previous + delta;
    if (delta.isZero()) continue;
    // The whole block moves; a body outside it (a static or kinematic one) takes nothing.
    m_velocityChange = delta[0] * m_frictionVelocity.col(response.column) + delta[1] * m_frictionVelocity.col(response.column + 1);
    applyVelocityChange(m_velocityChange, ctx);
    if (row.body >= 0) {  // the friction's own share of the body's impulse, for the report
      const Vec3 onBody = -(delta[0] * row.tangent1 + delta[1] * row.tangent2);
      ctx.rigid[row.body].impulse += onBody;
      ctx.rigid[row.body].angularImpulse += row.offset.cross(onBody);
    }
    m_rowImpulseChange = delta[0] * m_frictionImpulse.col(response.column) + delta[1] * m_frictionImpulse.col(response.column + 1);
    addRowImpulses(rows, m_rowImpulseChange, ctx);
    stats.add(delta[0]);
    stats.add(delta[1]);
  }
}

void DirectBlock::solveFrictionColumns(const ConstraintRows& rows) {
  const Eigen::Index size = m_dofCount + scalarRowCount();
  if (m_columns.cols() == 0) return;
  // A fresh factorisation may not be kept: its friction columns are solved as they are.
  if (m_factorFresh || m_unitResponses.rows() != size) {
    solveKktColumns(m_columns, true);
    return;
  }
  if (m_unitGeneration != m_factorGeneration || m_unitColumnOfDof.size() != static_cast<size_t>(m_dofCount)) {
    m_unitGeneration = m_factorGeneration;  // units of an older F are of no use
    m_unitCount = 0;
    m_unitColumnOfDof.assign(static_cast<size_t>(m_dofCount), -1);
  }
  m_unitMissing.clear();
  for (const FrictionResponse& response : m_friction)
    visitImpulseOnDofs(rows.contacts[m_rows[response.row].index], Vec3::UnitX(), [&](int32_t dof, const auto& entries) {
      for (Eigen::Index i = dof; i < dof + entries.size(); ++i)
        if (m_unitColumnOfDof[static_cast<size_t>(i)] < 0 &&
            std::find(m_unitMissing.begin(), m_unitMissing.end(), i) == m_unitMissing.end())
          m_unitMissing.push_back(i);
    });
  const auto missing = static_cast<Eigen::Index>(m_unitMissing.size());
  if (m_unitCount + missing > kMaxUnitResponses) {
    solveKktColumns(m_columns, true);
    return;
  }
  solveUnitColumns(m_unitMissing, m_unitResponses, m_unitCount);
  for (Eigen::Index dof : m_unitMissing) m_unitColumnOfDof[static_cast<size_t>(dof)] = static_cast<int32_t>(m_unitCount++);
  // Each right-hand side in m_columns is a sum of units: F⁻¹ of it is the same sum of their columns.
  m_unitWeights.clear();
  for (const FrictionResponse& response : m_friction) {
    const ContactRow& row = rows.contacts[m_rows[response.row].index];
    for (int a = 0; a < 2; ++a)
      visitImpulseOnDofs(row, a == 0 ? row.tangent1 : row.tangent2, [&](int32_t dof, const auto& entries) {
        for (Eigen::Index i = 0; i < entries.size(); ++i)
          m_unitWeights.push_back({m_unitColumnOfDof[static_cast<size_t>(dof + i)], response.column + a, entries[i]});
      });
  }
  m_columns.setZero();
  for (Eigen::Index k = 0; k < size; ++k) {
    const double* unit = m_unitResponses.data() + k * kMaxUnitResponses;
    double* out = m_columns.data() + k * m_columns.cols();
    for (const UnitWeight& weight : m_unitWeights) out[weight.column] += weight.value * unit[weight.unit];
  }
  dropReleasedEquations(m_columns);
}

}  // namespace tandem
