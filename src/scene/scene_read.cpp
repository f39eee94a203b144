// Scene files → Scene: JSON parsed with duplicate fields refused, then read object by object
// (scene/json_reader.h), every value checked where it is read, names cross-checked at the end.
#include "scene/json_reader.h"
#include "scene/scene_names.h"

#include <tandem/scene_file.h>

#include "input_file.h"

#include <filesystem>
#include <fstream>
#include <limits>
#include <map>

namespace tandem {
namespace {

using scene::fail;
using scene::Json;
using scene::ObjectReader;

// The physical magnitudes a run can survive (Limits), checked where each value is read: a value
// past its bound is refused with its JSON path, the value and the bound.
struct Bounds {
  const Limits& limits;
  double divergenceSpeed = 0.0;  // the scene's own

  void coordinates(const Vec3& x, const std::string& path) const {
    for (int k = 0; k < 3; ++k)
      if (std::abs(x[k]) > limits.maxCoordinate)
        fail(path + "/" + std::to_string(k), scene::formatValue(x[k]) + " m is farther from the origin than " +
                                                 scene::formatValue(limits.maxCoordinate) + " m (Limits::maxCoordinate)");
  }
  void size(double value, const std::string& path) const {
    if (value < limits.minSize || value > limits.maxSize)
      fail(path, scene::formatValue(value) + " m is outside [" + scene::formatValue(limits.minSize) + ", " +
                     scene::formatValue(limits.maxSize) + "] m (Limits::minSize, maxSize)");
  }
  void mass(double value, const std::string& path) const {
    if (value < limits.minMass || value > limits.maxMass)
      fail(path, scene::formatValue(value) + " kg is outside [" + scene::formatValue(limits.minMass) + ", " +
                     scene::formatValue(limits.maxMass) + "] kg (Limits::minMass, maxMass)");
  }
  void speed(const Vec3& velocity, const std::string& path) const {
    if (!(velocity.stableNorm() < divergenceSpeed))
      fail(path, "a speed of " + scene::formatValue(velocity.stableNorm()) + " m/s is not below the divergence speed of " +
                     scene::formatValue(divergenceSpeed) + " m/s (/divergence_speed): the run would stop at its first step");
  }
  void angularSpeed(const Vec3& velocity, const std::string& path) const {
    if (velocity.stableNorm() > limits.maxAngularSpeed)
      fail(path, scene::formatValue(velocity.stableNorm()) + " rad/s is faster than " +
                     scene::formatValue(limits.maxAngularSpeed) + " rad/s (Limits::maxAngularSpeed)");
  }
};

// Array `key` of `reader` (optional: empty when missing), each element with its path.
template <class Visit>
void forEachElement(ObjectReader& reader, const std::string& key, Visit visit) {
  if (!reader.has(key)) return;
  const Json& array = reader.required(key);
  const std::string path = reader.fieldPath(key);
  if (!array.is_array()) fail(path, "must be an array, got " + scene::typeName(array));
  for (size_t i = 0; i < array.size(); ++i) visit(array[i], path + "/" + std::to_string(i));
}

Quat readOrientation(ObjectReader& body) {
  const bool hasQuaternion = body.has("orientation"), hasEuler = body.has("euler_degrees");
  if (hasQuaternion && hasEuler)
    fail(body.fieldPath("euler_degrees"), "give either 'orientation' or 'euler_degrees', not both");
  if (hasEuler) {
    const Vec3 degrees = body.vec3("euler_degrees");
    const Vec3 radians = degrees * (M_PI / 180.0);
    return Quat(Eigen::AngleAxisd(radians.z(), Vec3::UnitZ()) * Eigen::AngleAxisd(radians.y(), Vec3::UnitY()) *
                Eigen::AngleAxisd(radians.x(), Vec3::UnitX()));
  }
  if (!hasQuaternion) return Quat::Identity();
  const Json& value = body.required("orientation");
  const std::string path = body.fieldPath("orientation");
  if (!value.is_array() || value.size() != 4) fail(path, "must be a quaternion [w, x, y, z]");
  Quat q(scene::readNumber(value[0], path + "/0"), scene::readNumber(value[1], path + "/1"),
         scene::readNumber(value[2], path + "/2"), scene::readNumber(value[3], path + "/3"));
  const double norm = q.norm();
  if (std::abs(norm - 1.0) > 1e-3) fail(path, "must be a unit quaternion [w, x, y, z], its norm is " + scene::formatValue(norm));
  // A quaternion already unit to rounding is kept bit for bit: normalising it again can move its
  // last bit, and a scene written and read back would not be the scene written.
  if (std::abs(q.squaredNorm() - 1.0) <= 4 * std::numeric_limits<double>::epsilon()) return q;
  return q.normalized();
}

std::vector<Vec3> readPoints(const Json& value, const std::string& path) {
  if (!value.is_array()) fail(path, "must be an array of [x, y, z] points");
  std::vector<Vec3> points;
  for (size_t i = 0; i < value.size(); ++i) points.push_back(scene::readVec3(value[i], path + "/" + std::to_string(i)));
  return points;
}

void readShape(ObjectReader& body, SceneRigidBody& out, const Bounds& bounds) {
  ObjectReader shape(body.required("shape"), body.fieldPath("shape"));
  RigidShape& s = out.desc.shape;
  shape.required("type");
  const std::string type = shape.string("type");
  if (type == "mesh") {
    SceneMeshShape mesh;
    mesh.file = shape.string("file");
    mesh.options.collision = shape.choice("collision", scene::kMeshCollisionNames, mesh.options.collision);
    mesh.options.maxHullVertices = shape.integer("max_hull_vertices", mesh.options.maxHullVertices, 4, 4096);
    mesh.options.scale = shape.positive("scale", mesh.options.scale);
    bounds.size(mesh.options.scale, shape.fieldPath("scale"));
    s.type = mesh.options.collision == MeshCollision::ConvexHull ? ShapeType::ConvexHull : ShapeType::Compound;
    out.meshShape = std::move(mesh);
    shape.finish();
    return;
  }
  if (std::none_of(scene::kShapeNames.begin(), scene::kShapeNames.end(), [&](const auto& n) { return n.first == type; })) {
    std::string allowed;
    for (const auto& [name, unused] : scene::kShapeNames) allowed += name + ", ";
    fail(shape.fieldPath("type"), "unknown value '" + type + "' (expected one of: " + allowed + "mesh)");
  }
  s.type = shape.choice("type", scene::kShapeNames, ShapeType::Box);
  auto positiveRequired = [&](const std::string& key) {
    shape.required(key);
    return shape.positive(key, 0);
  };
  switch (s.type) {
    case ShapeType::Box: {
      s.halfExtents = shape.vec3("half_extents");
      if (!(s.halfExtents.minCoeff() > 0)) fail(shape.fieldPath("half_extents"), "must all be > 0");
      for (int k = 0; k < 3; ++k) bounds.size(s.halfExtents[k], shape.fieldPath("half_extents") + "/" + std::to_string(k));
      break;
    }
    case ShapeType::Sphere:
      s.radius = positiveRequired("radius");
      bounds.size(s.radius, shape.fieldPath("radius"));
      break;
    case ShapeType::Cylinder:
    case ShapeType::Capsule:
      s.radius = positiveRequired("radius");
      s.halfHeight = positiveRequired("half_height");
      bounds.size(s.radius, shape.fieldPath("radius"));
      bounds.size(s.halfHeight, shape.fieldPath("half_height"));
      break;
    case ShapeType::Plane:
      s.planeNormal = shape.vec3("normal");
      // stableNorm: components past 1e154 would overflow the plain norm to inf (and normalise to 0).
      if (s.planeNormal.stableNorm() < 1e-9) fail(shape.fieldPath("normal"), "must not be zero");
      // Unit to rounding already: kept bit for bit, so that written and read back it is the same.
      if (std::abs(s.planeNormal.squaredNorm() - 1.0) > 4 * std::numeric_limits<double>::epsilon())
        s.planeNormal.stableNormalize();
      s.planeOffset = shape.number("offset", 0.0);
      bounds.coordinates(Vec3::Constant(s.planeOffset), shape.fieldPath("offset"));
      break;
    case ShapeType::ConvexHull:
    case ShapeType::TriangleMesh: {
      const bool fromFile = shape.has("file");
      const std::string pointsKey = s.type == ShapeType::ConvexHull ? "points" : "vertices";
      if (fromFile == shape.has(pointsKey))
        fail(shape.path(), "give either 'file' (an OBJ) or '" + pointsKey + "'");
      if (fromFile) {
        out.shapeFile = shape.string("file");
        break;
      }
      s.points = readPoints(shape.required(pointsKey), shape.fieldPath(pointsKey));
      for (size_t i = 0; i < s.points.size(); ++i)
        bounds.coordinates(s.points[i], shape.fieldPath(pointsKey) + "/" + std::to_string(i));
      if (s.type == ShapeType::TriangleMesh) {
        const Json& triangles = shape.required("triangles");
        const std::string path = shape.fieldPath("triangles");
        if (!triangles.is_array()) fail(path, "must be an array of [i, j, k]");
        for (size_t t = 0; t < triangles.size(); ++t) {
          const std::string at = path + "/" + std::to_string(t);
          if (!triangles[t].is_array() || triangles[t].size() != 3) fail(at, "must be [i, j, k]");
          std::array<int32_t, 3> triangle{};
          for (int k = 0; k < 3; ++k) triangle[k] = scene::readInteger(triangles[t][k], at + "/" + std::to_string(k));
          s.triangles.push_back(triangle);
        }
      }
      break;
    }
    case ShapeType::Compound: {
      const Json& hulls = shape.required("hulls");
      const std::string path = shape.fieldPath("hulls");
      if (!hulls.is_array() || hulls.empty()) fail(path, "must be a non-empty array of hulls, each an array of [x, y, z] points");
      for (size_t h = 0; h < hulls.size(); ++h) {
        const std::string at = path + "/" + std::to_string(h);
        s.hulls.push_back(readPoints(hulls[h], at));
        if (s.hulls.back().size() < 4) fail(at, "a hull needs at least 4 points");
        for (size_t i = 0; i < s.hulls.back().size(); ++i) bounds.coordinates(s.hulls.back()[i], at + "/" + std::to_string(i));
      }
      break;
    }
  }
  shape.finish();
}

SceneRigidBody readRigidBody(const Json& value, const std::string& path, const Bounds& bounds) {
  ObjectReader body(value, path);
  SceneRigidBody out;
  RigidBodyDesc& d = out.desc;
  d.name = body.string("name");
  readShape(body, out, bounds);
  if (body.has("density")) {
    if (!out.meshShape) fail(body.fieldPath("density"), "only a mesh shape has a density (give 'mass')");
    if (body.has("mass")) fail(body.fieldPath("density"), "give either 'mass' or 'density', not both");
    out.density = body.positive("density", 1.0);
  }
  d.mass = body.nonNegative("mass", 1.0);
  if (d.mass != 0) bounds.mass(d.mass, body.fieldPath("mass"));
  if (body.has("inertia")) {
    if (out.meshShape) fail(body.fieldPath("inertia"), "a mesh shape's inertia comes from its mesh");
    d.inertia = body.vec3("inertia");
    if (!(d.inertia->minCoeff() > 0)) fail(body.fieldPath("inertia"), "must be three principal moments > 0 (kg·m²)");
  }
  const bool kinematic = body.boolean("kinematic", false);
  d.motion = kinematic ? MotionType::Kinematic : d.mass == 0 ? MotionType::Static : MotionType::Dynamic;
  if ((d.shape.type == ShapeType::Plane || d.shape.type == ShapeType::TriangleMesh) && d.motion == MotionType::Dynamic)
    fail(body.fieldPath("mass"), "a plane or triangle mesh must be static (mass 0) or kinematic");
  d.position = body.vec3("position", Vec3::Zero());
  bounds.coordinates(d.position, body.fieldPath("position"));
  d.orientation = readOrientation(body);
  d.linearVelocity = body.vec3("linear_velocity", Vec3::Zero());
  bounds.speed(d.linearVelocity, body.fieldPath("linear_velocity"));
  d.angularVelocity = body.vec3("angular_velocity", Vec3::Zero());
  bounds.angularSpeed(d.angularVelocity, body.fieldPath("angular_velocity"));
  d.friction = body.nonNegative("friction", d.friction);
  d.restitution = body.numberIn("restitution", d.restitution, 0.0, 1.0);
  d.linearDamping = body.numberIn("linear_damping", d.linearDamping, 0.0, 1.0);
  d.angularDamping = body.numberIn("angular_damping", d.angularDamping, 0.0, 1.0);
  d.canSleep = body.boolean("can_sleep", d.canSleep);
  d.collisionGroup = body.bits("collision_group", d.collisionGroup);
  d.collisionMask = body.bits("collision_mask", d.collisionMask);
  if (body.has("colour")) out.colour = body.colour("colour");
  body.finish();
  return out;
}

SceneJoint readJoint(const Json& value, const std::string& path, const Bounds& bounds) {
  ObjectReader joint(value, path);
  SceneJoint out;
  joint.required("type");
  out.kind = joint.choice("type", scene::kJointNames, SceneJoint::Kind::Hinge);
  out.bodyA = joint.string("body_a");
  if (joint.has("body_b")) out.bodyB = joint.string("body_b");
  if (out.kind == SceneJoint::Kind::Hinge) {
    out.pivot = joint.vec3("pivot");
    bounds.coordinates(out.pivot, joint.fieldPath("pivot"));
    out.axis = joint.vec3("axis");
    if (out.axis.norm() < 1e-9) fail(joint.fieldPath("axis"), "must not be zero");
    if (joint.has("limits")) {
      const Json& limits = joint.required("limits");
      const std::string where = joint.fieldPath("limits");
      if (!limits.is_array() || limits.size() != 2) fail(where, "must be [lower, upper] in rad");
      out.lowerLimit = scene::readNumber(limits[0], where + "/0");
      out.upperLimit = scene::readNumber(limits[1], where + "/1");
      if (!(out.lowerLimit <= out.upperLimit) || out.lowerLimit < -M_PI || out.upperLimit > M_PI)
        fail(where, "must be [lower, upper] with -pi <= lower <= upper <= pi rad, got [" + scene::formatValue(out.lowerLimit) +
                        ", " + scene::formatValue(out.upperLimit) + "]");
    }
    if (joint.has("motor")) {
      ObjectReader motor(joint.required("motor"), joint.fieldPath("motor"));
      out.motor = true;
      out.motorTargetSpeed = motor.number("target_speed");
      motor.required("max_torque");
      out.motorMaxTorque = motor.nonNegative("max_torque", 0.0);
      motor.finish();
    }
  } else {
    for (const char* key : {"limits", "motor"})
      if (joint.has(key)) fail(joint.fieldPath(key), "only a hinge has limits and a motor");
  }
  joint.finish();
  return out;
}

SceneMesh readMesh(const Json& value, const std::string& path, const Bounds& bounds) {
  ObjectReader mesh(value, path);
  SceneMesh out;
  using Kind = SceneMesh::Kind;
  mesh.required("type");
  out.kind = mesh.choice("type", scene::kMeshNames, Kind::ClothGrid);
  constexpr int kMaxCount = 100000;
  auto count = [&](const std::string& key, int low) {
    mesh.required(key);
    return mesh.integer(key, 0, low, kMaxCount);
  };
  switch (out.kind) {
    case Kind::Rope:
      if (mesh.has("path")) {
        const Json& points = mesh.required("path");
        const std::string at = mesh.fieldPath("path");
        if (!points.is_array() || points.size() < 2 || points.size() > 10000)
          fail(at, "must be an array of 2 to 10000 [x, y, z] points");
        for (size_t i = 0; i < points.size(); ++i) {
          out.path.push_back(scene::readVec3(points[i], at + "/" + std::to_string(i)));
          bounds.coordinates(out.path.back(), at + "/" + std::to_string(i));
        }
      } else {
        out.start = mesh.vec3("start");
        bounds.coordinates(out.start, mesh.fieldPath("start"));
        out.end = mesh.vec3("end");
        bounds.coordinates(out.end, mesh.fieldPath("end"));
      }
      out.nodes = count("nodes", 2);
      break;
    case Kind::ClothGrid:
      out.corner = mesh.vec3("corner");
      out.sideU = mesh.vec3("side_u");
      out.sideV = mesh.vec3("side_v");
      bounds.coordinates(out.corner, mesh.fieldPath("corner"));
      bounds.coordinates(out.corner + out.sideU, mesh.fieldPath("side_u") + " (corner + side_u)");
      bounds.coordinates(out.corner + out.sideV, mesh.fieldPath("side_v") + " (corner + side_v)");
      bounds.coordinates(out.corner + out.sideU + out.sideV, mesh.fieldPath("side_v") + " (corner + side_u + side_v)");
      out.columns = count("columns", 2);
      out.rows = count("rows", 2);
      break;
    case Kind::TetBox: {
      out.minCorner = mesh.vec3("min");
      out.maxCorner = mesh.vec3("max");
      bounds.coordinates(out.minCorner, mesh.fieldPath("min"));
      bounds.coordinates(out.maxCorner, mesh.fieldPath("max"));
      const Json& cells = mesh.required("cells");
      const std::string at = mesh.fieldPath("cells");
      if (!cells.is_array() || cells.size() != 3) fail(at, "must be [x, y, z] cell counts");
      for (int k = 0; k < 3; ++k) {
        out.cells[k] = scene::readInteger(cells[k], at + "/" + std::to_string(k));
        if (out.cells[k] < 1 || out.cells[k] > 1000) fail(at + "/" + std::to_string(k), "must be in [1, 1000]");
      }
      break;
    }
    case Kind::TetCylinder:
      out.baseCentre = mesh.vec3("base_centre");
      bounds.coordinates(out.baseCentre, mesh.fieldPath("base_centre"));
      mesh.required("radius");
      out.radius = mesh.positive("radius", 0);
      bounds.size(out.radius, mesh.fieldPath("radius"));
      mesh.required("height");
      out.height = mesh.positive("height", 0);
      bounds.size(out.height, mesh.fieldPath("height"));
      out.rings = count("rings", 1);
      out.sectors = count("sectors", 3);
      out.layers = count("layers", 1);
      break;
    case Kind::Obj:
    case Kind::TetGen: out.file = mesh.string("file"); break;
  }
  mesh.finish();
  return out;
}

void readParadigm(ObjectReader& deformable, SceneDeformable& out) {
  if (!deformable.has("paradigm")) return;
  ObjectReader paradigm(deformable.required("paradigm"), deformable.fieldPath("paradigm"));
  ParadigmSettings& p = out.desc.paradigm;
  paradigm.required("type");
  p.type = paradigm.choice("type", scene::kParadigmNames, ParadigmType::MassSpring);
  switch (p.type) {
    case ParadigmType::MassSpring:
      out.desc.springs.stiffness = paradigm.nonNegative("spring_stiffness", 0.0);
      out.desc.springs.damping = paradigm.nonNegative("spring_damping", 0.0);
      out.desc.springs.implicit = paradigm.boolean("implicit", true);
      break;
    case ParadigmType::PositionBased:
      p.iterations = paradigm.integer("iterations", p.iterations, 1, 1000);
      [[fallthrough]];
    case ParadigmType::ShapeMatching:
      p.stiffness = paradigm.numberIn("stiffness", p.stiffness, 0.0, 1.0, true);
      p.damping = paradigm.numberIn("damping", p.damping, 0.0, 1.0);
      break;
    case ParadigmType::CorotationalFem:
      p.youngsModulus = paradigm.positive("youngs_modulus", p.youngsModulus);
      p.poissonRatio = paradigm.numberIn("poisson_ratio", p.poissonRatio, 0.0, 0.4999);
      break;
  }
  paradigm.finish();
}

void readRowSettings(ObjectReader& deformable, SceneDeformable& out) {
  if (deformable.has("inextensibility")) {
    ObjectReader inextensibility(deformable.required("inextensibility"), deformable.fieldPath("inextensibility"));
    InextensibilitySettings& s = out.desc.inextensibility;
    s.enabled = inextensibility.boolean("enabled", true);
    s.mode = inextensibility.choice("mode", scene::kInextensibilityModeNames, s.mode);
    s.maxForce = inextensibility.positive("max_force", s.maxForce);
    s.shearEdges = inextensibility.boolean("shear_edges", s.shearEdges);
    inextensibility.finish();
  }
  if (deformable.has("bending")) {
    ObjectReader bending(deformable.required("bending"), deformable.fieldPath("bending"));
    BendingSettings& s = out.desc.bending;
    s.enabled = bending.boolean("enabled", true);
    s.maxForce = bending.positive("max_force", s.maxForce);
    s.frequency = bending.positive("frequency", s.frequency);
    s.dampingRatio = bending.nonNegative("damping_ratio", s.dampingRatio);
    bending.finish();
  }
}

SceneFixedNodes readFixedNodes(const Json& value, const std::string& path) {
  ObjectReader fixed(value, path);
  SceneFixedNodes out;
  if (fixed.has("nodes") == fixed.has("region")) fail(path, "give either 'nodes' (indices) or 'region' (a box)");
  if (fixed.has("nodes")) {
    const Json& nodes = fixed.required("nodes");
    if (!nodes.is_array() || nodes.empty()) fail(fixed.fieldPath("nodes"), "must be a non-empty array of node indices");
    for (size_t i = 0; i < nodes.size(); ++i)
      out.nodes.push_back(scene::readInteger(nodes[i], fixed.fieldPath("nodes") + "/" + std::to_string(i)));
  } else {
    ObjectReader region(fixed.required("region"), fixed.fieldPath("region"));
    const Vec3 low = region.vec3("min"), high = region.vec3("max");
    if (!(low.array() <= high.array()).all()) fail(region.path(), "'min' must not exceed 'max'");
    region.finish();
    out.region = std::array<Vec3, 2>{low, high};
  }
  out.maxForce = fixed.positive("max_force", out.maxForce);
  fixed.finish();
  return out;
}

SceneDeformable readDeformable(const Json& value, const std::string& path, const Bounds& bounds) {
  ObjectReader deformable(value, path);
  SceneDeformable out;
  DeformableDesc& d = out.desc;
  d.name = deformable.string("name");
  out.mesh = readMesh(deformable.required("mesh"), deformable.fieldPath("mesh"), bounds);
  if (deformable.has("mass") == deformable.has("density"))
    fail(path, "give either 'mass' (kg, in all) or 'density' (kg/m^3; kg/m^2 for surfaces, kg/m for ropes)");
  if (deformable.has("mass")) {
    out.mass = deformable.positive("mass", 0);
    bounds.mass(*out.mass, deformable.fieldPath("mass"));
  }
  if (deformable.has("density")) out.density = deformable.positive("density", 0);
  readParadigm(deformable, out);
  readRowSettings(deformable, out);
  d.collision.enabled = deformable.boolean("collision", d.collision.enabled);
  d.collision.selfCollision = deformable.boolean("self_collision", d.collision.selfCollision);
  d.collision.thickness = deformable.nonNegative("thickness", d.collision.thickness);
  if (d.collision.thickness > bounds.limits.maxSize) bounds.size(d.collision.thickness, deformable.fieldPath("thickness"));
  d.collision.friction = deformable.nonNegative("friction", d.collision.friction);
  d.collision.group = deformable.bits("collision_group", d.collision.group);
  d.collision.mask = deformable.bits("collision_mask", d.collision.mask);
  d.damping = deformable.nonNegative("damping", d.damping);
  d.rowSolver = deformable.choice("row_solver", scene::kRowSolverNames, d.rowSolver);
  out.initialVelocity = deformable.vec3("initial_velocity", Vec3::Zero());
  bounds.speed(out.initialVelocity, deformable.fieldPath("initial_velocity"));
  forEachElement(deformable, "fixed",
                 [&](const Json& element, const std::string& at) { out.fixed.push_back(readFixedNodes(element, at)); });
  if (deformable.has("colour")) out.colour = deformable.colour("colour");
  deformable.finish();
  return out;
}

SceneAnchor readAnchor(const Json& value, const std::string& path, const Bounds& bounds) {
  ObjectReader anchor(value, path);
  SceneAnchor out;
  out.deformable = anchor.string("deformable");
  out.body = anchor.string("body");
  const int ways = int(anchor.has("node")) + int(anchor.has("nearest")) + int(anchor.has("face"));
  if (ways != 1) fail(path, "give exactly one of 'node' (an index), 'nearest' (a point) or 'face' (a triangle index)");
  if (anchor.has("node")) out.node = anchor.integer("node", 0, 0, std::numeric_limits<int>::max());
  if (anchor.has("nearest")) {
    out.nearest = anchor.vec3("nearest");
    bounds.coordinates(*out.nearest, anchor.fieldPath("nearest"));
  }
  if (anchor.has("face")) {
    out.face = anchor.integer("face", 0, 0, std::numeric_limits<int>::max());
    if (anchor.has("barycentric")) {
      const Json& weights = anchor.required("barycentric");
      const std::string at = anchor.fieldPath("barycentric");
      if (!weights.is_array() || weights.size() != 3) fail(at, "must be three weights [a, b, c]");
      double sum = 0;
      for (int k = 0; k < 3; ++k) {
        out.barycentric[k] = scene::readNumber(weights[k], at + "/" + std::to_string(k));
        if (out.barycentric[k] < 0) fail(at + "/" + std::to_string(k), "must be >= 0");
        sum += out.barycentric[k];
      }
      if (std::abs(sum - 1.0) > 1e-6) fail(at, "must sum to 1, they sum to " + scene::formatValue(sum));
    }
  } else if (anchor.has("barycentric")) {
    fail(anchor.fieldPath("barycentric"), "only goes with 'face'");
  }
  if (anchor.has("local_point")) {
    out.localPoint = anchor.vec3("local_point");
    bounds.coordinates(*out.localPoint, anchor.fieldPath("local_point"));
  }
  out.maxForce = anchor.positive("max_force", out.maxForce);
  anchor.finish();
  return out;
}

void readSolver(ObjectReader& root, Scene& out) {
  if (!root.has("solver")) return;
  ObjectReader solver(root.required("solver"), root.fieldPath("solver"));
  SolverSettings& s = out.settings.solver;
  s.iterations = solver.integer("iterations", s.iterations, 1, 1000);
  s.substeps = solver.integer("substeps", s.substeps, 1, 1000);
  s.baumgarte = solver.numberIn("baumgarte", s.baumgarte, 0.0, 1.0);
  s.warmStart = solver.boolean("warm_start", s.warmStart);
  s.friction = solver.choice("friction_model", scene::kFrictionModelNames, s.friction);
  s.contactSlop = solver.nonNegative("contact_slop", s.contactSlop);
  solver.finish();
}

// Names are unique within their kind, and every reference names something that exists.
void checkNames(const Scene& scene) {
  std::map<std::string, int> rigid, deformable;
  for (size_t i = 0; i < scene.rigidBodies.size(); ++i) {
    const std::string& name = scene.rigidBodies[i].desc.name;
    if (name.empty()) fail("/rigid_bodies/" + std::to_string(i) + "/name", "must not be empty");
    if (!rigid.emplace(name, int(i)).second)
      fail("/rigid_bodies/" + std::to_string(i) + "/name", "another rigid body is already named '" + name + "'");
  }
  for (size_t i = 0; i < scene.deformables.size(); ++i) {
    const std::string& name = scene.deformables[i].desc.name;
    if (name.empty()) fail("/deformables/" + std::to_string(i) + "/name", "must not be empty");
    if (!deformable.emplace(name, int(i)).second)
      fail("/deformables/" + std::to_string(i) + "/name", "another deformable is already named '" + name + "'");
  }
  auto needRigid = [&](const std::string& name, const std::string& path) {
    if (!rigid.count(name)) fail(path, "no rigid body is named '" + name + "'");
  };
  for (size_t i = 0; i < scene.joints.size(); ++i) {
    const std::string at = "/joints/" + std::to_string(i);
    needRigid(scene.joints[i].bodyA, at + "/body_a");
    if (scene.joints[i].bodyB) needRigid(*scene.joints[i].bodyB, at + "/body_b");
    if (scene.joints[i].bodyB == scene.joints[i].bodyA) fail(at + "/body_b", "must differ from body_a");
  }
  for (size_t i = 0; i < scene.anchors.size(); ++i) {
    const std::string at = "/anchors/" + std::to_string(i);
    if (!deformable.count(scene.anchors[i].deformable))
      fail(at + "/deformable", "no deformable is named '" + scene.anchors[i].deformable + "'");
    needRigid(scene.anchors[i].body, at + "/body");
  }
}

// nlohmann keeps the last of two equal keys; a scene file must not have them.
Json parseRefusingDuplicates(std::string_view text) {
  std::vector<std::set<std::string>> openObjects;
  auto callback = [&](int, Json::parse_event_t event, Json& parsed) {
    if (event == Json::parse_event_t::object_start) openObjects.emplace_back();
    if (event == Json::parse_event_t::object_end) openObjects.pop_back();
    if (event == Json::parse_event_t::key && !openObjects.back().insert(parsed.get<std::string>()).second)
      throw scene::ReadError("field '" + parsed.get<std::string>() + "' appears twice in one object");
    return true;
  };
  try {
    return Json::parse(text.begin(), text.end(), callback);
  } catch (const Json::exception& error) {  // syntax errors, and numbers beyond a double
    std::string message = error.what();
    if (const size_t cut = message.find("] "); message.rfind("[json.exception", 0) == 0 && cut != std::string::npos)
      message = message.substr(cut + 2);
    throw scene::ReadError("not valid JSON: " + message);
  }
}

}  // namespace

Result<Scene> parseScene(std::string_view text, const std::string& fileName, const std::string& directory,
                         const Limits& limits) {
  try {
    const Json json = parseRefusingDuplicates(text);
    ObjectReader root(json, "");
    Scene scene;
    scene.sourceFile = fileName;
    scene.directory = directory;
    const int format = root.integer("format", 0, std::numeric_limits<int>::min(), std::numeric_limits<int>::max());
    root.required("format");
    if (format != kSceneFormatVersion)
      fail("/format", "this Tandem reads format " + std::to_string(kSceneFormatVersion) + ", the file has " +
                          std::to_string(format));
    scene.name = root.string("name", "");
    scene.description = root.string("description", "");
    scene.timeStep = root.numberIn("time_step", scene.timeStep, limits.minTimeStep, 1.0);
    scene.duration = root.positive("duration", scene.duration);
    if (const double steps = std::round(scene.duration / scene.timeStep); steps > static_cast<double>(limits.maxSteps))
      fail(root.has("duration") ? "/duration" : "/time_step",
           scene::formatValue(scene.duration) + " s at a time step of " + scene::formatValue(scene.timeStep) + " s is " +
               scene::formatValue(steps) + " steps, more than a run's " + std::to_string(limits.maxSteps) +
               " (Limits::maxSteps)");
    scene.settings.gravity = root.vec3("gravity", scene.settings.gravity);
    if (scene.settings.gravity.stableNorm() > limits.maxGravity)
      fail("/gravity", scene::formatValue(scene.settings.gravity.stableNorm()) + " m/s^2 is more than " +
                           scene::formatValue(limits.maxGravity) + " m/s^2 (Limits::maxGravity)");
    scene.settings.divergenceSpeed = root.positive("divergence_speed", scene.settings.divergenceSpeed);
    const Bounds bounds{limits, scene.settings.divergenceSpeed};
    readSolver(root, scene);
    forEachElement(root, "rigid_bodies", [&](const Json& v, const std::string& at) {
      scene.rigidBodies.push_back(readRigidBody(v, at, bounds));
    });
    forEachElement(root, "joints",
                   [&](const Json& v, const std::string& at) { scene.joints.push_back(readJoint(v, at, bounds)); });
    forEachElement(root, "deformables", [&](const Json& v, const std::string& at) {
      scene.deformables.push_back(readDeformable(v, at, bounds));
    });
    forEachElement(root, "anchors",
                   [&](const Json& v, const std::string& at) { scene.anchors.push_back(readAnchor(v, at, bounds)); });
    root.finish();
    checkNames(scene);
    return scene;
  } catch (const scene::ReadError& error) {
    return Error{fileName + ": " + error.what()};
  }
}

Result<Scene> loadScene(const std::string& path, const Limits& limits) {
  Result<std::string> text = readInputFile(path, limits.maxSceneFileBytes, "scene file", "Limits::maxSceneFileBytes");
  if (!text) return Error{text.message()};
  const std::string directory = std::filesystem::path(path).parent_path().string();
  return parseScene(*text, path, directory.empty() ? "." : directory, limits);
}

}  // namespace tandem
