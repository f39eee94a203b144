// Scene files: load, parse, check, write back and build into a World; the built-in scenes.
#include "python_world.h"

#include <pybind11/stl_bind.h>

#include <tandem/scene_file.h>
#include <tandem/scenes.h>

#include <vector>

// A scene's lists are Python lists by reference, so that scene.deformables[0].desc.collision.friction = 0.3
// changes the scene.
PYBIND11_MAKE_OPAQUE(std::vector<tandem::SceneRigidBody>)
PYBIND11_MAKE_OPAQUE(std::vector<tandem::SceneJoint>)
PYBIND11_MAKE_OPAQUE(std::vector<tandem::SceneDeformable>)
PYBIND11_MAKE_OPAQUE(std::vector<tandem::SceneAnchor>)
PYBIND11_MAKE_OPAQUE(std::vector<tandem::SceneFixedNodes>)

namespace tandem::python {
namespace {

void buildInto(const Scene& scene, const py::object& worldObject) {
  PythonWorld& world = worldObject.cast<PythonWorld&>();
  world.nodeArraysChanging("build_scene");
  check(buildScene(scene, world.world()));
}

void bindSceneParts(py::module_& module) {
  py::class_<SceneMesh> mesh(module, "SceneMesh",
                             "Where a scene deformable's mesh comes from: a generator and its parameters, or a file.");
  py::enum_<SceneMesh::Kind>(mesh, "Kind")
      .value("ROPE", SceneMesh::Kind::Rope)
      .value("CLOTH_GRID", SceneMesh::Kind::ClothGrid)
      .value("TET_BOX", SceneMesh::Kind::TetBox)
      .value("TET_CYLINDER", SceneMesh::Kind::TetCylinder)
      .value("OBJ", SceneMesh::Kind::Obj)
      .value("TETGEN", SceneMesh::Kind::TetGen);
  defKeywordInit<SceneMesh>(mesh);
  mesh.def_readwrite("kind", &SceneMesh::kind, "SceneMesh.Kind.")
      .def_readwrite("start", &SceneMesh::start, "Rope: first end (m).")
      .def_readwrite("end", &SceneMesh::end, "Rope: second end (m).")
      .def_property(
          "path", [](const SceneMesh& m) { return toArray(m.path); },
          [](SceneMesh& m, const py::handle& a) { m.path = toVec3s(a, "SceneMesh.path"); },
          "Rope: the polyline it follows when not empty, (K, 3) (a copy).")
      .def_readwrite("nodes", &SceneMesh::nodes, "Rope: node count.")
      .def_readwrite("corner", &SceneMesh::corner, "Cloth grid: corner (m).")
      .def_readwrite("side_u", &SceneMesh::sideU, "Cloth grid: first side (m).")
      .def_readwrite("side_v", &SceneMesh::sideV, "Cloth grid: second side (m).")
      .def_readwrite("columns", &SceneMesh::columns, "Cloth grid: nodes along side_u.")
      .def_readwrite("rows", &SceneMesh::rows, "Cloth grid: nodes along side_v.")
      .def_readwrite("min_corner", &SceneMesh::minCorner, "Tet box (m).")
      .def_readwrite("max_corner", &SceneMesh::maxCorner, "Tet box (m).")
      .def_readwrite("cells", &SceneMesh::cells, "Tet box: cells along x, y, z.")
      .def_readwrite("base_centre", &SceneMesh::baseCentre, "Tet cylinder (m).")
      .def_readwrite("radius", &SceneMesh::radius, "Tet cylinder (m).")
      .def_readwrite("height", &SceneMesh::height, "Tet cylinder (m).")
      .def_readwrite("rings", &SceneMesh::rings, "Tet cylinder.")
      .def_readwrite("sectors", &SceneMesh::sectors, "Tet cylinder.")
      .def_readwrite("layers", &SceneMesh::layers, "Tet cylinder.")
      .def_readwrite("file", &SceneMesh::file, "OBJ or TetGen base path as written, relative to the scene's folder.");

  py::class_<SceneRigidBody> rigid(module, "SceneRigidBody", "A scene's rigid body.");
  defKeywordInit<SceneRigidBody>(rigid);
  rigid.def_readwrite("desc", &SceneRigidBody::desc, "Its RigidBodyDesc (changed in place).")
      .def_readwrite("shape_file", &SceneRigidBody::shapeFile, "The OBJ a hull or mesh shape came from, as written.")
      .def_readwrite("colour", &SceneRigidBody::colour, "(r, g, b) in [0, 1] as displayed, or None: the palette.");

  py::class_<SceneJoint> joint(module, "SceneJoint", "A scene's hinge or fixed joint, bodies by name.");
  py::enum_<SceneJoint::Kind>(joint, "Kind").value("HINGE", SceneJoint::Kind::Hinge).value("FIXED", SceneJoint::Kind::Fixed);
  defKeywordInit<SceneJoint>(joint);
  joint.def_readwrite("kind", &SceneJoint::kind, "SceneJoint.Kind.")
      .def_readwrite("body_a", &SceneJoint::bodyA, "Name of the first body.")
      .def_readwrite("body_b", &SceneJoint::bodyB, "Name of the second body, or None for the world.")
      .def_readwrite("pivot", &SceneJoint::pivot, "Hinge: world frame (m).")
      .def_readwrite("axis", &SceneJoint::axis, "Hinge: world frame.")
      .def_readwrite("lower_limit", &SceneJoint::lowerLimit, "Hinge: rad; lower_limit > upper_limit is no limit.")
      .def_readwrite("upper_limit", &SceneJoint::upperLimit, "Hinge: rad.")
      .def_readwrite("motor", &SceneJoint::motor, "Hinge: whether a motor drives it.")
      .def_readwrite("motor_target_speed", &SceneJoint::motorTargetSpeed, "Hinge: rad/s.")
      .def_readwrite("motor_max_torque", &SceneJoint::motorMaxTorque, "Hinge: N*m.");

  py::class_<SceneFixedNodes> fixedNodes(module, "SceneFixedNodes",
                                         "Nodes of a scene deformable held where they start: listed, or inside a box.");
  defKeywordInit<SceneFixedNodes>(fixedNodes);
  fixedNodes.def_readwrite("nodes", &SceneFixedNodes::nodes, "Node indices (a list; assign a whole list).")
      .def_readwrite("region", &SceneFixedNodes::region, "(min corner, max corner), or None.")
      .def_readwrite("max_force", &SceneFixedNodes::maxForce, "N.");
  py::bind_vector<std::vector<SceneFixedNodes>>(module, "SceneFixedNodesList");

  py::class_<SceneDeformable> deformable(module, "SceneDeformable", "A scene's deformable body.");
  defKeywordInit<SceneDeformable>(deformable);
  deformable.def_readwrite("desc", &SceneDeformable::desc, "Its DeformableDesc, all but the mesh (changed in place).")
      .def_readwrite("mesh", &SceneDeformable::mesh, "The SceneMesh it is made from.")
      .def_readwrite("mass", &SceneDeformable::mass, "Total mass (kg), or None when density is given.")
      .def_readwrite("density", &SceneDeformable::density, "kg/m^3, kg/m^2 or kg/m, or None when mass is given.")
      .def_readwrite("initial_velocity", &SceneDeformable::initialVelocity, "m/s, every node.")
      .def_readwrite("fixed", &SceneDeformable::fixed, "SceneFixedNodes list.")
      .def_readwrite("colour", &SceneDeformable::colour, "(r, g, b) in [0, 1] as displayed, or None: the palette.");

  py::class_<SceneAnchor> anchor(module, "SceneAnchor",
                                 "A scene's anchor: a node (by index or nearest a point) or a face point, held to a body.");
  defKeywordInit<SceneAnchor>(anchor);
  anchor.def_readwrite("deformable", &SceneAnchor::deformable, "Name of the deformable.")
      .def_readwrite("node", &SceneAnchor::node, "Node index, or None.")
      .def_readwrite("nearest", &SceneAnchor::nearest, "The node nearest this point (m), or None.")
      .def_readwrite("face", &SceneAnchor::face, "Surface triangle index, or None.")
      .def_readwrite("barycentric", &SceneAnchor::barycentric, "Weights on the face's nodes.")
      .def_readwrite("body", &SceneAnchor::body, "Name of the rigid body.")
      .def_readwrite("local_point", &SceneAnchor::localPoint, "In the body's frame, or None.")
      .def_readwrite("max_force", &SceneAnchor::maxForce, "N.");

  py::bind_vector<std::vector<SceneRigidBody>>(module, "SceneRigidBodyList");
  py::bind_vector<std::vector<SceneJoint>>(module, "SceneJointList");
  py::bind_vector<std::vector<SceneDeformable>>(module, "SceneDeformableList");
  py::bind_vector<std::vector<SceneAnchor>>(module, "SceneAnchorList");
}

}  // namespace

void bindScene(py::module_& module) {
  bindSceneParts(module);

  py::class_<Scene> scene(module, "Scene",
                          "A scene file's content (docs/scene-format.md) as plain data, bodies referred to by name. "
                          "Lists and nested settings change in place; build() or build_scene() makes it a World.");
  defKeywordInit<Scene>(scene);
  scene.def_readwrite("name", &Scene::name, "The scene's name.")
      .def_readwrite("description", &Scene::description, "What it shows.")
      .def_readwrite("time_step", &Scene::timeStep, "s per step.")
      .def_readwrite("duration", &Scene::duration, "s: how long `tandem run` runs it by default.")
      .def_readwrite("settings", &Scene::settings, "WorldSettings (changed in place).")
      .def_readwrite("rigid_bodies", &Scene::rigidBodies, "SceneRigidBody list.")
      .def_readwrite("joints", &Scene::joints, "SceneJoint list.")
      .def_readwrite("deformables", &Scene::deformables, "SceneDeformable list.")
      .def_readwrite("anchors", &Scene::anchors, "SceneAnchor list.")
      .def_readwrite("source_file", &Scene::sourceFile, "Where it was read from (named in messages).")
      .def_readwrite("directory", &Scene::directory, "Where its mesh files are found.")
      .def("to_json", &sceneToJson, "The scene as scene-file JSON text (every field written, numbers to the last bit).")
      .def(
          "build",
          [](const Scene& s) {
            py::object world = py::cast(std::make_unique<PythonWorld>());
            buildInto(s, world);
            return world;
          },
          "A new World with everything in the scene, its settings applied. Problems found only now (a mesh "
          "file that does not load, a node out of range) raise tandem.Error.");

  module.def(
      "load_scene", [](const std::string& path) { return unwrap(loadScene(path)); }, py::arg("path"),
      "Reads and checks a scene file. A problem raises tandem.Error: 'FILE: /json/path: what is wrong'.");
  module.def(
      "parse_scene",
      [](std::string_view json, const std::string& fileName, const std::string& directory) {
        return unwrap(parseScene(json, fileName, directory));
      },
      py::arg("json"), py::arg("file_name") = "<string>", py::arg("directory") = ".",
      "Reads and checks a scene from JSON text; file_name names it in messages, directory is where meshes are found.");
  module.def(
      "validate_scene",
      [](const std::string& path) {
        Scene loaded = unwrap(loadScene(path));
        World scratch;
        check(buildScene(loaded, scratch));
      },
      py::arg("path"),
      "Checks a scene file as `tandem validate` does: loads it and builds it into a scratch world. Returns None "
      "when it is good; raises tandem.Error naming the file, the JSON path and the problem.");
  module.def("build_scene", &buildInto, py::arg("scene"), py::arg("world"),
             "Adds everything in the scene to `world` (which should be empty) and applies its settings.");
  module.def(
      "builtin_scene_names",
      [] {
        std::vector<std::string> names;
        for (const BuiltinScene& s : builtinScenes()) names.emplace_back(s.name);
        return names;
      },
      "Names of the built-in scenes (`tandem list`).");
  module.def(
      "build_builtin_scene",
      [](const std::string& name, const py::object& worldObject) {
        const BuiltinScene* builtin = findBuiltinScene(name);
        if (!builtin) throw LibraryError("no built-in scene named '" + name + "'");
        PythonWorld& world = worldObject.cast<PythonWorld&>();
        world.nodeArraysChanging("build_builtin_scene");
        check(builtin->build(world.world()));
        return builtin->timeStep;
      },
      py::arg("name"), py::arg("world"), "Builds a built-in scene into `world`; returns the scene's time step (s).");
}

}  // namespace tandem::python
