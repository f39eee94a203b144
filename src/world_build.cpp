// Building a world: validating and adding rigid bodies, joints, deformables and constraints.
#include "world_impl.h"

#include <set>

namespace tandem {
namespace {

Status validateSettings(const WorldSettings& settings) {
  if (!settings.gravity.allFinite()) return Error{"settings: gravity must be finite"};
  if (settings.solver.iterations < 1 || settings.solver.iterations > 1000)
    return Error{"settings: solver iterations must be in [1, 1000], got " + std::to_string(settings.solver.iterations)};
  if (settings.solver.substeps < 1 || settings.solver.substeps > 1000)
    return Error{"settings: solver substeps must be in [1, 1000], got " + std::to_string(settings.solver.substeps)};
  if (!(settings.solver.baumgarte >= 0 && settings.solver.baumgarte <= 1))
    return Error{"settings: baumgarte (β·h) must be in [0, 1], got " + formatNumber(settings.solver.baumgarte)};
  if (!(settings.solver.contactSlop >= 0 && std::isfinite(settings.solver.contactSlop)))
    return Error{"settings: contact slop must be >= 0 m, got " + formatNumber(settings.solver.contactSlop)};
  if (!(settings.divergenceSpeed > 0))
    return Error{"settings: divergence speed must be positive, got " + formatNumber(settings.divergenceSpeed)};
  return {};
}

// `name` is "convex hull" or "compound hull N".
Status validateHull(const std::vector<Vec3>& points, const std::string& who, const std::string& name) {
  const bool single = name == "convex hull";
  if (points.size() < 4) return Error{who + ": " + (single ? "a " : "") + name + " needs at least 4 points"};
  for (size_t i = 0; i < points.size(); ++i)
    if (!points[i].allFinite()) return Error{who + ": " + name + " point " + std::to_string(i) + " is not finite"};
  bool solid = false;  // some four points span a volume
  for (size_t i = 2; i < points.size() && !solid; ++i)
    for (size_t j = i + 1; j < points.size() && !solid; ++j)
      solid = std::abs((points[1] - points[0]).dot((points[i] - points[0]).cross(points[j] - points[0]))) > 1e-12;
  if (!solid) return Error{who + ": " + (single ? "the convex hull's" : name + "'s") + " points are flat (no volume)"};
  return {};
}

Status validateVisual(const VisualMesh& visual, const std::string& who) {
  const auto count = static_cast<int32_t>(visual.positions.size());
  for (size_t i = 0; i < visual.positions.size(); ++i)
    if (!visual.positions[i].allFinite()) return Error{who + ": visual mesh vertex " + std::to_string(i) + " is not finite"};
  for (size_t t = 0; t < visual.triangles.size(); ++t)
    for (int32_t v : visual.triangles[t])
      if (v < 0 || v >= count)
        return Error{who + ": visual mesh triangle " + std::to_string(t) + " refers to vertex " + std::to_string(v) +
                     " (there are " + std::to_string(count) + ")"};
  return {};
}

// Principal moments: positive, finite, and each at most the sum of the other two (what any
// mass distribution gives; a relative 1e-9 of slack for rounding).
Status validateInertia(const Vec3& inertia, const std::string& who) {
  const std::string given = formatNumber(inertia.x()) + ", " + formatNumber(inertia.y()) + ", " + formatNumber(inertia.z());
  if (!inertia.allFinite() || !(inertia.minCoeff() > 0))
    return Error{who + ": inertia must be three positive principal moments (kg·m²), got " + given};
  for (int k = 0; k < 3; ++k)
    if (inertia[k] > (inertia[(k + 1) % 3] + inertia[(k + 2) % 3]) * (1 + 1e-9))
      return Error{who + ": inertia " + given + " kg·m² is no body's: moment " + std::to_string(k) +
                   " is more than the sum of the other two"};
  return {};
}

// Bullet's damping: each a fraction of the velocity lost per second.
Status validateDamping(double linearDamping, double angularDamping, const std::string& who) {
  if (!(linearDamping >= 0 && linearDamping <= 1))
    return Error{who + ": linear damping must be in [0, 1], got " + formatNumber(linearDamping)};
  if (!(angularDamping >= 0 && angularDamping <= 1))
    return Error{who + ": angular damping must be in [0, 1], got " + formatNumber(angularDamping)};
  return {};
}

Status validateShape(const RigidShape& s, const std::string& who) {
  auto positiveFinite = [](double v) { return std::isfinite(v) && v > 0; };
  switch (s.type) {
    case ShapeType::Box:
      if (!s.halfExtents.allFinite() || s.halfExtents.minCoeff() <= 0)
        return Error{who + ": box half extents must be positive and finite"};
      break;
    case ShapeType::Sphere:
      if (!positiveFinite(s.radius)) return Error{who + ": sphere radius must be positive, got " + formatNumber(s.radius)};
      break;
    case ShapeType::Cylinder:
    case ShapeType::Capsule:
      if (!positiveFinite(s.radius) || !positiveFinite(s.halfHeight))
        return Error{who + ": radius and half height must be positive, got " + formatNumber(s.radius) + " and " +
                     formatNumber(s.halfHeight)};
      break;
    case ShapeType::Plane:
      if (!s.planeNormal.allFinite() || s.planeNormal.norm() < 1e-9 || !std::isfinite(s.planeOffset))
        return Error{who + ": plane normal must be a finite non-zero vector and the offset finite"};
      break;
    case ShapeType::ConvexHull:
      if (Status status = validateHull(s.points, who, "convex hull"); !status) return status;
      break;
    case ShapeType::Compound:
      if (s.hulls.empty()) return Error{who + ": a compound needs at least one convex hull"};
      for (size_t h = 0; h < s.hulls.size(); ++h)
        if (Status status = validateHull(s.hulls[h], who, "compound hull " + std::to_string(h)); !status) return status;
      break;
    case ShapeType::TriangleMesh: {
      if (s.triangles.empty()) return Error{who + ": a triangle mesh needs at least one triangle"};
      DeformableMesh mesh;  // reuse the mesh checks: indices, finiteness, degenerate triangles
      mesh.positions = s.points;
      mesh.masses.assign(s.points.size(), 1.0);
      mesh.triangles = s.triangles;
      if (Status status = validateMesh(mesh); !status) return Error{who + ": triangle mesh: " + status.message()};
      break;
    }
  }
  if (Status status = validateVisual(s.visual, who); !status) return status;
  return {};
}

// Whether some node of the triangles is on no boundary edge (an edge of one triangle only): a
// sheet has such nodes, a ribbon two nodes wide has none.
bool hasInteriorNodes(const std::vector<std::array<int32_t, 3>>& triangles) {
  std::vector<std::array<int32_t, 2>> edges;
  for (const auto& t : triangles)
    for (int k = 0; k < 3; ++k) edges.push_back({std::min(t[k], t[(k + 1) % 3]), std::max(t[k], t[(k + 1) % 3])});
  std::sort(edges.begin(), edges.end());
  std::set<int32_t> onBoundary, used;
  for (size_t i = 0; i < edges.size();) {
    size_t j = i;
    while (j < edges.size() && edges[j] == edges[i]) ++j;
    if (j - i == 1) onBoundary.insert(edges[i].begin(), edges[i].end());
    used.insert(edges[i].begin(), edges[i].end());
    i = j;
  }
  return used.size() > onBoundary.size();
}

}  // namespace

RigidShape RigidShape::box(const Vec3& halfExtents) {
  RigidShape s;
  s.type = ShapeType::Box;
  s.halfExtents = halfExtents;
  return s;
}
RigidShape RigidShape::sphere(double radius) {
  RigidShape s;
  s.type = ShapeType::Sphere;
  s.radius = radius;
  return s;
}
RigidShape RigidShape::cylinder(double radius, double halfHeight) {
  RigidShape s;
  s.type = ShapeType::Cylinder;
  s.radius = radius;
  s.halfHeight = halfHeight;
  return s;
}
RigidShape RigidShape::capsule(double radius, double halfHeight) {
  RigidShape s = cylinder(radius, halfHeight);
  s.type = ShapeType::Capsule;
  return s;
}
RigidShape RigidShape::plane(const Vec3& normal, double offset) {
  RigidShape s;
  s.type = ShapeType::Plane;
  s.planeNormal = normal;
  s.planeOffset = offset;
  return s;
}

RigidShape RigidShape::convexHull(std::vector<Vec3> points) {
  RigidShape s;
  s.type = ShapeType::ConvexHull;
  s.points = std::move(points);
  return s;
}
RigidShape RigidShape::triangleMesh(std::vector<Vec3> vertices, std::vector<std::array<int32_t, 3>> triangles) {
  RigidShape s;
  s.type = ShapeType::TriangleMesh;
  s.points = std::move(vertices);
  s.triangles = std::move(triangles);
  return s;
}

RigidShape RigidShape::compound(std::vector<std::vector<Vec3>> hulls) {
  RigidShape s;
  s.type = ShapeType::Compound;
  s.hulls = std::move(hulls);
  return s;
}

AnchorDesc AnchorDesc::node(DeformableId deformable, int32_t node, RigidBodyId body) {
  AnchorDesc desc;
  desc.deformable = deformable;
  desc.nodes = {node, -1, -1, -1};
  desc.weights = {1.0, 0.0, 0.0, 0.0};
  desc.nodeCount = 1;
  desc.body = body;
  return desc;
}

Status World::setSettings(const WorldSettings& settings) {
  if (Status s = validateSettings(settings); !s) return s;
  m_impl->settings = settings;
  m_impl->bullet.setGravity(settings.gravity);
  return {};
}
Result<RigidBodyId> World::addRigidBody(const RigidBodyDesc& desc) {
  const std::string who = "rigid body '" + desc.name + "'";
  if (Status s = validateShape(desc.shape, who); !s) return Error{s.message()};
  if (desc.motion == MotionType::Dynamic && !(std::isfinite(desc.mass) && desc.mass > 0))
    return Error{who + ": mass must be positive and finite for a dynamic body, got " + formatNumber(desc.mass) + " kg"};
  if ((desc.shape.type == ShapeType::Plane || desc.shape.type == ShapeType::TriangleMesh) &&
      desc.motion != MotionType::Static)
    return Error{who + ": a plane or a triangle mesh can only be static"};
  if (desc.inertia && desc.motion == MotionType::Dynamic)
    if (Status s = validateInertia(*desc.inertia, who); !s) return Error{s.message()};
  if (!desc.position.allFinite()) return Error{who + ": position is not finite"};
  if (!desc.orientation.coeffs().allFinite() || desc.orientation.norm() < 1e-9)
    return Error{who + ": orientation must be a finite non-zero quaternion"};
  if (!desc.linearVelocity.allFinite() || !desc.angularVelocity.allFinite())
    return Error{who + ": velocity is not finite"};
  if (!(desc.friction >= 0 && std::isfinite(desc.friction)))
    return Error{who + ": friction must be >= 0, got " + formatNumber(desc.friction)};
  if (!(desc.restitution >= 0 && desc.restitution <= 1))
    return Error{who + ": restitution must be in [0, 1], got " + formatNumber(desc.restitution)};
  if (Status s = validateDamping(desc.linearDamping, desc.angularDamping, who); !s) return Error{s.message()};
  Impl& w = *m_impl;
  // A removed body's slot is reused (with the next generation), else a new one is made.
  int32_t slot = w.rigidSlots.firstFree();
  if (slot < 0) {
    slot = static_cast<int32_t>(w.rigidSlots.size());
    w.rigidNames.emplace_back();
    w.rigidFriction.push_back(0.0);
    w.rigidShapes.emplace_back();
    w.rigid.emplace_back();
    w.rigidGroup.push_back(0);
    w.rigidMask.push_back(0);
  }
  w.bullet.addRigidBody(desc, slot);
  w.rigidNames[slot] = desc.name;
  w.rigidFriction[slot] = desc.friction;
  auto shape = std::make_unique<geometry::CollisionShape>();
  shape->shape = desc.shape;
  if (desc.shape.type == ShapeType::ConvexHull) shape->planes = bullet::convexHullPlanes(desc.shape.points);
  if (desc.shape.type == ShapeType::Compound)
    for (const std::vector<Vec3>& hull : desc.shape.hulls) {
      shape->hullPlanesStart.push_back(static_cast<int32_t>(shape->planes.size()));
      for (const Eigen::Vector4d& plane : bullet::convexHullPlanes(hull)) shape->planes.push_back(plane);
    }
  if (desc.shape.type == ShapeType::TriangleMesh) shape->grid.build(desc.shape.points, desc.shape.triangles);
  w.rigidShapes[slot] = std::move(shape);
  w.rigid[slot] = RigidSolverState{};
  w.rigidGroup[slot] = desc.collisionGroup;
  w.rigidMask[slot] = desc.collisionMask;
  const IdSlots::Taken taken = w.rigidSlots.addAt(slot);
  ++w.rigidStructureVersion;
  w.directBlocksStale = true;
  return RigidBodyId{taken.index, taken.generation};
}

namespace {
Status validateHingeMotion(double lower, double upper, bool motor, double targetSpeed, double maxTorque,
                           const std::string& who) {
  if (std::isnan(lower) || std::isnan(upper) || (lower <= upper && (!std::isfinite(lower) || !std::isfinite(upper))))
    return Error{who + ": limits must be finite (lower > upper for none), got [" + formatNumber(lower) + ", " +
                 formatNumber(upper) + "]"};
  if (lower <= upper && (lower < -M_PI || upper > M_PI))
    return Error{who + ": limits must lie in [-pi, pi] rad, got [" + formatNumber(lower) + ", " +
                 formatNumber(upper) + "]"};
  if (motor && !std::isfinite(targetSpeed)) return Error{who + ": motor target speed must be finite"};
  if (motor && !(std::isfinite(maxTorque) && maxTorque >= 0))
    return Error{who + ": motor max torque must be >= 0 and finite, got " + formatNumber(maxTorque) + " N·m"};
  return {};
}
}  // namespace

Result<JointId> World::addHinge(const HingeDesc& desc) {
  Impl& w = *m_impl;
  if (!w.validRigid(desc.bodyA)) return Error{"hinge: body A: " + w.rigidSlots.check(desc.bodyA.index, desc.bodyA.generation).message()};
  if (desc.bodyB && !w.validRigid(*desc.bodyB))
    return Error{"hinge: body B: " + w.rigidSlots.check(desc.bodyB->index, desc.bodyB->generation).message()};
  if (desc.bodyB && *desc.bodyB == desc.bodyA) return Error{"hinge: body A and body B are the same body"};
  if (!desc.pivot.allFinite()) return Error{"hinge: pivot is not finite"};
  if (!desc.axis.allFinite() || desc.axis.norm() < 1e-9) return Error{"hinge: axis must be a finite non-zero vector"};
  if (Status s = validateHingeMotion(desc.lowerLimit, desc.upperLimit, desc.motor, desc.motorTargetSpeed,
                                     desc.motorMaxTorque, "hinge");
      !s)
    return Error{s.message()};
  int32_t slot = w.jointSlots.firstFree();
  if (slot < 0) slot = static_cast<int32_t>(w.jointSlots.size());
  w.bullet.addHinge(desc, slot);
  const IdSlots::Taken taken = w.jointSlots.addAt(slot);
  ++w.rigidStructureVersion;
  return JointId{taken.index, taken.generation};
}

Result<JointId> World::addFixedJoint(const FixedJointDesc& desc) {
  Impl& w = *m_impl;
  if (!w.validRigid(desc.bodyA))
    return Error{"fixed joint: body A: " + w.rigidSlots.check(desc.bodyA.index, desc.bodyA.generation).message()};
  if (desc.bodyB && !w.validRigid(*desc.bodyB))
    return Error{"fixed joint: body B: " + w.rigidSlots.check(desc.bodyB->index, desc.bodyB->generation).message()};
  if (desc.bodyB && *desc.bodyB == desc.bodyA) return Error{"fixed joint: body A and body B are the same body"};
  int32_t slot = w.jointSlots.firstFree();
  if (slot < 0) slot = static_cast<int32_t>(w.jointSlots.size());
  w.bullet.addFixedJoint(desc, slot);
  const IdSlots::Taken taken = w.jointSlots.addAt(slot);
  ++w.rigidStructureVersion;
  return JointId{taken.index, taken.generation};
}

Status World::putRigidToSleep(RigidBodyId body) {
  if (Status s = m_impl->rigidSlots.check(body.index, body.generation); !s) return Error{"put to sleep: " + s.message()};
  m_impl->bullet.putToSleep(body.index);
  return {};
}
Status World::setRigidCanSleep(RigidBodyId body, bool canSleep) {
  if (Status s = m_impl->rigidSlots.check(body.index, body.generation); !s) return Error{"can sleep: " + s.message()};
  m_impl->bullet.setCanSleep(body.index, canSleep);
  return {};
}

Status World::setRigidDamping(RigidBodyId body, double linearDamping, double angularDamping) {
  if (Status s = m_impl->rigidSlots.check(body.index, body.generation); !s) return Error{"damping: " + s.message()};
  if (Status s = validateDamping(linearDamping, angularDamping, "damping"); !s) return s;
  m_impl->bullet.setDamping(body.index, linearDamping, angularDamping);
  return {};
}

Status World::setKinematicTarget(RigidBodyId body, const Vec3& position, const Quat& orientation) {
  if (Status s = m_impl->rigidSlots.check(body.index, body.generation); !s)
    return Error{"kinematic target: " + s.message()};
  if (!position.allFinite() || !orientation.coeffs().allFinite() || orientation.norm() < 1e-9)
    return Error{"kinematic target: pose is not finite"};
  m_impl->bullet.setKinematicTarget(body.index, position, orientation);
  return {};
}

Result<DeformableId> World::addDeformable(const DeformableDesc& desc) {
  const std::string who = "deformable '" + desc.name + "'";
  if (Status s = validateMesh(desc.mesh); !s) return Error{who + ": " + s.message()};
  const MassSpringSettings& springs = desc.springs;
  if (!(springs.stiffness >= 0 && std::isfinite(springs.stiffness)) ||
      !(springs.damping >= 0 && std::isfinite(springs.damping)))
    return Error{who + ": spring stiffness and damping must be >= 0 and finite"};
  if (desc.inextensibility.enabled && !isPositive(desc.inextensibility.maxForce))
    return Error{who + ": inextensibility max force must be positive, got " + formatNumber(desc.inextensibility.maxForce)};
  if (desc.bending.enabled && !isPositive(desc.bending.maxForce))
    return Error{who + ": bending max force must be positive, got " + formatNumber(desc.bending.maxForce)};
  if (desc.bending.enabled && (!isPositive(desc.bending.frequency) || !(desc.bending.dampingRatio >= 0)))
    return Error{who + ": bending frequency must be positive and its damping ratio >= 0"};
  const ParadigmSettings& paradigm = desc.paradigm;
  if (!(paradigm.stiffness > 0 && paradigm.stiffness <= 1))
    return Error{who + ": paradigm stiffness k must be in (0, 1], got " + formatNumber(paradigm.stiffness)};
  if (!(paradigm.damping >= 0 && paradigm.damping <= 1))
    return Error{who + ": paradigm damping must be in [0, 1], got " + formatNumber(paradigm.damping)};
  if (paradigm.iterations < 1 || paradigm.iterations > 1000)
    return Error{who + ": paradigm iterations must be in [1, 1000], got " + std::to_string(paradigm.iterations)};
  if (paradigm.type == ParadigmType::CorotationalFem) {
    if (!(std::isfinite(paradigm.youngsModulus) && paradigm.youngsModulus > 0))
      return Error{who + ": Young's modulus must be positive, got " + formatNumber(paradigm.youngsModulus) + " Pa"};
    if (!(paradigm.poissonRatio >= 0 && paradigm.poissonRatio < 0.5))
      return Error{who + ": Poisson's ratio must be in [0, 0.5), got " + formatNumber(paradigm.poissonRatio)};
    if (desc.mesh.tetrahedra.empty()) return Error{who + ": co-rotational FEM needs a tetrahedral mesh"};
  }
  if (!(std::isfinite(desc.damping) && desc.damping >= 0))
    return Error{who + ": damping must be >= 0 per second and finite, got " + formatNumber(desc.damping)};
  if (!(std::isfinite(desc.collision.thickness) && desc.collision.thickness >= 0))
    return Error{who + ": collision thickness must be >= 0 m and finite, got " + formatNumber(desc.collision.thickness)};
  if (!(std::isfinite(desc.collision.friction) && desc.collision.friction >= 0))
    return Error{who + ": friction must be >= 0 and finite, got " + formatNumber(desc.collision.friction)};

  Impl& w = *m_impl;
  const DeformableMesh& mesh = desc.mesh;
  const int32_t first = static_cast<int32_t>(w.nodes.size());
  for (int32_t i = 0; i < mesh.nodeCount(); ++i) {
    w.nodes.position.push_back(mesh.positions[i]);
    w.nodes.velocity.push_back(Vec3::Zero());
    w.nodes.force.push_back(Vec3::Zero());
    w.nodes.inverseMass.push_back(1.0 / mesh.masses[i]);
  }
  std::vector<EdgeSpring> implicitSprings;
  auto addEdge = [&](const std::array<int32_t, 2>& e, bool inextensible) {
    const double restLength = (mesh.positions[e[1]] - mesh.positions[e[0]]).norm();
    if (springs.stiffness > 0 || springs.damping > 0)
      (springs.implicit ? implicitSprings : w.springs)
          .push_back({first + e[0], first + e[1], restLength, springs.stiffness, springs.damping});
    if (!inextensible) return;
    InextensibilityRow row;
    row.node = {first + e[0], first + e[1]};
    row.restLength = restLength;
    const auto bounds = inextensibilityForceBounds(desc.inextensibility.mode, desc.inextensibility.maxForce);
    row.lambdaMin = bounds[0];
    row.lambdaMax = bounds[1];
    w.rows.inextensibility.push_back(row);
  };
  for (const auto& e : mesh.edges) addEdge(e, desc.inextensibility.enabled);
  for (const auto& e : mesh.shearEdges) addEdge(e, desc.inextensibility.enabled && desc.inextensibility.shearEdges);
  if (desc.bending.enabled) {
    for (const EdgeHinge& hinge : findEdgeHinges(mesh.triangles)) {
      BendingRow row;
      row.node = {first + hinge.i, first + hinge.j, first + hinge.left, first + hinge.right};
      const auto& x = mesh.positions;
      row.restDot = bendingDot(x[hinge.i], x[hinge.j], x[hinge.left], x[hinge.right]);
      row.restEdgeLength = (x[hinge.j] - x[hinge.i]).norm();
      row.maxForce = desc.bending.maxForce;
      row.frequency = desc.bending.frequency;
      row.dampingRatio = desc.bending.dampingRatio;
      w.rows.bending.push_back(row);
    }
  }
  DeformableRecord record{desc.name, first, mesh.nodeCount(), mesh, desc.rowSolver, desc.collision, desc.paradigm,
                          desc.damping, {}, {}, {}, {}, {}, false, {}, {}};
  // FEM bodies and implicit springs are stepped by the implicit solve; springs on a
  // position-based body are too.
  FemElements fem;
  if (desc.paradigm.type == ParadigmType::CorotationalFem)
    fem = makeFemElements(first, mesh.positions, mesh.tetrahedra, desc.paradigm.youngsModulus, desc.paradigm.poissonRatio);
  record.implicitStep = !fem.tetrahedra.empty() || !implicitSprings.empty();
  record.hasInteriorSurfaceNodes = mesh.tetrahedra.empty() && hasInteriorNodes(mesh.triangles);
  record.supports.reset(first, mesh.nodeCount());
  record.supports.clearHolds();
  if (record.implicitStep)
    record.implicit = makeImplicitBody(first, mesh.nodeCount(), std::move(fem), std::move(implicitSprings));
  record.paradigmEdges = mesh.edges;
  record.paradigmEdges.insert(record.paradigmEdges.end(), mesh.shearEdges.begin(), mesh.shearEdges.end());
  if (desc.paradigm.type == ParadigmType::PositionBased)
    record.paradigmRest = positionBasedRest(mesh.positions, record.paradigmEdges, mesh.tetrahedra);
  // The collision surface: its triangles, and the nodes on them (every node when it has none).
  std::vector<bool> onSurface(mesh.nodeCount(), mesh.triangles.empty());
  for (const auto& t : mesh.triangles) {
    record.surfaceTriangles.push_back({first + t[0], first + t[1], first + t[2]});
    for (int32_t n : t) onSurface[n] = true;
  }
  for (int32_t n = 0; n < mesh.nodeCount(); ++n)
    if (onSurface[n]) record.surfaceNodes.push_back(first + n);
  // Its edges: the triangles' (each once), or a rope's.
  std::set<std::pair<int32_t, int32_t>> edges;
  for (const auto& t : mesh.triangles)
    for (int k = 0; k < 3; ++k) edges.insert({std::min(t[k], t[(k + 1) % 3]), std::max(t[k], t[(k + 1) % 3])});
  if (mesh.triangles.empty())
    for (const auto& e : mesh.edges) edges.insert({std::min(e[0], e[1]), std::max(e[0], e[1])});
  for (const auto& [i, j] : edges) record.surfaceEdges.push_back({first + i, first + j});
  w.deformables.push_back(std::move(record));
  w.directBlocksStale = true;
  // Deformables never reuse a slot: their records stay in node order (deformableOfNode).
  const IdSlots::Taken taken = w.deformableSlots.add(static_cast<int32_t>(w.deformables.size()) - 1, false);
  return DeformableId{taken.index, taken.generation};
}

Status World::setNodeVelocity(DeformableId body, int32_t node, const Vec3& velocity) {
  Result<int32_t> n = m_impl->globalNode(body, node, "set node velocity");
  if (!n) return n.status();
  if (!velocity.allFinite()) return Error{"set node velocity: velocity is not finite"};
  m_impl->nodes.velocity[*n] = velocity;
  return {};
}

Status World::setNodePosition(DeformableId body, int32_t node, const Vec3& position) {
  Result<int32_t> n = m_impl->globalNode(body, node, "set node position");
  if (!n) return n.status();
  if (!position.allFinite()) return Error{"set node position: position is not finite"};
  m_impl->nodes.position[*n] = position;
  return {};
}

Status World::fixNode(DeformableId body, int32_t node) {
  Result<int32_t> n = m_impl->globalNode(body, node, "fix node");
  if (!n) return n.status();
  m_impl->nodes.inverseMass[*n] = 0.0;
  m_impl->nodes.velocity[*n].setZero();
  return {};
}

// ---- Constraints ------------------------------------------------------------------------

Result<FixedPointId> World::addFixedPoint(DeformableId body, int32_t node, const Vec3& target, double maxForce) {
  Result<int32_t> n = m_impl->globalNode(body, node, "fixed point");
  if (!n) return Error{n.message()};
  if (!target.allFinite()) return Error{"fixed point: target is not finite"};
  if (!isPositive(maxForce)) return Error{"fixed point: max force must be positive, got " + formatNumber(maxForce)};
  FixedPointRow row;
  row.node = *n;
  row.target = row.previousTarget = target;
  row.maxForce = maxForce;
  m_impl->rows.fixedPoints.push_back(row);
  m_impl->directBlocksStale = true;
  const IdSlots::Taken taken =
      m_impl->fixedPointSlots.add(static_cast<int32_t>(m_impl->rows.fixedPoints.size()) - 1, true);
  return FixedPointId{taken.index, taken.generation};
}

Status World::setFixedPointTarget(FixedPointId id, const Vec3& target) {
  if (Status s = m_impl->fixedPointSlots.check(id.index, id.generation); !s)
    return Error{"fixed point target: " + s.message()};
  if (!target.allFinite()) return Error{"fixed point target: target is not finite"};
  m_impl->rows.fixedPoints[m_impl->fixedPointSlots.position(id.index)].target = target;
  return {};
}

Result<AnchorId> World::addAnchor(const AnchorDesc& desc) {
  Impl& w = *m_impl;
  if (!w.validRigid(desc.body))
    return Error{"anchor: " + w.rigidSlots.check(desc.body.index, desc.body.generation).message()};
  if (!isPositive(desc.maxForce)) return Error{"anchor: max force must be positive, got " + formatNumber(desc.maxForce)};
  Result<Impl::BarycentricPoint> point =
      w.barycentricPoint(desc.deformable, desc.nodes, desc.weights, desc.nodeCount, "anchor");
  if (!point) return Error{point.message()};
  AnchorRow row;
  row.body = desc.body.index;
  row.maxForce = desc.maxForce;
  row.node = point->node;
  row.weight = point->weight;
  const Vec3 com = w.bullet.position(row.body);
  const Quat orientation = w.bullet.orientation(row.body);
  if (desc.localPoint) {
    if (!desc.localPoint->allFinite()) return Error{"anchor: local point is not finite"};
    row.localPoint = *desc.localPoint;
  } else {
    row.localPoint = orientation.conjugate() * (row.deformablePoint(w.nodes.position) - com);
  }
  w.rows.anchors.push_back(row);
  w.directBlocksStale = true;
  const IdSlots::Taken taken = w.anchorSlots.add(static_cast<int32_t>(w.rows.anchors.size()) - 1, true);
  return AnchorId{taken.index, taken.generation};
}

}  // namespace tandem
