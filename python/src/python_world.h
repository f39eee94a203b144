// tandem.World: a World and what Python needs around it (id checks, the NumPy views it lent,
// snapshots).
#pragma once

#include "bindings.h"

#include <tandem/world.h>

#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <vector>

namespace tandem::python {

// tandem.WorldSnapshot: the library's snapshot and the layout of the world's node arrays when it
// was taken (see PythonWorld::restore).
struct PythonSnapshot {
  WorldSnapshot snapshot;
  uint64_t world = 0;       // the PythonWorld's serial
  uint64_t nodeLayout = 0;  // its node arrays' layout then
};

class PythonWorld {
 public:
  World& world() { return m_world; }
  const World& world() const { return m_world; }

  // The id if the world holds it (World::contains), else tandem.IdError "what: " and the
  // library's words for what is wrong with it ("rigid body 3 (generation 0) was removed").
  template <class Id>
  Id checked(Id id, const char* what) const {
    if (!m_world.contains(id)) throw IdError(std::string(what) + ": " + lookupMessage(id));
    return id;
  }

  // Raises a refused call's error: tandem.IdError when `id` (what the call took) is not held,
  // else tandem.Error; the library's message either way.
  template <class Id>
  void check(const Status& status, Id id) const {
    if (status) return;
    if (!m_world.contains(id)) throw IdError(status.message());
    throw LibraryError(status.message());
  }

  // A read-only NumPy view of the world's own node data (no copy), whose base is `owner`, this
  // world's Python object, which it keeps alive.
  static py::array viewOf(const py::object& owner, std::span<const Vec3> vectors);
  static py::array viewOf(const py::object& owner, std::span<const double> values);

  // Adding a deformable may move the storage every view points into. Refuses (tandem.Error
  // naming `what`) while any view of this world is alive, so that none is left pointing at
  // freed memory; then counts a new layout of the node arrays.
  void nodeArraysChanging(const char* what);

  // Snapshots remember the node arrays' layout. Restoring one of this world's taken with another
  // layout (before or after a deformable was added) resizes the arrays, which may move them:
  // refused while views are alive, as adding is.
  std::unique_ptr<PythonSnapshot> snapshot() const;
  void restore(const PythonSnapshot& snapshot);

 private:
  py::array track(py::array view);
  void checkNoLiveViews(const char* what);
  std::string lookupMessage(RigidBodyId id) const;
  std::string lookupMessage(DeformableId id) const;
  std::string lookupMessage(JointId id) const;
  std::string lookupMessage(AnchorId id) const;
  std::string lookupMessage(FixedPointId id) const;
  std::string lookupMessage(GrabId id) const;
  static uint64_t nextSerial();

  World m_world;
  uint64_t m_serial = nextSerial();  // this world among all made in this process
  std::vector<py::weakref> m_views;
  uint64_t m_nodeLayout = 0;      // which layout the node arrays have now
  uint64_t m_nextNodeLayout = 1;  // never reused: equal numbers mean the same arrays
};

// World's calls that push, move, filter, drive hinges, remove and snapshot (bind_world_edit.cpp),
// with the module-level pieces they use.
void bindWorldEditing(py::module_& module, py::class_<PythonWorld>& cls);

}  // namespace tandem::python
