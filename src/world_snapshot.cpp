// World: snapshots of the whole state, and restoring them.
//
// Tandem's side is copied whole: nodes, deformable records (models' state, supports), springs,
// every row with its warm-start impulse, the swept edges' coarse levels (kept from step to step
// while they fit), last step's contact impulses by feature, the rigid bodies' state as the rows
// saw it, ids' slots, settings, time and the last report. The direct blocks (factorisations) are
// not copied: they are rebuilt from the rows at the next step, as they would be after any edit,
// which gives the same factors. Bullet's side is bullet_snapshot.cpp's. A member added to
// World::Impl that the next step reads must be copied here too (the record-and-compare test in
// tests/test_snapshot.cpp finds one left out).
#include "world_impl.h"

#include "bullet/bullet_world_impl.h"

#include <atomic>

namespace tandem {

struct WorldSnapshot::Data {
  uint64_t world = 0;  // the serial of the world it was taken from
  uint64_t rigidStructureVersion = 0;
  WorldSettings settings;
  NodeArrays nodes;
  std::vector<DeformableRecord> deformables;
  std::vector<EdgeSpring> springs;
  ConstraintRows rows;
  SweptEdgeCoarseLevel sheetProjectionCoarse;  // kept from step to step while it fits
  std::vector<std::pair<uint64_t, ContactImpulse>> previousContacts;
  std::vector<RigidSolverState> rigid;
  std::vector<MovingSupportRecord> movingSupportRecords;
  std::vector<uint32_t> rigidGroup, rigidMask;
  IdSlots deformableSlots{""}, anchorSlots{""}, fixedPointSlots{""}, grabSlots{""};
  StepReport report;
  double time = 0.0;
  int64_t steps = 0;
  double timeStep = 0.0, substepLength = 0.0;
  std::unique_ptr<bullet::BulletWorld::State> bullet;
};

uint64_t World::Impl::nextSerial() {
  static std::atomic<uint64_t> serials{0};
  return ++serials;
}

WorldSnapshot::WorldSnapshot() = default;
WorldSnapshot::~WorldSnapshot() = default;
WorldSnapshot::WorldSnapshot(WorldSnapshot&&) noexcept = default;
WorldSnapshot& WorldSnapshot::operator=(WorldSnapshot&&) noexcept = default;
WorldSnapshot::WorldSnapshot(std::unique_ptr<Data> data) : m_data(std::move(data)) {}
bool WorldSnapshot::empty() const { return !m_data; }
double WorldSnapshot::time() const { return m_data ? m_data->time : 0.0; }
int64_t WorldSnapshot::stepCount() const { return m_data ? m_data->steps : 0; }

WorldSnapshot World::snapshot() const {
  const Impl& w = *m_impl;
  auto data = std::make_unique<WorldSnapshot::Data>();
  data->world = w.serial;
  data->rigidStructureVersion = w.rigidStructureVersion;
  data->settings = w.settings;
  data->nodes = w.nodes;
  data->deformables = w.deformables;
  data->springs = w.springs;
  data->rows = w.rows;
  data->sheetProjectionCoarse = w.strainScratch.together.coarse;
  data->previousContacts = w.previousContacts;
  data->rigid = w.rigid;
  data->movingSupportRecords = w.movingSupportRecords;
  data->rigidGroup = w.rigidGroup;
  data->rigidMask = w.rigidMask;
  data->deformableSlots = w.deformableSlots;
  data->anchorSlots = w.anchorSlots;
  data->fixedPointSlots = w.fixedPointSlots;
  data->grabSlots = w.grabSlots;
  data->report = w.report;
  data->time = w.time;
  data->steps = w.steps;
  data->timeStep = w.timeStep;
  data->substepLength = w.substepLength;
  data->bullet = w.bullet.saveState();
  return WorldSnapshot(std::move(data));
}

Status World::restore(const WorldSnapshot& snapshot) {
  Impl& w = *m_impl;
  const WorldSnapshot::Data* data = snapshot.data();
  if (!data) return Error{"restore: the snapshot is empty"};
  if (data->world != w.serial) return Error{"restore: the snapshot was taken from another world"};
  if (data->rigidStructureVersion != w.rigidStructureVersion)
    return Error{"restore: rigid bodies or joints were added or removed since the snapshot was taken"};
  w.settings = data->settings;
  w.bullet.setGravity(w.settings.gravity);
  w.nodes = data->nodes;
  w.deformables = data->deformables;
  w.springs = data->springs;
  w.rows = data->rows;
  w.strainScratch.together.coarse = data->sheetProjectionCoarse;
  w.previousContacts = data->previousContacts;
  w.rigid = data->rigid;
  w.movingSupportRecords = data->movingSupportRecords;
  for (size_t b = 0; b < w.rigidGroup.size(); ++b)
    if (w.rigidSlots.liveIndex(static_cast<int32_t>(b)) &&
        (w.rigidGroup[b] != data->rigidGroup[b] || w.rigidMask[b] != data->rigidMask[b]))
      w.bullet.setCollisionFilter(static_cast<int>(b), data->rigidGroup[b], data->rigidMask[b]);
  w.rigidGroup = data->rigidGroup;
  w.rigidMask = data->rigidMask;
  w.deformableSlots = data->deformableSlots;
  w.anchorSlots = data->anchorSlots;
  w.fixedPointSlots = data->fixedPointSlots;
  w.grabSlots = data->grabSlots;
  w.report = data->report;
  w.time = data->time;
  w.steps = data->steps;
  w.timeStep = data->timeStep;
  w.substepLength = data->substepLength;
  w.directBlocks.clear();
  w.directBlocksStale = true;
  w.lookupError.clear();
  const int unplaced = w.bullet.restoreState(*data->bullet);
  if (unplaced > 0)
    return Error{"restore: restored, except the contact points of " + std::to_string(unplaced) +
                 " pairs of rigid bodies, which had moved apart (the next steps differ slightly from the original run)"};
  return {};
}

}  // namespace tandem
