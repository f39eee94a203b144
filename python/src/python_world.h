// tandem.World: a World and what Python needs around it (id checks, the NumPy views it lent).
#pragma once

#include "bindings.h"

#include <tandem/world.h>

#include <span>
#include <vector>

namespace tandem::python {

class PythonWorld {
 public:
  World& world() { return m_world; }
  const World& world() const { return m_world; }

  // The id if it names something in the world, else an IndexError naming `what`, the id and
  // how many there are. (World's queries take ids on trust; Python's must not crash.)
  RigidBodyId checkedRigid(RigidBodyId id, const char* what) const;
  DeformableId checkedDeformable(DeformableId id, const char* what) const;
  GrabId checkedGrab(GrabId id, const char* what) const;
  void grabAdded(GrabId id);
  void grabRemoved(GrabId id);

  // A read-only NumPy view of the world's own node data (no copy), whose base is `owner`, this
  // world's Python object, which it keeps alive.
  static py::array viewOf(const py::object& owner, std::span<const Vec3> vectors);
  static py::array viewOf(const py::object& owner, std::span<const double> values);

  // Adding a deformable may move the storage every view points into. Refuses (tandem.Error
  // naming `what`) while any view of this world is alive, so that none is left pointing at
  // freed memory.
  void checkNoLiveViews(const char* what);

 private:
  py::array track(py::array view);

  World m_world;
  std::vector<py::weakref> m_views;
  std::vector<bool> m_liveGrabs;  // by grab index
};

}  // namespace tandem::python
