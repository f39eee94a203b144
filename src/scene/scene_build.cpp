// Scene → World: meshes generated or loaded, masses from mass or density, names turned into ids,
// and whatever the world refuses reported with the JSON path of what it refused.
#include <tandem/scene_file.h>

#include "format.h"

#include <filesystem>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <optional>

namespace tandem {
namespace {

struct BuildError {
  std::string message;
};

std::string resolve(const Scene& scene, const std::string& file) {
  const std::filesystem::path path(file);
  return path.is_absolute() ? file : (std::filesystem::path(scene.directory) / path).string();
}

// Tet volume, else triangle area, else edge length: what a density is per.
double meshMeasure(const DeformableMesh& mesh) {
  const auto& x = mesh.positions;
  double measure = 0;
  if (!mesh.tetrahedra.empty()) {
    for (const auto& t : mesh.tetrahedra)
      measure += std::abs((x[t[1]] - x[t[0]]).cross(x[t[2]] - x[t[0]]).dot(x[t[3]] - x[t[0]])) / 6.0;
  } else if (!mesh.triangles.empty()) {
    for (const auto& t : mesh.triangles) measure += 0.5 * (x[t[1]] - x[t[0]]).cross(x[t[2]] - x[t[0]]).norm();
  } else {
    for (const auto& e : mesh.edges) measure += (x[e[1]] - x[e[0]]).norm();
  }
  return measure;
}

// The mesh with unit total mass, spread as its generator or loader spreads it.
Result<DeformableMesh> makeMesh(const Scene& scene, const SceneMesh& m, const Limits& limits) {
  using Kind = SceneMesh::Kind;
  switch (m.kind) {
    case Kind::Rope:
      return m.path.empty() ? makeRope(m.start, m.end, m.nodes, 1.0, limits)
                            : makeRopeAlongPath(m.path, m.nodes, 1.0, limits);
    case Kind::ClothGrid: return makeClothGrid(m.corner, m.sideU, m.sideV, m.columns, m.rows, 1.0, limits);
    case Kind::TetBox: return makeTetBox(m.minCorner, m.maxCorner, m.cells[0], m.cells[1], m.cells[2], 1.0, limits);
    case Kind::TetCylinder:
      return makeTetCylinder(m.baseCentre, m.radius, m.height, m.rings, m.sectors, m.layers, 1.0, limits);
    case Kind::Obj: return loadObj(resolve(scene, m.file), 1.0, limits);
    case Kind::TetGen: {
      Result<DeformableMesh> mesh = loadTetGen(resolve(scene, m.file), 1.0, limits);
      if (!mesh) return mesh;
      double total = 0;
      for (double mass : mesh->masses) total += mass;
      for (double& mass : mesh->masses) mass /= total;
      return mesh;
    }
  }
  return Error{"unknown mesh kind"};
}

std::string bounds(double low, double high) {
  char text[64];
  std::snprintf(text, sizeof text, "[%g, %g]", low, high);
  return text;
}

// Points farther out than Limits::maxCoordinate (a mesh file's, or an OBJ shape's) are refused.
void checkCoordinates(const std::vector<Vec3>& points, const Limits& limits, const std::string& path) {
  for (size_t i = 0; i < points.size(); ++i)
    if (points[i].cwiseAbs().maxCoeff() > limits.maxCoordinate)
      throw BuildError{path + ": point " + std::to_string(i) + " at " + formatNumber(points[i].cwiseAbs().maxCoeff()) +
                       " m from the origin along an axis is farther than " + formatNumber(limits.maxCoordinate) +
                       " m (Limits::maxCoordinate)"};
}

DeformableMesh deformableMesh(const Scene& scene, const SceneDeformable& deformable, const std::string& path,
                              const Limits& limits) {
  Result<DeformableMesh> mesh = makeMesh(scene, deformable.mesh, limits);
  if (!mesh) throw BuildError{path + "/mesh: " + mesh.message()};
  checkCoordinates(mesh->positions, limits, path + "/mesh");
  const double totalMass = deformable.mass ? *deformable.mass : *deformable.density * meshMeasure(*mesh);
  if (!(totalMass > 0 && std::isfinite(totalMass)))
    throw BuildError{path + "/density: the mesh has no volume, area or length to give a mass"};
  if (totalMass < limits.minMass || totalMass > limits.maxMass)
    throw BuildError{path + (deformable.mass ? std::string("/mass: ") : std::string("/density: the total mass, ")) +
                     formatNumber(totalMass) + " kg, is outside " + bounds(limits.minMass, limits.maxMass) +
                     " kg (Limits::minMass, maxMass)"};
  for (double& mass : mesh->masses) mass *= totalMass;
  return std::move(mesh).value();
}

// A mesh body: its shape, mass and inertia, and the pose of its centre of mass and principal
// axes from where the scene places the mesh's own frame. `frame` gets the body frame in the mesh's.
RigidBodyDesc meshRigidDesc(const Scene& scene, const SceneRigidBody& body, const std::string& path,
                            const Limits& limits, MeshBody& frame) {
  const std::string file = resolve(scene, body.meshShape->file);
  Result<SurfaceMesh> surface = loadObjSurface(file, limits);
  if (!surface) throw BuildError{path + "/shape/file: " + surface.message()};
  checkCoordinates(surface->positions, limits, path + "/shape/file");
  Result<MeshBody> mesh = makeMeshBody(*surface, body.meshShape->options, file);
  if (!mesh) throw BuildError{path + "/shape/file: " + mesh.message()};
  RigidBodyDesc desc = body.desc;
  if (desc.motion == MotionType::Dynamic && body.density) {
    desc.mass = *body.density * mesh->massProperties.volume;
    if (!(desc.mass >= limits.minMass && desc.mass <= limits.maxMass))
      throw BuildError{path + "/density: the body's mass, " + formatNumber(desc.mass) + " kg (" +
                       formatNumber(mesh->massProperties.volume) + " m³ of the mesh), is outside " +
                       bounds(limits.minMass, limits.maxMass) + " kg (Limits::minMass, maxMass)"};
  }
  const RigidBodyDesc placed = mesh->desc(desc.name, desc.mass, desc.position, desc.orientation);
  desc.shape = placed.shape;
  desc.position = placed.position;
  desc.orientation = placed.orientation;
  desc.inertia = desc.motion == MotionType::Dynamic ? placed.inertia : std::nullopt;
  frame = std::move(mesh).value();
  frame.shape = RigidShape{};  // only the frame is kept
  return desc;
}

RigidBodyDesc rigidDesc(const Scene& scene, const SceneRigidBody& body, const std::string& path, const Limits& limits,
                        std::optional<MeshBody>& meshFrame) {
  if (body.meshShape) return meshRigidDesc(scene, body, path, limits, meshFrame.emplace());
  RigidBodyDesc desc = body.desc;
  if (body.shapeFile.empty()) return desc;
  Result<DeformableMesh> obj = loadObj(resolve(scene, body.shapeFile), 1.0, limits);
  if (!obj) throw BuildError{path + "/shape/file: " + obj.message()};
  checkCoordinates(obj->positions, limits, path + "/shape/file");
  desc.shape.points = obj->positions;
  desc.shape.triangles = obj->triangles;
  if (desc.shape.type == ShapeType::ConvexHull) desc.shape.triangles.clear();
  return desc;
}

void check(const Status& status, const std::string& path) {
  if (!status) throw BuildError{path + ": " + status.message()};
}

int32_t nodeIndex(int32_t node, int32_t nodeCount, const std::string& path) {
  if (node < 0 || node >= nodeCount)
    throw BuildError{path + ": node " + std::to_string(node) + " is out of range (the mesh has " +
                     std::to_string(nodeCount) + " nodes)"};
  return node;
}

void addFixedNodes(World& world, DeformableId id, const SceneFixedNodes& fixed, const std::string& path) {
  const std::span<const Vec3> x = world.nodePositions(id);
  std::vector<int32_t> nodes;
  if (fixed.region) {
    const auto& [low, high] = *fixed.region;
    for (int32_t n = 0; n < static_cast<int32_t>(x.size()); ++n)
      if ((x[n].array() >= low.array()).all() && (x[n].array() <= high.array()).all()) nodes.push_back(n);
    if (nodes.empty()) throw BuildError{path + "/region: holds no node of the mesh"};
  } else {
    for (size_t i = 0; i < fixed.nodes.size(); ++i)
      nodes.push_back(nodeIndex(fixed.nodes[i], static_cast<int32_t>(x.size()), path + "/nodes/" + std::to_string(i)));
  }
  for (int32_t n : nodes) check(world.addFixedPoint(id, n, x[n], fixed.maxForce).status(), path);
}

AnchorDesc anchorDesc(const World& world, DeformableId deformable, RigidBodyId body, const SceneAnchor& anchor,
                      const std::string& path) {
  const std::span<const Vec3> x = world.nodePositions(deformable);
  const int32_t nodeCount = static_cast<int32_t>(x.size());
  AnchorDesc desc;
  desc.deformable = deformable;
  desc.body = body;
  desc.localPoint = anchor.localPoint;
  desc.maxForce = anchor.maxForce;
  if (anchor.node) desc.nodes[0] = nodeIndex(*anchor.node, nodeCount, path + "/node");
  if (anchor.nearest) {
    int32_t nearest = 0;
    for (int32_t n = 1; n < nodeCount; ++n)
      if ((x[n] - *anchor.nearest).squaredNorm() < (x[nearest] - *anchor.nearest).squaredNorm()) nearest = n;
    desc.nodes[0] = nearest;
  }
  if (anchor.face) {
    const auto& triangles = world.restMesh(deformable).triangles;
    if (*anchor.face >= static_cast<int32_t>(triangles.size()))
      throw BuildError{path + "/face: triangle " + std::to_string(*anchor.face) + " is out of range (the mesh has " +
                       std::to_string(triangles.size()) + " triangles)"};
    const auto& triangle = triangles[*anchor.face];
    desc.nodeCount = 3;
    for (int k = 0; k < 3; ++k) {
      desc.nodes[k] = triangle[k];
      desc.weights[k] = anchor.barycentric[k];
    }
  }
  return desc;
}

// The heaviest and the lightest dynamic mass of the scene (rigid bodies, and deformables' nodes),
// with where each comes from: a ratio past Limits::maxMassRatio is more than double precision
// and the solver's iterations can hold together.
struct MassRange {
  struct Mass {
    double kg = 0.0;
    std::string path;  // where it is set in the file
    std::string what;  // "the body", "a node"
  };
  Mass lightest{INFINITY, "", ""}, heaviest{0.0, "", ""};

