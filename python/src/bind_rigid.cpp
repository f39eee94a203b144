// Rigid bodies (Bullet's): shapes, descriptions, joints.
#include "bindings.h"

#include <tandem/world.h>

namespace tandem::python {

void bindRigid(py::module_& module) {
  py::enum_<ShapeType>(module, "ShapeType", "The kind of a RigidShape.")
      .value("BOX", ShapeType::Box)
      .value("SPHERE", ShapeType::Sphere)
      .value("CYLINDER", ShapeType::Cylinder)
      .value("CAPSULE", ShapeType::Capsule)
      .value("PLANE", ShapeType::Plane)
      .value("CONVEX_HULL", ShapeType::ConvexHull)
      .value("TRIANGLE_MESH", ShapeType::TriangleMesh)
      .value("COMPOUND", ShapeType::Compound);

  py::enum_<MotionType>(module, "MotionType",
                        "DYNAMIC bodies move under forces; STATIC never move; KINEMATIC follow "
                        "World.set_kinematic_target.")
      .value("DYNAMIC", MotionType::Dynamic)
      .value("STATIC", MotionType::Static)
      .value("KINEMATIC", MotionType::Kinematic);

  py::class_<RigidShape> shape(module, "RigidShape",
                               "A rigid body's collision shape, in the body's frame about its centre of mass. "
                               "Make one with RigidShape.box(...), sphere, cylinder, capsule, plane, convex_hull "
                               "or triangle_mesh.");
  defKeywordInit<RigidShape>(shape);
  shape.def_readwrite("type", &RigidShape::type, "The ShapeType.")
      .def_readwrite("half_extents", &RigidShape::halfExtents, "Box: half its size along x, y, z (m).")
      .def_readwrite("radius", &RigidShape::radius, "Sphere, cylinder, capsule (m).")
      .def_readwrite("half_height", &RigidShape::halfHeight, "Cylinder, capsule: half the length along local y (m).")
      .def_readwrite("plane_normal", &RigidShape::planeNormal, "Plane: the points x with n.x = offset.")
      .def_readwrite("plane_offset", &RigidShape::planeOffset, "Plane: offset along the normal (m).")
      .def_property(
          "points", [](const RigidShape& s) { return toArray(s.points); },
          [](RigidShape& s, const py::handle& points) { s.points = toVec3s(points, "RigidShape.points"); },
          "Convex hull: its points; triangle mesh: its vertices; an (N, 3) array (a copy).")
      .def_property(
          "triangles", [](const RigidShape& s) { return toArray(s.triangles); },
          [](RigidShape& s, const py::handle& triangles) {
            s.triangles = toIndexTuples<3>(triangles, "RigidShape.triangles");
          },
          "Triangle mesh: vertex indices, an (M, 3) int32 array (a copy).")
      .def_static("box", &RigidShape::box, py::arg("half_extents"), "A box of these half extents (m).")
      .def_static("sphere", &RigidShape::sphere, py::arg("radius"), "A sphere (m).")
      .def_static("cylinder", &RigidShape::cylinder, py::arg("radius"), py::arg("half_height"),
                  "A cylinder along the body's local y axis (m).")
      .def_static("capsule", &RigidShape::capsule, py::arg("radius"), py::arg("half_height"),
                  "A capsule along the body's local y axis (m).")
      .def_static("plane", &RigidShape::plane, py::arg("normal"), py::arg("offset"),
                  "The static plane n.x = offset (static bodies only).")
      .def_static(
          "convex_hull",
          [](const py::handle& points) { return RigidShape::convexHull(toVec3s(points, "convex_hull: points")); },
          py::arg("points"), "The convex hull of these (N, 3) points, in the body's frame about its centre of mass.")
      .def_static(
          "triangle_mesh",
          [](const py::handle& vertices, const py::handle& triangles) {
            return RigidShape::triangleMesh(toVec3s(vertices, "triangle_mesh: vertices"),
                                            toIndexTuples<3>(triangles, "triangle_mesh: triangles"));
          },
          py::arg("vertices"), py::arg("triangles"), "A triangle mesh (static bodies only).")
      .def("__repr__", [](const RigidShape& s) {
        return "RigidShape(" + std::string(py::str(py::cast(s.type))) + ")";
      });

  py::class_<RigidBodyDesc> desc(module, "RigidBodyDesc",
                                 "Everything World.add_rigid_body needs; set fields by keyword: "
                                 "RigidBodyDesc(name='box', shape=RigidShape.box((0.1, 0.1, 0.1)), mass=1.0).");
  defKeywordInit<RigidBodyDesc>(desc);
  desc.def_readwrite("name", &RigidBodyDesc::name, "Name, for find_rigid_body and messages.")
      .def_readwrite("shape", &RigidBodyDesc::shape, "The RigidShape.")
      .def_readwrite("motion", &RigidBodyDesc::motion, "The MotionType.")
      .def_readwrite("mass", &RigidBodyDesc::mass, "kg (dynamic bodies only).")
      .def_readwrite("position", &RigidBodyDesc::position, "Centre of mass, world frame (m).")
      .def_readwrite("orientation", &RigidBodyDesc::orientation, "Quaternion (w, x, y, z).")
      .def_readwrite("linear_velocity", &RigidBodyDesc::linearVelocity, "m/s.")
      .def_readwrite("angular_velocity", &RigidBodyDesc::angularVelocity, "rad/s, world frame.")
      .def_readwrite("friction", &RigidBodyDesc::friction, "Friction coefficient.")
      .def_readwrite("restitution", &RigidBodyDesc::restitution, "Restitution coefficient.")
      .def_readwrite("linear_damping", &RigidBodyDesc::linearDamping,
                     "Fraction of the linear velocity lost per second, in [0, 1] (Bullet's damping).")
      .def_readwrite("angular_damping", &RigidBodyDesc::angularDamping,
                     "Fraction of the angular velocity lost per second, in [0, 1].")
      .def_readwrite("can_sleep", &RigidBodyDesc::canSleep,
                     "Whether Bullet may put it to sleep after 2 s at rest (then it reports no contact forces).")
      .def_property(
          "collision_group", [](const RigidBodyDesc& d) { return d.collisionGroup; },
          [](RigidBodyDesc& d, int64_t group) { d.collisionGroup = toCollisionBits(group, "RigidBodyDesc.collision_group"); },
          "The groups it is in, a set of 32 bits (default DEFAULT_COLLISION_GROUP); see collision_groups_meet.")
      .def_property(
          "collision_mask", [](const RigidBodyDesc& d) { return d.collisionMask; },
          [](RigidBodyDesc& d, int64_t mask) { d.collisionMask = toCollisionBits(mask, "RigidBodyDesc.collision_mask"); },
          "The groups it collides with (default ALL_COLLISION_GROUPS).");

  py::class_<HingeDesc> hinge(module, "HingeDesc",
                              "A revolute joint about `axis` through `pivot` (world frame, at creation) between "
                              "body_a and body_b, or body_a and the world when body_b is None. Its angle is body_a's "
                              "rotation about the axis relative to body_b (or the world) since it was made, "
                              "right-handed about the axis; limits keep it in [lower_limit, upper_limit], a motor "
                              "drives its speed.");
  defKeywordInit<HingeDesc>(hinge);
  hinge.def_readwrite("body_a", &HingeDesc::bodyA, "A RigidBodyId.")
      .def_readwrite("body_b", &HingeDesc::bodyB, "A RigidBodyId, or None for the world.")
      .def_readwrite("pivot", &HingeDesc::pivot, "World frame (m).")
      .def_readwrite("axis", &HingeDesc::axis, "World frame.")
      .def_readwrite("lower_limit", &HingeDesc::lowerLimit,
                     "rad, in [-pi, pi]; lower_limit > upper_limit (the default 1 > -1) is no limit.")
      .def_readwrite("upper_limit", &HingeDesc::upperLimit, "rad, in [-pi, pi].")
      .def_readwrite("motor", &HingeDesc::motor, "Whether a motor drives the hinge's speed.")
      .def_readwrite("motor_target_speed", &HingeDesc::motorTargetSpeed, "rad/s.")
      .def_readwrite("motor_max_torque", &HingeDesc::motorMaxTorque, "N*m, >= 0: the most the motor applies.");

  py::class_<RigidContact>(module, "RigidContact",
                           "A contact point between two rigid bodies (Bullet's) in the last step. Impulses are on "
                           "body_a; body_b got the opposite.")
      .def_readonly("body_a", &RigidContact::bodyA, "A RigidBodyId.")
      .def_readonly("body_b", &RigidContact::bodyB, "A RigidBodyId.")
      .def_readonly("point_on_a", &RigidContact::pointOnA, "World frame (m).")
      .def_readonly("point_on_b", &RigidContact::pointOnB, "World frame (m).")
      .def_readonly("normal", &RigidContact::normal, "From B to A.")
      .def_readonly("distance", &RigidContact::distance, "m, negative when penetrating.")
      .def_readonly("normal_impulse", &RigidContact::normalImpulse, "N*s, >= 0.")
      .def_readonly("friction_impulse", &RigidContact::frictionImpulse, "N*s, tangential.")
      .def(
          "to_dict",
          [](const RigidContact& c) {
            py::dict d;
            d["body_a"] = c.bodyA.index;
            d["body_b"] = c.bodyB.index;
            d["point_on_a"] = c.pointOnA;
            d["point_on_b"] = c.pointOnB;
            d["normal"] = c.normal;
            d["distance"] = c.distance;
            d["normal_impulse"] = c.normalImpulse;
            d["friction_impulse"] = c.frictionImpulse;
            return d;
          },
          "The contact as a dict (ids as indices).")
      .def("__repr__", [](const RigidContact& c) {
        return "RigidContact(body_a=" + std::to_string(c.bodyA.index) + ", body_b=" + std::to_string(c.bodyB.index) +
               ", normal_impulse=" + std::to_string(c.normalImpulse) + ")";
      });

  py::class_<FixedJointDesc> fixed(module, "FixedJointDesc",
                                   "Holds body_a to body_b (or to the world when None) in their pose at creation.");
  defKeywordInit<FixedJointDesc>(fixed);
  fixed.def_readwrite("body_a", &FixedJointDesc::bodyA, "A RigidBodyId.")
      .def_readwrite("body_b", &FixedJointDesc::bodyB, "A RigidBodyId, or None for the world.");
}

}  // namespace tandem::python
