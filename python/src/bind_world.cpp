// tandem.World: building, stepping and reading a world.
#include "python_world.h"

#include <Eigen/Geometry>

namespace tandem::python {
namespace {

using Self = PythonWorld;

Eigen::Matrix4d poseMatrix(const World& world, RigidBodyId id) {
  Eigen::Matrix4d pose = Eigen::Matrix4d::Identity();
  pose.topLeftCorner<3, 3>() = world.rigidOrientation(id).toRotationMatrix();
  pose.topRightCorner<3, 1>() = world.rigidPosition(id);
  return pose;
}

void bindBuilding(py::class_<Self>& cls) {
  cls.def(
         "add_rigid_body", [](Self& w, const RigidBodyDesc& d) { return unwrap(w.world().addRigidBody(d)); },
         py::arg("desc"), "Adds a rigid body; returns its RigidBodyId. A bad description raises tandem.Error.")
      .def(
          "add_hinge", [](Self& w, const HingeDesc& d) { return unwrap(w.world().addHinge(d)); }, py::arg("desc"),
          "Adds a hinge (HingeDesc); returns its JointId.")
      .def(
          "add_fixed_joint", [](Self& w, const FixedJointDesc& d) { return unwrap(w.world().addFixedJoint(d)); },
          py::arg("desc"), "Adds a fixed joint (FixedJointDesc); returns its JointId.")
      .def(
          "add_deformable",
          [](Self& w, const DeformableDesc& d) {
            w.nodeArraysChanging("add_deformable");
            return unwrap(w.world().addDeformable(d));
          },
          py::arg("desc"),
          "Adds a deformable body; returns its DeformableId. Refused while NumPy views of this world's nodes "
          "are alive (their storage may move).")
      .def(
          "add_fixed_point",
          [](Self& w, DeformableId body, int32_t node, const std::optional<Vec3>& target, double maxForce) {
            w.checked(body, "add_fixed_point");
            // None: where the node is now (a bad node index is left for the world to name).
            const std::span<const Vec3> nodes = w.world().nodePositions(body);
            const bool inRange = node >= 0 && node < static_cast<int32_t>(nodes.size());
            const Vec3 where = target ? *target : (inRange ? nodes[node] : Vec3(Vec3::Zero()));
            return unwrap(w.world().addFixedPoint(body, node, where, maxForce));
          },
          py::arg("deformable"), py::arg("node"), py::arg("target") = py::none(), py::arg("max_force") = kUnbounded,
          "Holds a node at target (m; None: where it is now) with at most max_force (N); returns a FixedPointId.")
      .def(
          "set_fixed_point_target",
          [](Self& w, FixedPointId id, const Vec3& target) { w.check(w.world().setFixedPointTarget(id, target), id); },
          py::arg("fixed_point"), py::arg("target"), "Moves a fixed point's target (a kinematic target, m).")
      .def(
          "add_anchor", [](Self& w, const AnchorDesc& d) { return unwrap(w.world().addAnchor(d)); }, py::arg("desc"),
          "Holds a point of a deformable to a point of a rigid body (AnchorDesc); returns an AnchorId.")
      .def(
          "add_grab",
          [](Self& w, const GrabDesc& d) { return unwrap(w.world().addGrab(d)); },
          py::arg("desc"), "Starts pulling a point towards a target (GrabDesc); returns a GrabId.")
      .def(
          "set_grab_target",
          [](Self& w, GrabId id, const Vec3& target) { w.check(w.world().setGrabTarget(id, target), id); },
          py::arg("grab"), py::arg("target"), "Moves a grab's target (m).")
      .def(
          "remove_grab",
          [](Self& w, GrabId id) { w.check(w.world().removeGrab(id), id); }, py::arg("grab"),
          "Lets go; the id is refused from then on (tandem.IdError).")
      .def(
          "set_node_velocity",
          [](Self& w, DeformableId body, int32_t node, const Vec3& v) {
            check(w.world().setNodeVelocity(w.checked(body, "set_node_velocity"), node, v));
          },
          py::arg("deformable"), py::arg("node"), py::arg("velocity"), "Sets a node's velocity (m/s).")
      .def(
          "set_node_position",
          [](Self& w, DeformableId body, int32_t node, const Vec3& p) {
            check(w.world().setNodePosition(w.checked(body, "set_node_position"), node, p));
          },
          py::arg("deformable"), py::arg("node"), py::arg("position"),
          "Moves a node (a teleport: no velocity, no collision on the way); its rest shape is unchanged.")
      .def(
          "fix_node",
          [](Self& w, DeformableId body, int32_t node) {
            check(w.world().fixNode(w.checked(body, "fix_node"), node));
          },
          py::arg("deformable"), py::arg("node"), "Pins a node where it is: its inverse mass becomes zero.")
      .def(
          "put_rigid_to_sleep",
          [](Self& w, RigidBodyId id) { check(w.world().putRigidToSleep(w.checked(id, "put_rigid_to_sleep"))); },
          py::arg("body"), "Puts a rigid body to sleep.")
      .def(
          "set_rigid_can_sleep",
          [](Self& w, RigidBodyId id, bool canSleep) {
            check(w.world().setRigidCanSleep(w.checked(id, "set_rigid_can_sleep"), canSleep));
          },
          py::arg("body"), py::arg("can_sleep"), "Lets Bullet put the body to sleep, or not.")
      .def(
          "set_rigid_damping",
          [](Self& w, RigidBodyId id, double linearDamping, double angularDamping) {
            check(w.world().setRigidDamping(w.checked(id, "set_rigid_damping"), linearDamping, angularDamping));
          },
          py::arg("body"), py::arg("linear_damping"), py::arg("angular_damping"),
          "The fractions of its linear and angular velocity a body loses per second, each in [0, 1].")
      .def(
          "set_kinematic_target",
          [](Self& w, RigidBodyId id, const Vec3& position, const Quat& orientation) {
            w.check(w.world().setKinematicTarget(id, position, orientation), id);
          },
          py::arg("body"), py::arg("position"), py::arg("orientation") = Quat::Identity(),
          "Moves a kinematic body to this pose (orientation (w, x, y, z)) by the end of the next step.");
}

void bindRigidQueries(py::class_<Self>& cls) {
  cls.def_property_readonly(
         "rigid_body_count", [](const Self& w) { return w.world().rigidBodyCount(); },
         "Number of rigid bodies the world holds (removed ones not counted).")
      .def(
          "find_rigid_body", [](const Self& w, std::string_view name) { return w.world().findRigidBody(name); },
          py::arg("name"), "The RigidBodyId of the body with this name, or None.")
      .def(
          "rigid_name", [](const Self& w, RigidBodyId id) { return w.world().rigidName(w.checked(id, "rigid_name")); },
          py::arg("body"), "The body's name.")
      .def(
          "rigid_position",
          [](const Self& w, RigidBodyId id) { return w.world().rigidPosition(w.checked(id, "rigid_position")); },
          py::arg("body"), "Centre of mass, world frame (m): a (3,) array.")
      .def(
          "rigid_orientation",
          [](const Self& w, RigidBodyId id) {
            return w.world().rigidOrientation(w.checked(id, "rigid_orientation"));
          },
          py::arg("body"), "Orientation quaternion (w, x, y, z): a (4,) array.")
      .def(
          "rigid_pose", [](const Self& w, RigidBodyId id) { return poseMatrix(w.world(), w.checked(id, "rigid_pose")); },
          py::arg("body"), "The body's pose as a 4x4 homogeneous matrix (rotation, then position in the last column).")
      .def(
          "rigid_linear_velocity",
          [](const Self& w, RigidBodyId id) {
            return w.world().rigidLinearVelocity(w.checked(id, "rigid_linear_velocity"));
          },
          py::arg("body"), "m/s: a (3,) array.")
      .def(
          "rigid_angular_velocity",
          [](const Self& w, RigidBodyId id) {
            return w.world().rigidAngularVelocity(w.checked(id, "rigid_angular_velocity"));
          },
          py::arg("body"), "rad/s, world frame: a (3,) array.")
      .def(
          "rigid_mass", [](const Self& w, RigidBodyId id) { return w.world().rigidMass(w.checked(id, "rigid_mass")); },
          py::arg("body"), "kg; 0 for static and kinematic bodies.")
      .def(
          "rigid_inertia",
          [](const Self& w, RigidBodyId id) { return w.world().rigidInertia(w.checked(id, "rigid_inertia")); },
          py::arg("body"), "kg*m^2, world frame, about the centre of mass: a 3x3 array (0 if not dynamic).")
      .def(
          "rigid_is_awake",
          [](const Self& w, RigidBodyId id) { return w.world().rigidIsAwake(w.checked(id, "rigid_is_awake")); },
          py::arg("body"), "Whether Bullet has the body awake.")
      .def(
          "rigid_shape",
          [](const Self& w, RigidBodyId id) { return w.world().rigidShape(w.checked(id, "rigid_shape")); },
          py::arg("body"), "The RigidShape the body was made with (a copy).")
      .def(
          "rigid_contact_impulse",
          [](const Self& w, RigidBodyId a, RigidBodyId b) {
            return w.world().rigidContactImpulse(w.checked(a, "rigid_contact_impulse"),
                                                 w.checked(b, "rigid_contact_impulse"));
          },
          py::arg("a"), py::arg("b"), "Sum of Bullet's normal contact impulses between two rigid bodies, last step (N*s).")
      .def(
          "deformable_impulse_on_rigid",
          [](const Self& w, RigidBodyId id) {
            return w.world().deformableImpulseOnRigid(w.checked(id, "deformable_impulse_on_rigid"));
          },
          py::arg("body"), "Total impulse Tandem's rows put on the body in the last step (N*s).")
      .def(
          "deformable_angular_impulse_on_rigid",
          [](const Self& w, RigidBodyId id) {
            return w.world().deformableAngularImpulseOnRigid(w.checked(id, "deformable_angular_impulse_on_rigid"));
          },
          py::arg("body"), "Angular impulse about the centre of mass from Tandem's rows, last step (N*m*s).")
      .def(
          "deformable_force_on_rigid",
          [](const Self& w, RigidBodyId id) {
            return w.world().deformableForceOnRigid(w.checked(id, "deformable_force_on_rigid"));
          },
          py::arg("body"), "The same impulse as a mean force over the last step (N).")
      .def(
          "deformable_torque_on_rigid",
          [](const Self& w, RigidBodyId id) {
            return w.world().deformableTorqueOnRigid(w.checked(id, "deformable_torque_on_rigid"));
          },
          py::arg("body"), "The angular impulse as a mean torque over the last step (N*m).");
}

void bindDeformableQueries(py::class_<Self>& cls) {
  cls.def_property_readonly(
         "deformable_count", [](const Self& w) { return w.world().deformableCount(); }, "Number of deformables.")
      .def(
          "find_deformable", [](const Self& w, std::string_view name) { return w.world().findDeformable(name); },
          py::arg("name"), "The DeformableId of the deformable with this name, or None.")
      .def(
          "deformable_name",
          [](const Self& w, DeformableId id) { return w.world().deformableName(w.checked(id, "deformable_name")); },
          py::arg("deformable"), "The deformable's name.")
      .def(
          "node_positions",
          [](const py::object& self, DeformableId id) {
            const Self& w = self.cast<const Self&>();
            return Self::viewOf(self, w.world().nodePositions(w.checked(id, "node_positions")));
          },
          py::arg("deformable"),
          "The nodes' positions (m) as a read-only (N, 3) view of the world's own memory: no copy, it changes "
          "as the world steps, and it keeps the world alive. Adding a deformable is refused while views exist; "
          "numpy.array(view) makes a copy to keep.")
      .def(
          "node_velocities",
          [](const py::object& self, DeformableId id) {
            const Self& w = self.cast<const Self&>();
            return Self::viewOf(self, w.world().nodeVelocities(w.checked(id, "node_velocities")));
          },
          py::arg("deformable"), "The nodes' velocities (m/s) as a read-only (N, 3) view, like node_positions.")
      .def(
          "node_inverse_masses",
          [](const py::object& self, DeformableId id) {
            const Self& w = self.cast<const Self&>();
            return Self::viewOf(self, w.world().nodeInverseMasses(w.checked(id, "node_inverse_masses")));
          },
          py::arg("deformable"), "The nodes' inverse masses (1/kg; 0 for pinned nodes) as a read-only (N,) view.")
      .def(
          "rest_mesh",
          [](const Self& w, DeformableId id) { return w.world().restMesh(w.checked(id, "rest_mesh")); },
          py::arg("deformable"), "The DeformableMesh as added (a copy).")
      .def(
          "fixed_point_impulse",
          [](const Self& w, FixedPointId id) {
            return w.world().fixedPointImpulse(w.checked(id, "fixed_point_impulse"));
          },
          py::arg("fixed_point"), "Impulse on the node in the last step (N*s).")
      .def(
          "anchor_state",
          [](const Self& w, AnchorId id) {
            return w.world().anchorState(w.checked(id, "anchor_state"));
          },
          py::arg("anchor"), "The AnchorState after the last step: impulse and both points.")
      .def(
          "grab_impulse",
          [](const Self& w, GrabId id) { return w.world().grabImpulse(w.checked(id, "grab_impulse")); },
          py::arg("grab"), "Impulse on the grabbed point in the last step (N*s).")
      .def(
          "grab_point", [](const Self& w, GrabId id) { return w.world().grabPoint(w.checked(id, "grab_point")); },
          py::arg("grab"), "Where the grabbed point is now (m).")
      .def(
          "contacts", [](const Self& w) { return w.world().contacts(); },
          "The contacts of deformable surfaces in the last step: a list of ContactReport.")
      .def(
          "cast_ray",
          [](const Self& w, const Vec3& origin, const Vec3& direction, double maxDistance) {
            if (!origin.allFinite() || !direction.allFinite() || direction.norm() == 0.0)
              throw py::value_error("cast_ray: origin and direction must be finite and direction non-zero");
            return w.world().castRay(origin, direction, maxDistance);
          },
          py::arg("origin"), py::arg("direction"), py::arg("max_distance") = 1.0e3,
          "The nearest rigid shape or deformable face along the ray within max_distance (m): a RayHit, or None.");
}

void bindStepping(py::class_<Self>& cls) {
  cls.def_property(
         "settings", [](const Self& w) { return w.world().settings(); },
         [](Self& w, const WorldSettings& s) { check(w.world().setSettings(s)); },
         "The WorldSettings (a copy). Assign a changed copy to apply it; a bad value raises tandem.Error and "
         "nothing changes.")
      .def(
          "step",
          [](Self& w, double timeStep, int steps) {
            if (steps < 1) throw py::value_error("step: steps must be >= 1, got " + std::to_string(steps));
            for (int i = 0; i < steps; ++i) {
              check(w.world().step(timeStep));
              if (PyErr_CheckSignals() != 0) throw py::error_already_set();
            }
            return w.world().lastReport();
          },
          py::arg("time_step"), py::arg("steps") = 1,
          "Advances the world by `steps` steps of time_step seconds; returns the last step's StepReport. A bad "
          "time step, or a step that diverges (naming the body and node), raises tandem.Error.")
      .def_property_readonly(
          "last_report", [](const Self& w) { return w.world().lastReport(); }, "The last step's StepReport (a copy).")
      .def_property_readonly("time", [](const Self& w) { return w.world().time(); }, "Simulated seconds so far.")
      .def_property_readonly(
          "step_count", [](const Self& w) { return w.world().stepCount(); }, "Steps taken so far.")
      .def_property_readonly(
          "last_time_step", [](const Self& w) { return w.world().lastTimeStep(); },
          "h of the last step (0 before the first): impulses / h are forces.")
      .def(
          "total_linear_momentum", [](const Self& w) { return w.world().totalLinearMomentum(); },
          "Momentum of every dynamic thing (nodes with finite mass, dynamic rigid bodies), kg*m/s.");
}

}  // namespace

void bindWorld(py::module_& module) {
  py::class_<Self> cls(module, "World",
                       "Bullet rigid bodies and Tandem deformable bodies stepped together. Everything added is "
                       "named by a typed id (RigidBodyId, DeformableId, ...).");
  cls.def(py::init<>(), "An empty world with default settings (gravity -9.81 m/s^2 along y, 4 iterations).")
      .def(py::init([](const WorldSettings& settings) {
             auto w = std::make_unique<Self>();
             check(w->world().setSettings(settings));
             return w;
           }),
           py::arg("settings"), "An empty world with these settings (checked: a bad value raises tandem.Error).");
  bindBuilding(cls);
  bindRigidQueries(cls);
  bindDeformableQueries(cls);
  bindStepping(cls);
  bindWorldEditing(module, cls);
}

}  // namespace tandem::python