  void add(double kg, const std::string& path, const char* what) {
    if (kg < lightest.kg) lightest = {kg, path, what};
    if (kg > heaviest.kg) heaviest = {kg, path, what};
  }
  void check(const Limits& limits) const {
    if (heaviest.kg == 0.0 || heaviest.kg / lightest.kg <= limits.maxMassRatio) return;
    throw BuildError{lightest.path + ": " + lightest.what + " of " + formatNumber(lightest.kg) + " kg against " +
                     heaviest.what + " of " + formatNumber(heaviest.kg) + " kg (" + heaviest.path +
                     ") is a mass ratio of " + formatNumber(heaviest.kg / lightest.kg) + ", more than " +
                     formatNumber(limits.maxMassRatio) + " (Limits::maxMassRatio)"};
  }
};

void build(const Scene& scene, World& world, const Limits& limits) {
  MassRange masses;
  check(world.setSettings(scene.settings), "/solver");
  std::map<std::string, RigidBodyId> rigid;
  std::map<std::string, MeshBody> meshFrames;  // mesh bodies: their frame in the mesh's
  for (size_t i = 0; i < scene.rigidBodies.size(); ++i) {
    const std::string path = "/rigid_bodies/" + std::to_string(i);
    std::optional<MeshBody> meshFrame;
    const RigidBodyDesc desc = rigidDesc(scene, scene.rigidBodies[i], path, limits, meshFrame);
    Result<RigidBodyId> id = world.addRigidBody(desc);
    check(id.status(), path);
    if (desc.motion == MotionType::Dynamic)
      masses.add(desc.mass, path + (scene.rigidBodies[i].density ? "/density" : "/mass"), "the body");
    rigid[desc.name] = *id;
    if (meshFrame) meshFrames[desc.name] = std::move(*meshFrame);
  }
  for (size_t i = 0; i < scene.joints.size(); ++i) {
    const SceneJoint& joint = scene.joints[i];
    std::optional<RigidBodyId> bodyB;
    if (joint.bodyB) bodyB = rigid.at(*joint.bodyB);
    HingeDesc hinge{rigid.at(joint.bodyA), bodyB, joint.pivot, joint.axis};
    hinge.lowerLimit = joint.lowerLimit;
    hinge.upperLimit = joint.upperLimit;
    hinge.motor = joint.motor;
    hinge.motorTargetSpeed = joint.motorTargetSpeed;
    hinge.motorMaxTorque = joint.motorMaxTorque;
    const Status status = joint.kind == SceneJoint::Kind::Hinge
                              ? world.addHinge(hinge).status()
                              : world.addFixedJoint({rigid.at(joint.bodyA), bodyB}).status();
    check(status, "/joints/" + std::to_string(i));
  }
  std::map<std::string, DeformableId> deformables;
  for (size_t i = 0; i < scene.deformables.size(); ++i) {
    const SceneDeformable& deformable = scene.deformables[i];
    const std::string path = "/deformables/" + std::to_string(i);
    DeformableDesc desc = deformable.desc;
    desc.mesh = deformableMesh(scene, deformable, path, limits);
    const std::string massPath = path + (deformable.mass ? "/mass" : "/density");
    const auto [lightest, heaviest] = std::minmax_element(desc.mesh.masses.begin(), desc.mesh.masses.end());
    masses.add(*lightest, massPath, "a node");
    masses.add(*heaviest, massPath, "a node");
    masses.check(limits);
    Result<DeformableId> id = world.addDeformable(desc);
    check(id.status(), path);
    deformables[desc.name] = *id;
    if (deformable.initialVelocity != Vec3::Zero())
      for (int32_t n = 0; n < desc.mesh.nodeCount(); ++n) check(world.setNodeVelocity(*id, n, deformable.initialVelocity), path);
    for (size_t f = 0; f < deformable.fixed.size(); ++f)
      addFixedNodes(world, *id, deformable.fixed[f], path + "/fixed/" + std::to_string(f));
  }
  for (size_t i = 0; i < scene.anchors.size(); ++i) {
    const SceneAnchor& anchor = scene.anchors[i];
    const std::string path = "/anchors/" + std::to_string(i);
    AnchorDesc desc = anchorDesc(world, deformables.at(anchor.deformable), rigid.at(anchor.body), anchor, path);
    // A mesh body's points are written in the mesh's frame.
    if (desc.localPoint && meshFrames.count(anchor.body)) desc.localPoint = meshFrames.at(anchor.body).toBodyFrame(*desc.localPoint);
    check(world.addAnchor(desc).status(), path);
  }
  masses.check(limits);
}

}  // namespace

Status buildScene(const Scene& scene, World& world, const Limits& limits) {
  const std::string file = scene.sourceFile.empty() ? "scene" : scene.sourceFile;
  try {
    build(scene, world, limits);
    return {};
  } catch (const BuildError& error) {
    return Error{file + ": " + error.message};
  } catch (const std::out_of_range&) {
    return Error{file + ": a joint or anchor names a body the scene does not have"};
  }
}

}  // namespace tandem
