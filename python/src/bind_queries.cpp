// What the world reports back: contacts of deformable surfaces and ray hits.
#include "bindings.h"

#include <tandem/world.h>

namespace tandem::python {

void bindQueries(py::module_& module) {
  py::class_<ContactReport>(module, "ContactReport",
                            "A contact of a deformable surface in the last step; impulses are on the deformable "
                            "(side A), the other side got the opposite.")
      .def_readonly("deformable", &ContactReport::deformable, "Side A: a DeformableId.")
      .def_readonly("rigid", &ContactReport::rigid, "Side B: a RigidBodyId, or None.")
      .def_readonly("other", &ContactReport::other, "Side B: a DeformableId (possibly the same), or None.")
      .def_readonly("point", &ContactReport::point, "On side A (m).")
      .def_readonly("normal", &ContactReport::normal, "From B to A.")
      .def_readonly("gap", &ContactReport::gap, "m at the start of the step, thickness taken off.")
      .def_readonly("normal_impulse", &ContactReport::normalImpulse, "N*s, >= 0.")
      .def_readonly("friction_impulse", &ContactReport::frictionImpulse, "N*s, tangential.")
      .def("to_dict", [](const ContactReport& c) {
        py::dict d;
        d["deformable"] = c.deformable.index;
        d["rigid"] = c.rigid ? py::cast(c.rigid->index) : py::none();
        d["other"] = c.other ? py::cast(c.other->index) : py::none();
        d["point"] = c.point;
        d["normal"] = c.normal;
        d["gap"] = c.gap;
        d["normal_impulse"] = c.normalImpulse;
        d["friction_impulse"] = c.frictionImpulse;
        return d;
      }, "The contact as a dict (ids as indices).");

  py::class_<RayHit>(module, "RayHit", "The first surface a ray met: a rigid body's shape or a deformable's face.")
      .def_readonly("rigid", &RayHit::rigid, "A RigidBodyId, or None.")
      .def_readonly("deformable", &RayHit::deformable, "A DeformableId, or None.")
      .def_readonly("nodes", &RayHit::nodes, "Deformable: the triangle's node indices.")
      .def_readonly("weights", &RayHit::weights, "Deformable: the hit's barycentric weights on them.")
      .def_readonly("point", &RayHit::point, "m.")
      .def_readonly("normal", &RayHit::normal, "Facing the ray's origin.")
      .def_readonly("distance", &RayHit::distance, "m from the origin along the normalised direction.");
}

}  // namespace tandem::python
