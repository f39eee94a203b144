// Scenes as files: a JSON scene (docs/scene-format.md) read into plain data, checked, written
// back, and built into a World.
//
// Everything in a Scene refers to bodies by name, as the file does; buildScene turns names into
// ids. Meshes are generated or loaded when the scene is built, from files found relative to the
// scene file.
#pragma once

#include <tandem/export.h>
#include <tandem/limits.h>
#include <tandem/mesh_body.h>
#include <tandem/world.h>

#include <array>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace tandem {

inline constexpr int kSceneFormatVersion = 1;

// How a body looks: red, green and blue in [0, 1], as displayed (sRGB, like "#rrggbb").
using Colour = std::array<double, 3>;

// Where a deformable's mesh comes from: a generator and its parameters, or a file.
struct SceneMesh {
  enum class Kind { Rope, ClothGrid, TetBox, TetCylinder, Obj, TetGen };
  Kind kind = Kind::ClothGrid;
  // rope: from start to end, or along path when it is not empty
  Vec3 start = Vec3::Zero(), end = Vec3::UnitX();
  std::vector<Vec3> path;
  int nodes = 2;
  // cloth grid
  Vec3 corner = Vec3::Zero(), sideU = Vec3::UnitX(), sideV = Vec3::UnitZ();
  int columns = 2, rows = 2;
  // tet box
  Vec3 minCorner = Vec3::Zero(), maxCorner = Vec3::Ones();
  std::array<int, 3> cells{1, 1, 1};
  // tet cylinder
  Vec3 baseCentre = Vec3::Zero();
  double radius = 0.1, height = 0.2;
  int rings = 2, sectors = 8, layers = 3;
  // obj, tetgen: the path as written in the file (an OBJ file; TetGen's base path without
  // .node/.ele), relative to the scene file's folder unless absolute
  std::string file;
};

// A rigid body's shape made from a closed OBJ mesh (shape type "mesh"): collides as convex
// hulls, drawn as the mesh, mass properties from its volume (include/tandem/mesh_body.h).
struct SceneMeshShape {
  std::string file;  // as written in the file, relative to the scene's folder unless absolute
  MeshBodyOptions options;
};

struct SceneRigidBody {
  // For a mesh shape, desc.position and desc.orientation place the mesh's own frame (its OBJ
  // coordinates), and desc.mass, desc.inertia and desc.shape are filled in by buildScene.
  RigidBodyDesc desc;
  std::string shapeFile;  // convex hull or triangle mesh: the OBJ its points came from, as written
  std::optional<SceneMeshShape> meshShape;
  std::optional<double> density;  // kg/m³, mesh shapes only: mass = density × the mesh's volume
  std::optional<Colour> colour;  // unset: the renderer's palette
};

struct SceneJoint {
  enum class Kind { Hinge, Fixed };
  Kind kind = Kind::Hinge;
  std::string bodyA;
  std::optional<std::string> bodyB;  // unset: to the world
  Vec3 pivot = Vec3::Zero();         // hinge, world frame
  Vec3 axis = Vec3::UnitZ();         // hinge, world frame
  double lowerLimit = 1.0, upperLimit = -1.0;  // hinge, rad; lower > upper: none (HingeDesc)
  bool motor = false;                          // hinge
  double motorTargetSpeed = 0.0, motorMaxTorque = 0.0;
};

// Nodes of a deformable held where they start by fixed-point rows: listed, or every node
// inside an axis-aligned box.
struct SceneFixedNodes {
  std::vector<int32_t> nodes;
  std::optional<std::array<Vec3, 2>> region;  // min, max corners
  double maxForce = kUnbounded;               // N
};

struct SceneDeformable {
  DeformableDesc desc;  // everything but the mesh, which comes from `mesh`
  SceneMesh mesh;
  // Exactly one of the two: total mass (kg), or density (kg/m³ for tetrahedral meshes, kg/m²
  // for surfaces, kg/m for ropes).
  std::optional<double> mass;
  std::optional<double> density;
  Vec3 initialVelocity = Vec3::Zero();  // m/s, every node
  std::vector<SceneFixedNodes> fixed;
  std::optional<Colour> colour;  // unset: the renderer's palette
};

// A point of a deformable held to a point of a rigid body: a node by index, the node nearest a
// point, or a barycentric point of a surface triangle.
struct SceneAnchor {
  std::string deformable;
  std::optional<int32_t> node;
  std::optional<Vec3> nearest;
  std::optional<int32_t> face;
  std::array<double, 3> barycentric{1.0 / 3, 1.0 / 3, 1.0 / 3};
  std::string body;
  std::optional<Vec3> localPoint;  // in the body's frame; default: where the deformable point starts
  double maxForce = kUnbounded;    // N
};

struct Scene {
  std::string name;
  std::string description;
  double timeStep = 1.0 / 50;  // s
  double duration = 5.0;       // s: how long `tandem run` runs it unless told otherwise
  WorldSettings settings;
  std::vector<SceneRigidBody> rigidBodies;
  std::vector<SceneJoint> joints;
  std::vector<SceneDeformable> deformables;
  std::vector<SceneAnchor> anchors;
  // Where it was read from: error messages name the file, meshes are found beside it.
  std::string sourceFile;
  std::string directory;
};

// Reads and checks a scene file. A problem gives "FILE: /json/path: what is wrong". Besides the
// format, the file's size and the scene's physical magnitudes (positions, sizes, masses, speeds,
// gravity, time step and run length) are checked against `limits`: what loads and builds can run.
TANDEM_API Result<Scene> loadScene(const std::string& path, const Limits& limits = {});
// The same from text; `fileName` names it in messages, `directory` is where meshes are found.
TANDEM_API Result<Scene> parseScene(std::string_view json, const std::string& fileName, const std::string& directory,
                         const Limits& limits = {});

// The scene as a scene file (every field written, numbers to the last bit).
TANDEM_API std::string sceneToJson(const Scene& scene);

// Adds everything in the scene to `world` (which should be empty) and applies its settings.
// Problems found only now (a mesh file that does not load, a node index out of range, a body
// the world refuses) are named like parse errors. Meshes are generated and read within `limits`
// (sizes), and checked against it (node positions, a deformable's total mass, the ratio of the
// heaviest dynamic mass to the lightest, nodes included).
TANDEM_API Status buildScene(const Scene& scene, World& world, const Limits& limits = {});

}  // namespace tandem
