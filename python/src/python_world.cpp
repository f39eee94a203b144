#include "python_world.h"

#include <string>

namespace tandem::python {
namespace {

void makeReadOnly(py::array& view) {
  py::detail::array_proxy(view.ptr())->flags &= ~py::detail::npy_api::NPY_ARRAY_WRITEABLE_;
}

// What a query recorded about a bad id (World::takeLookupError), after clearing any older record.
template <class Query>
std::string recordedLookupError(const World& world, Query query) {
  (void)world.takeLookupError();
  query();
  return world.takeLookupError().message();
}

}  // namespace

// Each asks a cheap query with the bad id, which records the library's words for it.
std::string PythonWorld::lookupMessage(RigidBodyId id) const {
  return recordedLookupError(m_world, [&] { (void)m_world.rigidMass(id); });
}
std::string PythonWorld::lookupMessage(DeformableId id) const {
  return recordedLookupError(m_world, [&] { (void)m_world.deformableName(id); });
}
std::string PythonWorld::lookupMessage(JointId id) const {
  return recordedLookupError(m_world, [&] { (void)m_world.hingeAngle(id); });
}
std::string PythonWorld::lookupMessage(AnchorId id) const {
  return recordedLookupError(m_world, [&] { (void)m_world.anchorState(id); });
}
std::string PythonWorld::lookupMessage(FixedPointId id) const {
  return recordedLookupError(m_world, [&] { (void)m_world.fixedPointImpulse(id); });
}
std::string PythonWorld::lookupMessage(GrabId id) const {
  return recordedLookupError(m_world, [&] { (void)m_world.grabImpulse(id); });
}

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
                     "node_inverse_masses) are still alive, and this may move the storage they "
                     "point into. Copy what you want to keep (numpy.array(view)) and delete the views first");
}

void PythonWorld::nodeArraysChanging(const char* what) {
  checkNoLiveViews(what);
  m_nodeLayout = m_nextNodeLayout++;
}

std::unique_ptr<PythonSnapshot> PythonWorld::snapshot() const {
  auto taken = std::make_unique<PythonSnapshot>();
  taken->snapshot = m_world.snapshot();
  taken->world = m_serial;
  taken->nodeLayout = m_nodeLayout;
  return taken;
}

void PythonWorld::restore(const PythonSnapshot& snapshot) {
  // Another world's snapshot is the library's to refuse (it changes nothing then, and says why).
  if (snapshot.world == m_serial && snapshot.nodeLayout != m_nodeLayout) checkNoLiveViews("restore");
  tandem::python::check(m_world.restore(snapshot.snapshot));
  m_nodeLayout = snapshot.nodeLayout;
}

uint64_t PythonWorld::nextSerial() {
  static uint64_t serials = 0;  // only ever touched with the GIL held
  return ++serials;
}

}  // namespace tandem::python
