// Scene → scene file. Every field is written (defaults too, so a written file documents what the
// scene does); nlohmann writes doubles with enough digits to read back the same bits.
#include "scene/scene_names.h"

#include <tandem/scene_file.h>

#include <nlohmann/json.hpp>

#include <cmath>

namespace tandem {
namespace {

using Json = nlohmann::ordered_json;

Json vec(const Vec3& v) { return Json::array({v.x(), v.y(), v.z()}); }
Json colourJson(const Colour& c) { return Json::array({c[0], c[1], c[2]}); }

Json shapeJson(const SceneRigidBody& body) {
  const RigidShape& s = body.desc.shape;
  if (body.meshShape) {
    const MeshBodyOptions& options = body.meshShape->options;
    return Json{{"type", "mesh"},
                {"file", body.meshShape->file},
                {"collision", scene::nameOf(scene::kMeshCollisionNames, options.collision)},
                {"max_hull_vertices", options.maxHullVertices},
                {"scale", options.scale}};
  }
  Json shape{{"type", scene::nameOf(scene::kShapeNames, s.type)}};
  switch (s.type) {
    case ShapeType::Box: shape["half_extents"] = vec(s.halfExtents); break;
    case ShapeType::Sphere: shape["radius"] = s.radius; break;
    case ShapeType::Cylinder:
    case ShapeType::Capsule:
      shape["radius"] = s.radius;
      shape["half_height"] = s.halfHeight;
      break;
    case ShapeType::Plane:
      shape["normal"] = vec(s.planeNormal);
      shape["offset"] = s.planeOffset;
      break;
    case ShapeType::ConvexHull:
    case ShapeType::TriangleMesh: {
      if (!body.shapeFile.empty()) {
        shape["file"] = body.shapeFile;
        break;
      }
      Json points = Json::array();
      for (const Vec3& p : s.points) points.push_back(vec(p));
      if (s.type == ShapeType::ConvexHull) {
        shape["points"] = points;
        break;
      }
      shape["vertices"] = points;
      Json triangles = Json::array();
      for (const auto& t : s.triangles) triangles.push_back({t[0], t[1], t[2]});
      shape["triangles"] = triangles;
      break;
    }
    case ShapeType::Compound: {
      Json hulls = Json::array();
      for (const std::vector<Vec3>& hull : s.hulls) {
        Json points = Json::array();
        for (const Vec3& p : hull) points.push_back(vec(p));
        hulls.push_back(points);
      }
      shape["hulls"] = hulls;
      break;
    }
  }
  return shape;
}

Json rigidJson(const SceneRigidBody& body) {
  const RigidBodyDesc& d = body.desc;
  const Quat& q = d.orientation;
  Json out{{"name", d.name},
           {"shape", shapeJson(body)},
           {"mass", d.motion == MotionType::Dynamic ? d.mass : 0.0},
           {"kinematic", d.motion == MotionType::Kinematic},
           {"position", vec(d.position)},
           {"orientation", {q.w(), q.x(), q.y(), q.z()}},
           {"linear_velocity", vec(d.linearVelocity)},
           {"angular_velocity", vec(d.angularVelocity)},
           {"friction", d.friction},
           {"restitution", d.restitution},
           {"linear_damping", d.linearDamping},
           {"angular_damping", d.angularDamping},
           {"can_sleep", d.canSleep},
           {"collision_group", d.collisionGroup},
           {"collision_mask", d.collisionMask}};
  if (body.density) {
    out.erase("mass");
    out["density"] = *body.density;
  }
  if (d.inertia && !body.meshShape && d.motion == MotionType::Dynamic) out["inertia"] = vec(*d.inertia);
  if (body.colour) out["colour"] = colourJson(*body.colour);
  return out;
}

Json jointJson(const SceneJoint& joint) {
  Json out{{"type", scene::nameOf(scene::kJointNames, joint.kind)}, {"body_a", joint.bodyA}};
  if (joint.bodyB) out["body_b"] = *joint.bodyB;
  if (joint.kind == SceneJoint::Kind::Hinge) {
    out["pivot"] = vec(joint.pivot);
    out["axis"] = vec(joint.axis);
    if (joint.lowerLimit <= joint.upperLimit) out["limits"] = {joint.lowerLimit, joint.upperLimit};
    if (joint.motor) out["motor"] = {{"target_speed", joint.motorTargetSpeed}, {"max_torque", joint.motorMaxTorque}};
  }
  return out;
}

// "type" from the table the reader reads it with, then the kind's own fields.
Json meshJson(const SceneMesh& mesh) {
  using Kind = SceneMesh::Kind;
  Json out{{"type", scene::nameOf(scene::kMeshNames, mesh.kind)}};
  switch (mesh.kind) {
    case Kind::Rope:
      if (!mesh.path.empty()) {
        out["path"] = Json::array();
        for (const Vec3& p : mesh.path) out["path"].push_back(vec(p));
      } else {
        out["start"] = vec(mesh.start);
        out["end"] = vec(mesh.end);
      }
      out["nodes"] = mesh.nodes;
      break;
    case Kind::ClothGrid:
      out["corner"] = vec(mesh.corner);
      out["side_u"] = vec(mesh.sideU);
      out["side_v"] = vec(mesh.sideV);
      out["columns"] = mesh.columns;
      out["rows"] = mesh.rows;
      break;
    case Kind::TetBox:
      out["min"] = vec(mesh.minCorner);
      out["max"] = vec(mesh.maxCorner);
      out["cells"] = {mesh.cells[0], mesh.cells[1], mesh.cells[2]};
      break;
    case Kind::TetCylinder:
      out["base_centre"] = vec(mesh.baseCentre);
      out["radius"] = mesh.radius;
      out["height"] = mesh.height;
      out["rings"] = mesh.rings;
      out["sectors"] = mesh.sectors;
      out["layers"] = mesh.layers;
      break;
    case Kind::Obj:
    case Kind::TetGen: out["file"] = mesh.file; break;
  }
  return out;
}

Json paradigmJson(const DeformableDesc& d) {
  const ParadigmSettings& p = d.paradigm;
  Json out{{"type", scene::nameOf(scene::kParadigmNames, p.type)}};
  switch (p.type) {
    case ParadigmType::MassSpring:
      out["spring_stiffness"] = d.springs.stiffness;
      out["spring_damping"] = d.springs.damping;
      out["implicit"] = d.springs.implicit;
      break;
    case ParadigmType::PositionBased: out["iterations"] = p.iterations; [[fallthrough]];
    case ParadigmType::ShapeMatching:
      out["stiffness"] = p.stiffness;
      out["damping"] = p.damping;
      break;
    case ParadigmType::CorotationalFem:
      out["youngs_modulus"] = p.youngsModulus;
      out["poisson_ratio"] = p.poissonRatio;
      break;
  }
  return out;
}

// Unbounded forces are the default and have no JSON spelling: they are left out.
void putMaxForce(Json& out, double maxForce) {
  if (std::isfinite(maxForce)) out["max_force"] = maxForce;
}

Json deformableJson(const SceneDeformable& deformable) {
  const DeformableDesc& d = deformable.desc;
  Json out{{"name", d.name}, {"mesh", meshJson(deformable.mesh)}};
  if (deformable.mass) out["mass"] = *deformable.mass;
  if (deformable.density) out["density"] = *deformable.density;
  out["paradigm"] = paradigmJson(d);
  Json inextensibility{{"enabled", d.inextensibility.enabled},
                       {"mode", scene::nameOf(scene::kInextensibilityModeNames, d.inextensibility.mode)},
                       {"shear_edges", d.inextensibility.shearEdges}};
  putMaxForce(inextensibility, d.inextensibility.maxForce);
  out["inextensibility"] = inextensibility;
  out["bending"] = {{"enabled", d.bending.enabled},
                    {"max_force", d.bending.maxForce},
                    {"frequency", d.bending.frequency},
                    {"damping_ratio", d.bending.dampingRatio}};
  out["collision"] = d.collision.enabled;
  out["self_collision"] = d.collision.selfCollision;
  out["thickness"] = d.collision.thickness;
  out["friction"] = d.collision.friction;
  out["collision_group"] = d.collision.group;
  out["collision_mask"] = d.collision.mask;
  out["damping"] = d.damping;
  out["row_solver"] = scene::nameOf(scene::kRowSolverNames, d.rowSolver);
  out["initial_velocity"] = vec(deformable.initialVelocity);
  Json fixed = Json::array();
  for (const SceneFixedNodes& f : deformable.fixed) {
    Json entry;
    if (f.region)
      entry["region"] = {{"min", vec((*f.region)[0])}, {"max", vec((*f.region)[1])}};
    else
      entry["nodes"] = f.nodes;
    putMaxForce(entry, f.maxForce);
    fixed.push_back(entry);
  }
  out["fixed"] = fixed;
  if (deformable.colour) out["colour"] = colourJson(*deformable.colour);
  return out;
}

Json anchorJson(const SceneAnchor& anchor) {
  Json out{{"deformable", anchor.deformable}, {"body", anchor.body}};
  if (anchor.node) out["node"] = *anchor.node;
  if (anchor.nearest) out["nearest"] = vec(*anchor.nearest);
  if (anchor.face) {
    out["face"] = *anchor.face;
    out["barycentric"] = {anchor.barycentric[0], anchor.barycentric[1], anchor.barycentric[2]};
  }
  if (anchor.localPoint) out["local_point"] = vec(*anchor.localPoint);
  putMaxForce(out, anchor.maxForce);
  return out;
}

}  // namespace

std::string sceneToJson(const Scene& scene) {
  const SolverSettings& solver = scene.settings.solver;
  Json out{{"format", kSceneFormatVersion},
           {"name", scene.name},
           {"description", scene.description},
           {"time_step", scene.timeStep},
           {"duration", scene.duration},
           {"gravity", vec(scene.settings.gravity)},
           {"divergence_speed", scene.settings.divergenceSpeed},
           {"solver",
            {{"iterations", solver.iterations},
             {"substeps", solver.substeps},
             {"baumgarte", solver.baumgarte},
             {"warm_start", solver.warmStart},
             {"friction_model", scene::nameOf(scene::kFrictionModelNames, solver.friction)},
             {"contact_slop", solver.contactSlop}}}};
  Json& rigid = out["rigid_bodies"] = Json::array();
  for (const SceneRigidBody& body : scene.rigidBodies) rigid.push_back(rigidJson(body));
  Json& joints = out["joints"] = Json::array();
  for (const SceneJoint& joint : scene.joints) joints.push_back(jointJson(joint));
  Json& deformables = out["deformables"] = Json::array();
  for (const SceneDeformable& deformable : scene.deformables) deformables.push_back(deformableJson(deformable));
  Json& anchors = out["anchors"] = Json::array();
  for (const SceneAnchor& anchor : scene.anchors) anchors.push_back(anchorJson(anchor));
  return out.dump(2) + "\n";
}

}  // namespace tandem
