// World: grabs (a hand or a mouse pulling a point) and ray casts (what the mouse points at).
#include "world_impl.h"

namespace tandem {

Result<GrabId> World::addGrab(const GrabDesc& desc) {
  Impl& w = *m_impl;
  if (desc.body.has_value() == desc.deformable.has_value())
    return Error{"grab: give either a rigid body or a deformable, not both or neither"};
  if (!desc.target.allFinite()) return Error{"grab: target is not finite"};
  if (!isPositive(desc.frequency) || std::isinf(desc.frequency))
    return Error{"grab: frequency must be positive and finite, got " + formatNumber(desc.frequency) + " Hz"};
  if (!(desc.dampingRatio >= 0) || std::isinf(desc.dampingRatio))
    return Error{"grab: damping ratio must be >= 0 and finite, got " + formatNumber(desc.dampingRatio)};
  if (!isPositive(desc.maxForce))
    return Error{"grab: maxForce must be positive, got " + formatNumber(desc.maxForce) + " N"};
  GrabRow row;
  row.active = true;
  row.target = row.previousTarget = desc.target;
  row.frequency = desc.frequency;
  row.dampingRatio = desc.dampingRatio;
  row.maxForce = desc.maxForce;
  if (desc.body) {
    if (!w.validRigid(*desc.body))
      return Error{"grab: " + w.rigidSlots.check(desc.body->index, desc.body->generation).message()};
    if (!w.bullet.isDynamic(desc.body->index))
      return Error{"grab: rigid body '" + w.rigidNames[desc.body->index] + "' is static or kinematic"};
    if (!desc.point.allFinite()) return Error{"grab: point is not finite"};
    row.body = desc.body->index;
    row.springMass = w.bullet.mass(row.body);
    row.localPoint = w.bullet.orientation(row.body).conjugate() * (desc.point - w.bullet.position(row.body));
    w.bullet.wake(row.body);
  } else {
    Result<Impl::BarycentricPoint> point =
        w.barycentricPoint(*desc.deformable, desc.nodes, desc.weights, desc.nodeCount, "grab");
    if (!point) return Error{point.message()};
    for (int k = 0; k < desc.nodeCount; ++k)  // a grab is on its face, not beyond it
      if (!(desc.weights[k] >= 0 && desc.weights[k] <= 1))
        return Error{"grab: weight " + std::to_string(k) + " must be in [0, 1], got " + formatNumber(desc.weights[k])};
    row.node = point->node;
    row.weight = point->weight;
    const DeformableRecord& body = w.deformables[desc.deformable->index];
    for (int32_t n = body.firstNode; n < body.firstNode + body.nodeCount; ++n)
      if (w.nodes.inverseMass[n] > 0) row.springMass += 1.0 / w.nodes.inverseMass[n];
  }
  std::vector<GrabRow>& grabs = w.rows.grabs;
  auto slot = std::find_if(grabs.begin(), grabs.end(), [](const GrabRow& g) { return !g.active; });
  if (slot == grabs.end()) slot = grabs.insert(grabs.end(), row);
  else *slot = row;
  const IdSlots::Taken taken = w.grabSlots.addAt(static_cast<int32_t>(slot - grabs.begin()));
  return GrabId{taken.index, taken.generation};
}

namespace {
Status checkGrab(const IdSlots& slots, GrabId id) {
  if (Status s = slots.check(id.index, id.generation); !s) return Error{"grab: " + s.message()};
  return {};
}
}  // namespace

Status World::setGrabTarget(GrabId id, const Vec3& target) {
  if (Status s = checkGrab(m_impl->grabSlots, id); !s) return s;
  if (!target.allFinite()) return Error{"grab: target is not finite"};
  m_impl->rows.grabs[id.index].target = target;
  return {};
}

Status World::removeGrab(GrabId id) {
  if (Status s = checkGrab(m_impl->grabSlots, id); !s) return s;
  m_impl->rows.grabs[id.index] = GrabRow{};
  m_impl->grabSlots.remove(id.index, false);
  return {};
}

Vec3 World::grabImpulse(GrabId id) const {
  const std::vector<GrabRow>& grabs = m_impl->rows.grabs;
  return m_impl->lookup(m_impl->grabSlots, id) ? grabs[id.index].stepImpulse : Vec3::Zero();
}

Vec3 World::grabPoint(GrabId id) const {
  const Impl& w = *m_impl;
  if (!w.lookup(w.grabSlots, id)) return Vec3::Zero();
  const GrabRow& row = w.rows.grabs[id.index];
  if (row.onRigid()) return w.bullet.position(row.body) + w.bullet.orientation(row.body) * row.localPoint;
  return row.point(w.nodes.position, nullptr);
}

std::optional<RayHit> World::castRay(const Vec3& origin, const Vec3& direction, double maxDistance) const {
  const Impl& w = *m_impl;
  if (!origin.allFinite() || !direction.allFinite() || direction.norm() < 1e-12 || !(maxDistance > 0))
    return std::nullopt;
  const Vec3 d = direction.normalized();
  std::optional<RayHit> best;
  if (std::isfinite(maxDistance))
    if (auto hit = w.bullet.castRay(origin, origin + maxDistance * d)) {
      best = RayHit{};
      best->rigid = w.rigidId(hit->body);
      best->distance = hit->fraction * maxDistance;
      best->point = origin + best->distance * d;
      best->normal = hit->normal.dot(d) > 0 ? Vec3(-hit->normal) : hit->normal;
    }
  for (size_t b = 0; b < w.deformables.size(); ++b) {
    const DeformableRecord& body = w.deformables[b];
    for (const auto& t : body.restMesh.triangles) {
      const Vec3& p0 = w.nodes.position[body.firstNode + t[0]];
      const Vec3& p1 = w.nodes.position[body.firstNode + t[1]];
      const Vec3& p2 = w.nodes.position[body.firstNode + t[2]];
      const auto hit = geometry::intersectRayTriangle(origin, d, p0, p1, p2);
      if (!hit || hit->t > maxDistance || (best && hit->t >= best->distance)) continue;
      best = RayHit{};
      best->deformable = w.deformableId(b);
      best->nodes = t;
      best->weights = hit->weights;
      best->distance = hit->t;
      best->point = origin + hit->t * d;
      const Vec3 normal = (p1 - p0).cross(p2 - p0).normalized();
      best->normal = normal.dot(d) > 0 ? Vec3(-normal) : normal;
    }
  }
  return best;
}

const RigidShape& World::rigidShape(RigidBodyId body) const {
  static const RigidShape kNoShape;
  return m_impl->lookup(m_impl->rigidSlots, body) ? m_impl->rigidShapes[body.index]->shape : kNoShape;
}

}  // namespace tandem
