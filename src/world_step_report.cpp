// World::Impl, stage 8: the rows left violated, and divergence. (src/world.cpp runs the stages in
// order; src/world_impl.h holds the state.)
#include "world_impl.h"

namespace tandem {

void World::Impl::reportViolatedRows() {
  report.violations.clear();
  for (size_t d = 0; d < deformables.size(); ++d) {
    const DeformableRecord& body = deformables[d];
    const auto inBody = [&](int32_t node) { return node >= body.firstNode && node < body.firstNode + body.nodeCount; };
    RowViolation worstAnchor{RowViolation::Kind::AnchorGap, -1, kAnchorGapWarning, {}};
    for (size_t a = 0; a < rows.anchors.size(); ++a) {
      const AnchorRow& row = rows.anchors[a];
      if (!inBody(row.node[0])) continue;
      const double gap = (row.deformablePoint(nodes.position) -
                          (bullet.position(row.body) + bullet.orientation(row.body) * row.localPoint)).norm();
      if (!(gap <= worstAnchor.value)) worstAnchor = {RowViolation::Kind::AnchorGap, static_cast<int>(a), gap, {}};
    }
    if (worstAnchor.index >= 0) {
      const AnchorRow& row = rows.anchors[worstAnchor.index];
      worstAnchor.message = "anchor " + std::to_string(worstAnchor.index) + " of deformable '" + body.name +
                            "' to rigid body '" + rigidNames[row.body] + "' is " + formatNumber(worstAnchor.value) +
                            " m apart";
      report.violations.push_back(std::move(worstAnchor));
    }
    RowViolation worstEdge{RowViolation::Kind::EdgeStretch, -1, kEdgeStretchWarning, {}};
    int edge = 0;
    for (const InextensibilityRow& row : rows.inextensibility) {
      if (!inBody(row.node[0])) continue;
      const double strain = (nodes.position[row.node[1]] - nodes.position[row.node[0]]).norm() / row.restLength - 1.0;
      if (!(strain <= worstEdge.value)) worstEdge = {RowViolation::Kind::EdgeStretch, edge, strain, {}};
      ++edge;
    }
    if (worstEdge.index >= 0) {
      worstEdge.message = "inextensible edge " + std::to_string(worstEdge.index) + " of deformable '" + body.name +
                          "' is stretched " + formatNumber(100.0 * worstEdge.value) + " %";
      report.violations.push_back(std::move(worstEdge));
    }
  }
}

Status World::Impl::checkDiverged() const {
  const double limit = settings.divergenceSpeed;
  auto bad = [limit](const Vec3& x, const Vec3& v) { return !x.allFinite() || !v.allFinite() || v.norm() > limit; };
  const char* const advice = ": the simulation diverged (try a smaller time step, more iterations or softer springs)";
  for (const DeformableRecord& body : deformables)
    for (int32_t i = 0; i < body.nodeCount; ++i) {
      const int32_t n = body.firstNode + i;
      if (bad(nodes.position[n], nodes.velocity[n]))
        return Error{"step " + std::to_string(steps) + ": deformable '" + body.name + "' node " + std::to_string(i) +
                     " has a non-finite or faster than " + formatNumber(limit) + " m/s state" + advice};
    }
  for (int b = 0; b < bullet.rigidBodyCount(); ++b)
    if (bad(bullet.position(b), bullet.linearVelocity(b)) || !bullet.angularVelocity(b).allFinite())
      return Error{"step " + std::to_string(steps) + ": rigid body '" + rigidNames[b] +
                   "' has a non-finite or faster than " + formatNumber(limit) + " m/s state" + advice};
  return {};
}

}  // namespace tandem
