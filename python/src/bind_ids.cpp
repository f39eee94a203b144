// Typed ids: what add_* returns and the world's queries take. Each is a small value with an
// index; ids of different kinds do not mix.
#include "bindings.h"

#include <tandem/world.h>

namespace tandem::python {
namespace {

template <class Id>
void bindId(py::module_& module, const char* name, const char* doc) {
  py::class_<Id>(module, name, doc)
      .def(py::init([](int32_t index) { return Id{index}; }), py::arg("index"), "The id with this index.")
      .def_readonly("index", &Id::index, "Index of what this id names, in the order it was added.")
      .def("__eq__", [](const Id& a, const Id& b) { return a.index == b.index; }, py::is_operator())
      .def("__hash__", [name](const Id& id) { return py::hash(py::make_tuple(name, id.index)); })
      .def("__int__", [](const Id& id) { return id.index; })
      .def("__index__", [](const Id& id) { return id.index; })
      .def("__repr__", [name](const Id& id) { return std::string(name) + "(" + std::to_string(id.index) + ")"; });
}

}  // namespace

void bindIds(py::module_& module) {
  bindId<RigidBodyId>(module, "RigidBodyId", "Names a rigid body of a World (World.add_rigid_body).");
  bindId<DeformableId>(module, "DeformableId", "Names a deformable body of a World (World.add_deformable).");
  bindId<AnchorId>(module, "AnchorId", "Names an anchor of a World (World.add_anchor).");
  bindId<FixedPointId>(module, "FixedPointId", "Names a fixed point of a World (World.add_fixed_point).");
  bindId<JointId>(module, "JointId", "Names a hinge or fixed joint of a World (World.add_hinge, add_fixed_joint).");
  bindId<GrabId>(module, "GrabId", "Names a grab of a World (World.add_grab); a removed grab's id may be reused.");
}

}  // namespace tandem::python
