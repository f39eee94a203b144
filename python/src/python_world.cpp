#include "python_world.h"

#include <string>

namespace tandem::python {
namespace {

std::string missing(const char* what, const char* kind, int32_t index, int count) {
  return std::string(what) + ": no " + kind + " with id " + std::to_string(index) + " (the world has " +
         std::to_string(count) + ")";
}

void makeReadOnly(py::array& view) {
  py::detail::array_proxy(view.ptr())->flags &= ~py::detail::npy_api::NPY_ARRAY_WRITEABLE_;
}

}  // namespace

RigidBodyId PythonWorld::checkedRigid(RigidBodyId id, const char* what) const {
  if (id.index < 0 || id.index >= m_world.rigidBodyCount())
    throw py::index_error(missing(what, "rigid body", id.index, m_world.rigidBodyCount()));
  return id;
}

DeformableId PythonWorld::checkedDeformable(DeformableId id, const char* what) const {
  if (id.index < 0 || id.index >= m_world.deformableCount())
    throw py::index_error(missing(what, "deformable", id.index, m_world.deformableCount()));
  return id;
}

GrabId PythonWorld::checkedGrab(GrabId id, const char* what) const {
  if (id.index < 0 || id.index >= static_cast<int32_t>(m_liveGrabs.size()) || !m_liveGrabs[id.index])
    throw py::index_error(std::string(what) + ": no grab with id " + std::to_string(id.index) +
                          " (never added, or removed)");
  return id;
}

void PythonWorld::grabAdded(GrabId id) {
  if (id.index >= static_cast<int32_t>(m_liveGrabs.size())) m_liveGrabs.resize(id.index + 1, false);
  m_liveGrabs[id.index] = true;
}

void PythonWorld::grabRemoved(GrabId id) { m_liveGrabs[id.index] = false; }

py::array PythonWorld::viewOf(const py::object& owner, std::span<const Vec3> vectors) {
  static_assert(sizeof(Vec3) == 3 * sizeof(double), "node positions must be packed triples of doubles");
  const std::vector<py::ssize_t> shape{static_cast<py::ssize_t>(vectors.size()), 3};
  const std::vector<py::ssize_t> strides{sizeof(Vec3), sizeof(double)};
  py::array view(py::dtype::of<double>(), shape, strides, vectors.empty() ? nullptr : vectors.data()->data(), owner);
  makeReadOnly(view);
  return owner.cast<PythonWorld&>().track(std::move(view));
}

py::array PythonWorld::viewOf(const py::object& owner, std::span<const double> values) {
  const std::vector<py::ssize_t> shape{static_cast<py::ssize_t>(values.size())};
  const std::vector<py::ssize_t> strides{sizeof(double)};
  py::array view(py::dtype::of<double>(), shape, strides, values.data(), owner);
  makeReadOnly(view);
  return owner.cast<PythonWorld&>().track(std::move(view));
}

py::array PythonWorld::track(py::array view) {
  // Forget views that are gone, so that the list stays as long as the live ones.
  std::erase_if(m_views, [](const py::weakref& ref) { return ref().is_none(); });
  m_views.emplace_back(view);
  return view;
}

void PythonWorld::checkNoLiveViews(const char* what) {
  std::erase_if(m_views, [](const py::weakref& ref) { return ref().is_none(); });
  if (m_views.empty()) return;
  throw LibraryError(std::string(what) + ": " + std::to_string(m_views.size()) +
                     " NumPy view(s) of this world's nodes (from node_positions, node_velocities or "
                     "node_inverse_masses) are still alive, and adding a deformable may move the storage they "
                     "point into. Copy what you want to keep (numpy.array(view)) and delete the views first");
}

}  // namespace tandem::python
