// Typed ids: what add_* returns and the world's calls take. Each is a small value: a slot index
// and a generation (world.h, "Ids and what a bad id gets"); ids of different kinds do not mix.
#include "bindings.h"

#include <tandem/world.h>

namespace tandem::python {
namespace {

template <class Id>
void bindId(py::module_& module, const char* name, const char* doc) {
  py::class_<Id>(module, name, doc)
      .def(py::init([](int32_t index, uint32_t generation) { return Id{index, generation}; }), py::arg("index"),
           py::arg("generation") = 0,
           "The id of slot `index` at `generation` (0: the slot's first occupant).")
      .def_readonly("index", &Id::index, "The slot: where what this id names is kept, in the order it was added.")
      .def_readonly("generation", &Id::generation,
                    "How many times the slot was freed before this id's thing took it (0 for the first).")
      .def(
          "__eq__", [](const Id& a, const Id& b) { return a == b; }, py::is_operator())
      .def("__hash__", [name](const Id& id) { return py::hash(py::make_tuple(name, id.index, id.generation)); })
      .def("__int__", [](const Id& id) { return id.index; })
      .def("__index__", [](const Id& id) { return id.index; })
      .def("__repr__", [name](const Id& id) {
        return std::string(name) + "(" + std::to_string(id.index) +
               (id.generation ? ", generation=" + std::to_string(id.generation) : std::string()) + ")";
      });
}

}  // namespace

void bindIds(py::module_& module) {
  bindId<RigidBodyId>(module, "RigidBodyId", "Names a rigid body of a World (World.add_rigid_body).");
  bindId<DeformableId>(module, "DeformableId", "Names a deformable body of a World (World.add_deformable).");
  bindId<AnchorId>(module, "AnchorId", "Names an anchor of a World (World.add_anchor).");
  bindId<FixedPointId>(module, "FixedPointId", "Names a fixed point of a World (World.add_fixed_point).");
  bindId<JointId>(module, "JointId", "Names a hinge or fixed joint of a World (World.add_hinge, add_fixed_joint).");
  bindId<GrabId>(module, "GrabId", "Names a grab of a World (World.add_grab).");
}

}  // namespace tandem::python
