// tandem.World: pushing and moving rigid bodies, collision filters, hinge limits and motors,
// rigid contacts, which ids the world holds, removing things, snapshots.
#include "python_world.h"

#include <Eigen/Geometry>

#include <cmath>
#include <memory>
#include <string>

namespace tandem::python {
namespace {

using Self = PythonWorld;

// A 4x4 pose (rotation, then position in the last column; World.rigid_pose's form) as the
// position and orientation World::setRigidPose takes. Non-finite entries are left for the
// library to name; a finite matrix that is not a rigid transform is a ValueError.
std::pair<Vec3, Quat> poseParts(const Eigen::Matrix4d& pose) {
  const Mat3 rotation = pose.topLeftCorner<3, 3>();
  if (pose.allFinite()) {
    const double orthonormality = (rotation.transpose() * rotation - Mat3::Identity()).norm();
    if (orthonormality > 1e-6 || rotation.determinant() <= 0.0)
      throw py::value_error("set_rigid_pose: the 4x4 pose's upper-left 3x3 block is not a rotation "
                            "(|R^T R - I| = " + std::to_string(orthonormality) + ", det R = " +
                            std::to_string(rotation.determinant()) + ")");
    if ((pose.row(3) - Eigen::RowVector4d(0, 0, 0, 1)).norm() > 1e-12)
      throw py::value_error("set_rigid_pose: the 4x4 pose's last row must be (0, 0, 0, 1)");
  }
  return {Vec3(pose.topRightCorner<3, 1>()), Quat(rotation)};
}

void bindPushing(py::class_<Self>& cls) {
  cls.def(
         "apply_force",
         [](Self& w, RigidBodyId body, const Vec3& force) { w.check(w.world().applyForce(body, force), body); },
         py::arg("body"), py::arg("force"),
         "Adds a force (N, world frame) at the centre of mass of a dynamic body. Forces and torques accumulate "
         "until the next step, act uniformly over it (every substep), then are cleared. Wakes the body. A static "
         "or kinematic body, or a non-finite force, raises tandem.Error.")
      .def(
          "apply_force_at_point",
          [](Self& w, RigidBodyId body, const Vec3& force, const Vec3& point) {
            w.check(w.world().applyForceAtPoint(body, force, point), body);
          },
          py::arg("body"), py::arg("force"), py::arg("point"),
          "Adds a force (N) at a point (m), both world frame: the force, and the torque r x F about the centre "
          "of mass, for the next step.")
      .def(
          "apply_torque",
          [](Self& w, RigidBodyId body, const Vec3& torque) { w.check(w.world().applyTorque(body, torque), body); },
          py::arg("body"), py::arg("torque"), "Adds a torque (N*m, world frame) for the next step.")
      .def(
          "apply_impulse",
          [](Self& w, RigidBodyId body, const Vec3& impulse) {
            w.check(w.world().applyImpulse(body, impulse), body);
          },
          py::arg("body"), py::arg("impulse"),
          "Applies an impulse (N*s, world frame) at the centre of mass now: the velocity changes by J/m at once.")
      .def(
          "apply_impulse_at_point",
          [](Self& w, RigidBodyId body, const Vec3& impulse, const Vec3& point) {
            w.check(w.world().applyImpulseAtPoint(body, impulse, point), body);
          },
          py::arg("body"), py::arg("impulse"), py::arg("point"),
          "Applies an impulse (N*s) at a point (m), both world frame, now: dv = J/m, dw = I^-1 (r x J) with r "
          "from the centre of mass to the point.")
      .def(
          "apply_angular_impulse",
          [](Self& w, RigidBodyId body, const Vec3& angularImpulse) {
            w.check(w.world().applyAngularImpulse(body, angularImpulse), body);
          },
          py::arg("body"), py::arg("angular_impulse"),
          "Applies an angular impulse (N*m*s, world frame) now: dw = I^-1 L.")
      .def(
          "set_rigid_linear_velocity",
          [](Self& w, RigidBodyId body, const Vec3& velocity) {
            w.check(w.world().setRigidLinearVelocity(body, velocity), body);
          },
          py::arg("body"), py::arg("velocity"), "Sets a dynamic body's velocity (m/s); wakes it.")
      .def(
          "set_rigid_angular_velocity",
          [](Self& w, RigidBodyId body, const Vec3& velocity) {
            w.check(w.world().setRigidAngularVelocity(body, velocity), body);
          },
          py::arg("body"), py::arg("velocity"), "Sets a dynamic body's angular velocity (rad/s, world frame); wakes it.")
      .def(
          "set_rigid_pose",
          [](Self& w, RigidBodyId body, const Vec3& position, const Quat& orientation) {
            w.check(w.world().setRigidPose(body, position, orientation), body);
          },
          py::arg("body"), py::arg("position"), py::arg("orientation") = Quat::Identity(),
          "Teleports a body (any motion type) to a pose: centre of mass (m) and orientation (w, x, y, z), world "
          "frame. Velocities are kept; a dynamic body is woken; a kinematic body's target becomes this pose. "
          "Anchors and joints on it pull it back towards what they hold in the next step.")
      .def(
          "set_rigid_pose",
          [](Self& w, RigidBodyId body, const Eigen::Matrix4d& pose) {
            const auto [position, orientation] = poseParts(pose);
            w.check(w.world().setRigidPose(body, position, orientation), body);
          },
          py::arg("body"), py::arg("pose"),
          "The same from a 4x4 homogeneous matrix, as World.rigid_pose returns (a matrix that is not a rigid "
          "transform is a ValueError).");
}

void bindFilters(py::class_<Self>& cls) {
  cls.def(
         "set_rigid_collision_filter",
         [](Self& w, RigidBodyId body, int64_t group, int64_t mask) {
           w.check(w.world().setRigidCollisionFilter(body, toCollisionBits(group, "set_rigid_collision_filter: group"),
                                                     toCollisionBits(mask, "set_rigid_collision_filter: mask")),
                   body);
         },
         py::arg("body"), py::arg("group"), py::arg("mask"),
         "Who collides with the body from now on: two things meet when (group_a & mask_b) and (group_b & mask_a) "
         "are both non-zero (tandem.collision_groups_meet). Group and mask are 32-bit sets, ints in [0, 2**32).")
      .def(
          "rigid_collision_group",
          [](const Self& w, RigidBodyId body) {
            return w.world().rigidCollisionGroup(w.checked(body, "rigid_collision_group"));
          },
          py::arg("body"), "The body's collision group (a 32-bit set).")
      .def(
          "rigid_collision_mask",
          [](const Self& w, RigidBodyId body) {
            return w.world().rigidCollisionMask(w.checked(body, "rigid_collision_mask"));
          },
          py::arg("body"), "The groups the body collides with (a 32-bit set).")
      .def(
          "set_deformable_collision_filter",
          [](Self& w, DeformableId body, int64_t group, int64_t mask) {
            w.check(w.world().setDeformableCollisionFilter(
                        body, toCollisionBits(group, "set_deformable_collision_filter: group"),
                        toCollisionBits(mask, "set_deformable_collision_filter: mask")),
                    body);
          },
          py::arg("deformable"), py::arg("group"), py::arg("mask"),
          "Who the deformable's surface collides with from now on (rigid bodies and other deformables; its "
          "contacts with itself follow CollisionSettings.self_collision). See set_rigid_collision_filter.");
}

void bindHinges(py::class_<Self>& cls) {
  cls.def(
         "set_hinge_limits",
         [](Self& w, JointId hinge, double lower, double upper) {
           w.check(w.world().setHingeLimits(hinge, lower, upper), hinge);
         },
         py::arg("hinge"), py::arg("lower"), py::arg("upper"),
         "Keeps the hinge's angle in [lower, upper] rad, within [-pi, pi]; lower > upper removes the limit. A "
         "fixed joint's id, NaN or a limit beyond pi raises tandem.Error.")
      .def(
          "set_hinge_motor",
          [](Self& w, JointId hinge, bool enabled, double targetSpeed, double maxTorque) {
            w.check(w.world().setHingeMotor(hinge, enabled, targetSpeed, maxTorque), hinge);
          },
          py::arg("hinge"), py::arg("enabled"), py::arg("target_speed") = 0.0, py::arg("max_torque") = 0.0,
          "Drives the hinge's speed towards target_speed (rad/s) with at most max_torque (N*m, >= 0), or stops "
          "driving it (enabled=False).")
      .def(
          "hinge_angle",
          [](const Self& w, JointId hinge) {
            (void)w.world().takeLookupError();
            const double angle = w.world().hingeAngle(w.checked(hinge, "hinge_angle"));
            if (Status s = w.world().takeLookupError(); !s) throw LibraryError("hinge_angle: " + s.message());
            return angle;
          },
          py::arg("hinge"),
          "Body A's rotation about the axis relative to body B (or the world) since the hinge was made, "
          "right-handed about the axis (rad). A fixed joint's id raises tandem.Error.")
      .def(
          "hinge_speed",
          [](const Self& w, JointId hinge) {
            (void)w.world().takeLookupError();
            const double speed = w.world().hingeSpeed(w.checked(hinge, "hinge_speed"));
            if (Status s = w.world().takeLookupError(); !s) throw LibraryError("hinge_speed: " + s.message());
            return speed;
          },
          py::arg("hinge"), "The rate of hinge_angle (rad/s).");
}

void bindIdsAndContacts(py::class_<Self>& cls) {
  cls.def(
         "contains", [](const Self& w, RigidBodyId id) { return w.world().contains(id); }, py::arg("id"),
         "Whether the world holds what the id names: added and not removed since (any kind of id).")
      .def(
          "contains", [](const Self& w, DeformableId id) { return w.world().contains(id); }, py::arg("id"))
      .def(
          "contains", [](const Self& w, JointId id) { return w.world().contains(id); }, py::arg("id"))
      .def(
          "contains", [](const Self& w, AnchorId id) { return w.world().contains(id); }, py::arg("id"))
      .def(
          "contains", [](const Self& w, FixedPointId id) { return w.world().contains(id); }, py::arg("id"))
      .def(
          "contains", [](const Self& w, GrabId id) { return w.world().contains(id); }, py::arg("id"))
      .def(
          "rigid_bodies", [](const Self& w) { return w.world().rigidBodies(); },
          "The ids of the rigid bodies the world holds, by index (a list of RigidBodyId).")
      .def(
          "deformable_ids", [](const Self& w) { return w.world().deformableIds(); },
          "The ids of the deformables the world holds, by index (a list of DeformableId).")
      .def(
          "rigid_contacts", [](const Self& w) { return w.world().rigidContacts(); },
          "Every contact point between rigid bodies (Bullet's) in the last step: a list of RigidContact. With n "
          "substeps each substep's points are listed, so a pair's impulses sum to what it exchanged over the step.");
}

void bindRemoval(py::class_<Self>& cls) {
  cls.def(
         "remove_rigid_body", [](Self& w, RigidBodyId body) { w.check(w.world().removeRigidBody(body), body); },
         py::arg("body"),
         "Takes the body out with its joints, anchors, grabs and contacts. Its id (and theirs) are refused from "
         "then on with tandem.IdError; a body added later may take its slot with the next generation.")
      .def(
          "remove_deformable", [](Self& w, DeformableId body) { w.check(w.world().removeDeformable(body), body); },
          py::arg("deformable"),
          "Takes the deformable out with its fixed points, anchors, grabs and contacts. Views of its nodes stay "
          "valid (the nodes are kept, inert); its id is refused from then on.")
      .def(
          "remove_joint", [](Self& w, JointId joint) { w.check(w.world().removeJoint(joint), joint); },
          py::arg("joint"), "Takes a hinge or fixed joint out.")
      .def(
          "remove_anchor", [](Self& w, AnchorId anchor) { w.check(w.world().removeAnchor(anchor), anchor); },
          py::arg("anchor"), "Takes an anchor out.")
      .def(
          "remove_fixed_point",
          [](Self& w, FixedPointId fixedPoint) { w.check(w.world().removeFixedPoint(fixedPoint), fixedPoint); },
          py::arg("fixed_point"), "Takes a fixed point out: the node is free again.");
}

void bindSnapshots(py::module_& module, py::class_<Self>& cls) {
  py::class_<PythonSnapshot, std::unique_ptr<PythonSnapshot>>(
      module, "WorldSnapshot",
      "A copy of a world's whole state (World.snapshot): rigid bodies with Bullet's contact points and their "
      "warm-start impulses, deformables, every row with its warm-start impulse, targets, settings, time. Opaque; "
      "World.restore puts it back into the world it came from.")
      .def_property_readonly(
          "time", [](const PythonSnapshot& s) { return s.snapshot.time(); }, "The world's time when it was taken (s).")
      .def_property_readonly(
          "step_count", [](const PythonSnapshot& s) { return s.snapshot.stepCount(); },
          "The world's step count when it was taken.")
      .def("__repr__", [](const PythonSnapshot& s) {
        return "WorldSnapshot(step_count=" + std::to_string(s.snapshot.stepCount()) + ")";
      });

  cls.def(
         "snapshot", [](const Self& w) { return w.snapshot(); },
         "A WorldSnapshot of the whole state the next step reads. Stepping on after World.restore(snapshot) "
         "repeats, bit for bit, what stepping on from here does.")
      .def(
          "restore", [](Self& w, const PythonSnapshot& snapshot) { w.restore(snapshot); }, py::arg("snapshot"),
          "Puts the world back into the snapshot's state. Refused (tandem.Error, nothing changed) for another "
          "world's snapshot, or when rigid bodies or joints were added or removed since it was taken; a deformable "
          "removed since comes back, one added since goes. A snapshot taken before or after a deformable was added "
          "is refused while NumPy views of the nodes are alive, as adding is.");
}

}  // namespace

void bindWorldEditing(py::module_& module, py::class_<PythonWorld>& cls) {
  module.attr("DEFAULT_COLLISION_GROUP") = kDefaultCollisionGroup;
  module.attr("ALL_COLLISION_GROUPS") = kAllCollisionGroups;
  module.def(
      "collision_groups_meet",
      [](int64_t groupA, int64_t maskA, int64_t groupB, int64_t maskB) {
        return collisionGroupsMeet(toCollisionBits(groupA, "group_a"), toCollisionBits(maskA, "mask_a"),
                                   toCollisionBits(groupB, "group_b"), toCollisionBits(maskB, "mask_b"));
      },
      py::arg("group_a"), py::arg("mask_a"), py::arg("group_b"), py::arg("mask_b"),
      "Whether two things with these groups and masks collide: (group_a & mask_b) and (group_b & mask_a) both "
      "non-zero.");
  bindPushing(cls);
  bindFilters(cls);
  bindHinges(cls);
  bindIdsAndContacts(cls);
  bindRemoval(cls);
  bindSnapshots(module, cls);
}

uint32_t collisionBitsOf(int64_t value, const char* what) { return toCollisionBits(value, what); }

}  // namespace tandem::python
