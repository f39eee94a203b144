// Contacts moving on within a step: contacts are found once per step (speculative over the whole
// step) and solved in each of its n substeps, so before each substep after the first every
// contact's gap, and where needed its normal and rigid point, follow the motion since the
// step's start.
//
// - A node against a rigid shape is measured again: the signed distance from the node to the
//   shape in the body's current pose gives gap, normal and the body's point (where the node's
//   centre rests when touching, as detection puts it). Its normal turns as the node goes round
//   a curved surface; with the step's first normal kept, a rope sliding round a post was held
//   to the tangent planes it started on, an infeasible set that stretched it.
// - Any other contact (a face against a rigid feature, deformable against deformable) keeps its
//   normal; its gap moves on by the two sides' relative displacement along it,
//   g = g₀ + n · (Σ cₖ (xₖ − xₖ⁰) − Δp_B), with a rigid side's point turned with its body,
//   Δp_B = (c − c⁰) + (R R₀ᵀ − I) r₀.
#pragma once

#include "collision/contact_detection.h"
#include "collision/geometry.h"
#include "constraints/contact.h"

#include <algorithm>
#include <span>

namespace tandem {

struct RigidPose {
  Vec3 centerOfMass = Vec3::Zero();
  Quat orientation = Quat::Identity();
};

// `shapes[b]`: rigid body b's shape and pose now; `startPoses[b]` its pose at the step's start;
// `thickness(node)`: the collision thickness of the node's deformable.
template <typename ThicknessOfNode>
void moveContactsOn(std::span<ContactRow> contacts, std::span<const Vec3> positions,
                    std::span<const Vec3> startPositions, std::span<const CollisionRigid> shapes,
                    std::span<const RigidPose> startPoses, const ThicknessOfNode& thickness) {
  for (ContactRow& row : contacts) {
    if (row.isNodeOnRigid()) {
      const CollisionRigid& body = shapes[row.body];
      const double t = thickness(row.node[0]);
      const Vec3 local = body.orientation.conjugate() * (positions[row.node[0]] - body.position);
      const geometry::ShapeDistance d =
          geometry::distanceToShape(*body.shape, local, 2.0 * t + std::max(row.startGap, 0.0));
      row.normal = body.orientation * d.normal;
      row.offset = body.orientation * (d.surfacePoint + t * d.normal);
      row.gap = d.distance - t;
      continue;
    }
    Vec3 moved = Vec3::Zero();
    for (int k = 0; k < 4; ++k) moved += row.coefficient[k] * (positions[row.node[k]] - startPositions[row.node[k]]);
    if (row.body >= 0) {
      const RigidPose& start = startPoses[row.body];
      const CollisionRigid& body = shapes[row.body];
      row.offset = (body.orientation * start.orientation.conjugate()) * row.startOffset;
      moved -= body.position - start.centerOfMass + row.offset - row.startOffset;
    }
    row.gap = row.startGap + row.normal.dot(moved);
  }
}

}  // namespace tandem
