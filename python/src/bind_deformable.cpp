// Deformable bodies: their settings and description, and what ties them to the world (anchors,
// grabs).
#include "bindings.h"

#include <tandem/world.h>

namespace tandem::python {

void bindDeformable(py::module_& module) {
  module.attr("UNBOUNDED") = kUnbounded;

  py::enum_<InextensibilityMode>(module, "InextensibilityMode",
                                 "How an inextensibility row's impulse is bounded: RESIST_BOTH, "
                                 "RESIST_COMPRESSION (pushes apart only), RESIST_STRETCH (pulls together only).")
      .value("RESIST_BOTH", InextensibilityMode::ResistBoth)
      .value("RESIST_COMPRESSION", InextensibilityMode::ResistCompression)
      .value("RESIST_STRETCH", InextensibilityMode::ResistStretch);
  py::enum_<RowSolverKind>(module, "RowSolverKind",
                           "How bilateral rows are solved per sweep: AUTO, DIRECT (exactly, as one block), "
                           "ITERATIVE (projected Gauss-Seidel).")
      .value("AUTO", RowSolverKind::Auto)
      .value("DIRECT", RowSolverKind::Direct)
      .value("ITERATIVE", RowSolverKind::Iterative);
  py::enum_<ParadigmType>(module, "ParadigmType", "How a deformable computes its unconstrained node velocities.")
      .value("MASS_SPRING", ParadigmType::MassSpring)
      .value("SHAPE_MATCHING", ParadigmType::ShapeMatching)
      .value("POSITION_BASED", ParadigmType::PositionBased)
      .value("COROTATIONAL_FEM", ParadigmType::CorotationalFem);

  py::class_<InextensibilitySettings> inextensibility(module, "InextensibilitySettings",
                                                      "Rows that keep edges at their rest length.");
  defKeywordInit<InextensibilitySettings>(inextensibility);
  inextensibility.def_readwrite("enabled", &InextensibilitySettings::enabled, "Whether the rows exist.")
      .def_readwrite("mode", &InextensibilitySettings::mode, "The InextensibilityMode.")
      .def_readwrite("max_force", &InextensibilitySettings::maxForce, "N; the impulse bound per step is max_force*h.")
      .def_readwrite("shear_edges", &InextensibilitySettings::shearEdges, "Also on the shear edges.");

  py::class_<BendingSettings> bending(module, "BendingSettings",
                                     "A damped, bounded spring resisting folding across each interior edge.");
  defKeywordInit<BendingSettings>(bending);
  bending.def_readwrite("enabled", &BendingSettings::enabled, "Whether the rows exist.")
      .def_readwrite("max_force", &BendingSettings::maxForce, "N; bounds |lambda| <= max_force*h.")
      .def_readwrite("frequency", &BendingSettings::frequency, "Hz: how stiff (infinite: a rigid row).")
      .def_readwrite("damping_ratio", &BendingSettings::dampingRatio, "1 is critically damped.");

  py::class_<MassSpringSettings> springs(module, "MassSpringSettings", "Springs on every edge.");
  defKeywordInit<MassSpringSettings>(springs);
  springs.def_readwrite("stiffness", &MassSpringSettings::stiffness, "N/m per edge spring.")
      .def_readwrite("damping", &MassSpringSettings::damping, "N*s/m per edge spring, along the edge.")
      .def_readwrite("implicit", &MassSpringSettings::implicit, "Linearised backward Euler (else explicit).");

  py::class_<ParadigmSettings> paradigm(module, "ParadigmSettings", "The deformable model and its parameters.");
  defKeywordInit<ParadigmSettings>(paradigm);
  paradigm.def_readwrite("type", &ParadigmSettings::type, "The ParadigmType.")
      .def_readwrite("stiffness", &ParadigmSettings::stiffness, "k in (0, 1] (shape matching, position based).")
      .def_readwrite("damping", &ParadigmSettings::damping, "gamma in [0, 1].")
      .def_readwrite("iterations", &ParadigmSettings::iterations, "Constraint projections per step (position based).")
      .def_readwrite("youngs_modulus", &ParadigmSettings::youngsModulus, "E, Pa (co-rotational FEM).")
      .def_readwrite("poisson_ratio", &ParadigmSettings::poissonRatio, "nu in [0, 0.5) (co-rotational FEM).");

  py::class_<CollisionSettings> collision(module, "CollisionSettings", "How a deformable's surface collides.");
  defKeywordInit<CollisionSettings>(collision);
  collision.def_readwrite("enabled", &CollisionSettings::enabled, "Against rigid bodies and other deformables.")
      .def_readwrite("self_collision", &CollisionSettings::selfCollision, "Against itself.")
      .def_readwrite("thickness", &CollisionSettings::thickness, "m kept between the surface and what it touches.")
      .def_readwrite("friction", &CollisionSettings::friction, "mu; a contact's mu is the product of both sides'.")
      .def_property(
          "group", [](const CollisionSettings& c) { return c.group; },
          [](CollisionSettings& c, int64_t group) { c.group = toCollisionBits(group, "CollisionSettings.group"); },
          "The groups the surface is in, a set of 32 bits (default DEFAULT_COLLISION_GROUP); see "
          "collision_groups_meet.")
      .def_property(
          "mask", [](const CollisionSettings& c) { return c.mask; },
          [](CollisionSettings& c, int64_t mask) { c.mask = toCollisionBits(mask, "CollisionSettings.mask"); },
          "The groups it collides with (default ALL_COLLISION_GROUPS).");

  py::class_<DeformableDesc> desc(module, "DeformableDesc",
                                  "Everything World.add_deformable needs; set fields by keyword: "
                                  "DeformableDesc(name='rope', mesh=make_rope(...), "
                                  "inextensibility=InextensibilitySettings(enabled=True)). Nested settings change "
                                  "in place: desc.collision.friction = 0.3.");
  defKeywordInit<DeformableDesc>(desc);
  desc.def_readwrite("name", &DeformableDesc::name, "Name, for find_deformable and messages.")
      .def_readwrite("mesh", &DeformableDesc::mesh, "The DeformableMesh.")
      .def_readwrite("springs", &DeformableDesc::springs, "MassSpringSettings.")
      .def_readwrite("inextensibility", &DeformableDesc::inextensibility, "InextensibilitySettings.")
      .def_readwrite("bending", &DeformableDesc::bending, "BendingSettings.")
      .def_readwrite("paradigm", &DeformableDesc::paradigm, "ParadigmSettings.")
      .def_readwrite("collision", &DeformableDesc::collision, "CollisionSettings.")
      .def_readwrite("row_solver", &DeformableDesc::rowSolver, "RowSolverKind.")
      .def_readwrite("damping", &DeformableDesc::damping,
                     "1/s: each step every node loses this fraction per second of its velocity relative to the "
                     "body's mean velocity (momentum is untouched).");

  py::class_<AnchorDesc> anchor(module, "AnchorDesc",
                                "A point of a deformable (a node, or barycentric weights on up to four nodes) held "
                                "to a point fixed in a rigid body. AnchorDesc.node(deformable, node, body) for one node.");
  defKeywordInit<AnchorDesc>(anchor);
  anchor.def_readwrite("deformable", &AnchorDesc::deformable, "A DeformableId.")
      .def_readwrite("nodes", &AnchorDesc::nodes, "Up to four node indices (unused ones -1).")
      .def_readwrite("weights", &AnchorDesc::weights, "Their barycentric weights, summing to 1.")
      .def_readwrite("node_count", &AnchorDesc::nodeCount, "How many of nodes are used (1 to 4).")
      .def_readwrite("body", &AnchorDesc::body, "The RigidBodyId.")
      .def_readwrite("local_point", &AnchorDesc::localPoint,
                     "In the body's frame; None: where the deformable point is now.")
      .def_readwrite("max_force", &AnchorDesc::maxForce, "N; the most the anchor pulls with.")
      .def_static("node", &AnchorDesc::node, py::arg("deformable"), py::arg("node"), py::arg("body"),
                  "An anchor of one node to a rigid body, where the node is now.");

  py::class_<AnchorState>(module, "AnchorState", "An anchor after the last step.")
      .def_readonly("impulse", &AnchorState::impulse,
                    "N*s applied to the deformable in the last step (the body got -impulse).")
      .def_readonly("world_point_on_body", &AnchorState::worldPointOnBody, "m.")
      .def_readonly("world_point_on_deformable", &AnchorState::worldPointOnDeformable, "m.");

  py::class_<GrabDesc> grab(module, "GrabDesc",
                            "A point of a dynamic rigid body (body, point) or of a deformable (deformable, nodes, "
                            "weights, node_count) pulled towards target by a damped spring of `frequency` Hz up "
                            "to max_force, solved with everything else.");
  defKeywordInit<GrabDesc>(grab);
  grab.def_readwrite("body", &GrabDesc::body, "A RigidBodyId, or None.")
      .def_readwrite("deformable", &GrabDesc::deformable, "A DeformableId, or None.")
      .def_readwrite("point", &GrabDesc::point, "Rigid: the grabbed point, world frame, now (m).")
      .def_readwrite("nodes", &GrabDesc::nodes, "Deformable: up to four node indices.")
      .def_readwrite("weights", &GrabDesc::weights, "Deformable: their weights, summing to 1.")
      .def_readwrite("node_count", &GrabDesc::nodeCount, "Deformable: how many nodes are used.")
      .def_readwrite("target", &GrabDesc::target, "World frame (m); moved with World.set_grab_target.")
      .def_readwrite("frequency", &GrabDesc::frequency, "Hz.")
      .def_readwrite("damping_ratio", &GrabDesc::dampingRatio, "1 is critically damped.")
      .def_readwrite("max_force", &GrabDesc::maxForce, "N.");
}

}  // namespace tandem::python
