// The .npz record (include/tandem/record.h): each array's rows go to a temporary file as the run
// goes (memory stays small however long the run), and the archive is written whole at close.
#include "npz_file.h"
#include "record_writer.h"

#include <array>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>

#include <unistd.h>

namespace tandem {
namespace {

struct FileCloser {
  void operator()(std::FILE* file) const { std::fclose(file); }
};
using File = std::unique_ptr<std::FILE, FileCloser>;

// An anonymous temporary file beside `path` (same disk as the record), or in the system's
// temporary folder when that folder takes none.
File temporaryFileBeside(const std::string& path) {
  std::filesystem::path folder = std::filesystem::path(path).parent_path();
  if (folder.empty()) folder = ".";
  std::string name = (folder / ".tandem-record-XXXXXX").string();
  const int descriptor = mkstemp(name.data());
  if (descriptor >= 0) {
    unlink(name.c_str());
    if (std::FILE* file = fdopen(descriptor, "w+b")) return File(file);
    ::close(descriptor);
  }
  return File(std::tmpfile());
}

// One array that grows by a row per step: its element type, the shape of a row, its data so far.
struct GrowingArray {
  std::string name;
  std::string descr;
  std::vector<int64_t> rowShape;
  File data;
  uint64_t bytes = 0;
};

class NpzRecord final : public StepRecorder::Writer {
 public:
  NpzRecord(File file, std::string path, bool nodes) : m_file(std::move(file)), m_path(std::move(path)), m_nodes(nodes) {}

  Status write(const World& world) override {
    if (!m_file) return Error{"record: '" + m_path + "' is already closed"};
    if (m_arrays.empty()) {
      if (Status s = start(world); !s) return s;
    } else if (Status s = checkSameBodies(world); !s) {
      return s;
    }
    const int64_t step = world.stepCount();
    const double time = world.time();
    append(kStep, &step, sizeof step);
    append(kTime, &time, sizeof time);
    m_row.clear();
    for (int b = 0; b < world.rigidBodyCount(); ++b) {
      const Vec3 x = world.rigidPosition(RigidBodyId{b});
      m_row.insert(m_row.end(), {x.x(), x.y(), x.z()});
    }
    appendRow(kRigidPosition);
    for (int b = 0; b < world.rigidBodyCount(); ++b) {
      const Quat q = world.rigidOrientation(RigidBodyId{b});
      m_row.insert(m_row.end(), {q.w(), q.x(), q.y(), q.z()});
    }
    appendRow(kRigidOrientation);
    for (int b = 0; b < world.rigidBodyCount(); ++b) {
      const Vec3 v = world.rigidLinearVelocity(RigidBodyId{b});
      m_row.insert(m_row.end(), {v.x(), v.y(), v.z()});
    }
    appendRow(kRigidLinearVelocity);
    for (int b = 0; b < world.rigidBodyCount(); ++b) {
      const Vec3 w = world.rigidAngularVelocity(RigidBodyId{b});
      m_row.insert(m_row.end(), {w.x(), w.y(), w.z()});
    }
    appendRow(kRigidAngularVelocity);
    if (m_nodes) {
      for (int d = 0; d < world.deformableCount(); ++d)
        for (const Vec3& x : world.nodePositions(DeformableId{d})) m_row.insert(m_row.end(), {x.x(), x.y(), x.z()});
      appendRow(kNodePosition);
      for (int d = 0; d < world.deformableCount(); ++d)
        for (const Vec3& v : world.nodeVelocities(DeformableId{d})) m_row.insert(m_row.end(), {v.x(), v.y(), v.z()});
      appendRow(kNodeVelocity);
    }
    ++m_steps;
    for (const GrowingArray& array : m_arrays)
      if (std::ferror(array.data.get()))
        return Error{"record: writing the temporary data of '" + m_path + "' failed: " + std::strerror(errno)};
    return {};
  }

  Status close() override {
    if (!m_file) return Error{"record: '" + m_path + "' is already closed"};
    File file = std::move(m_file);
    NpzWriter npz(file.get(), m_path);
    for (GrowingArray& array : m_arrays) {
      std::vector<int64_t> shape{m_steps};
      shape.insert(shape.end(), array.rowShape.begin(), array.rowShape.end());
      if (std::fflush(array.data.get()) != 0)
        return Error{"record: writing the temporary data of '" + m_path + "' failed: " + std::strerror(errno)};
      if (Status s = npz.addArray(array.name, array.descr, shape, array.data.get(), array.bytes); !s) return s;
      if (&array == &m_arrays[kTime]) {  // the names after step and time, before the big arrays
        if (Status s = addNames(npz, "rigid_name", m_rigidNames); !s) return s;
        if (m_nodes) {
          if (Status s = addNames(npz, "deformable_name", m_deformableNames); !s) return s;
          if (Status s = npz.addArray("deformable_node_start", "<i8", {static_cast<int64_t>(m_nodeStarts.size())},
                                      m_nodeStarts.data(), m_nodeStarts.size() * sizeof(int64_t));
              !s)
            return s;
        }
      }
    }
    m_arrays.clear();
    if (Status s = npz.finish(); !s) return s;
    return closeRecordFile(file.release(), m_path);
  }

 private:
  enum ArrayIndex : size_t { kStep, kTime, kRigidPosition, kRigidOrientation, kRigidLinearVelocity, kRigidAngularVelocity,
                             kNodePosition, kNodeVelocity };

  Status start(const World& world) {
    const int64_t bodies = world.rigidBodyCount();
    for (int b = 0; b < world.rigidBodyCount(); ++b) m_rigidNames.push_back(world.rigidName(RigidBodyId{b}));
    m_nodeStarts.push_back(0);
    for (int d = 0; d < world.deformableCount(); ++d) {
      m_deformableNames.push_back(world.deformableName(DeformableId{d}));
      m_nodeStarts.push_back(m_nodeStarts.back() + static_cast<int64_t>(world.nodePositions(DeformableId{d}).size()));
    }
    const int64_t nodes = m_nodeStarts.back();
    const std::vector<std::array<std::string, 2>> names{{"step", "<i8"}, {"time", "<f8"}, {"rigid_position", "<f8"},
                                                        {"rigid_orientation", "<f8"}, {"rigid_linear_velocity", "<f8"},
                                                        {"rigid_angular_velocity", "<f8"}, {"node_position", "<f8"},
                                                        {"node_velocity", "<f8"}};
    const std::vector<std::vector<int64_t>> rowShapes{{}, {}, {bodies, 3}, {bodies, 4}, {bodies, 3}, {bodies, 3}, {nodes, 3}, {nodes, 3}};
    const size_t count = m_nodes ? names.size() : kNodePosition;
    for (size_t a = 0; a < count; ++a) {
      File data = temporaryFileBeside(m_path);
      if (!data) return Error{"record: cannot make a temporary file for '" + m_path + "': " + std::strerror(errno)};
      m_arrays.push_back(GrowingArray{names[a][0], names[a][1], rowShapes[a], std::move(data), 0});
    }
    m_row.reserve(static_cast<size_t>(3 * nodes + 4 * bodies));
    return {};
  }

  Status checkSameBodies(const World& world) const {
    const int64_t nodes = m_nodeStarts.back();
    int64_t nodesNow = 0;
    for (int d = 0; d < world.deformableCount(); ++d) nodesNow += static_cast<int64_t>(world.nodePositions(DeformableId{d}).size());
    if (static_cast<size_t>(world.rigidBodyCount()) != m_rigidNames.size() || nodesNow != nodes ||
        static_cast<size_t>(world.deformableCount()) != m_deformableNames.size())
      return Error{"record: '" + m_path + "' started with " + std::to_string(m_rigidNames.size()) + " rigid bodies and " +
                   std::to_string(nodes) + " nodes; the world now has " + std::to_string(world.rigidBodyCount()) +
                   " and " + std::to_string(nodesNow) + " (an .npz record holds a fixed set)"};
    return {};
  }

  void append(size_t array, const void* data, size_t bytes) {
    std::fwrite(data, 1, bytes, m_arrays[array].data.get());
    m_arrays[array].bytes += bytes;
  }
  void appendRow(size_t array) {
    append(array, m_row.data(), m_row.size() * sizeof(double));
    m_row.clear();
  }

  static Status addNames(NpzWriter& npz, const std::string& name, const std::vector<std::string>& names) {
    std::string descr;
    const std::vector<char32_t> items = npyUnicode(names, descr);
    return npz.addArray(name, descr, {static_cast<int64_t>(names.size())}, items.data(), items.size() * sizeof(char32_t));
  }

  File m_file;
  std::string m_path;
  bool m_nodes = false;
  int64_t m_steps = 0;
  std::vector<GrowingArray> m_arrays;
  std::vector<std::string> m_rigidNames, m_deformableNames;
  std::vector<int64_t> m_nodeStarts;
  std::vector<double> m_row;
};

}  // namespace

Result<std::unique_ptr<StepRecorder::Writer>> openNpzRecord(const std::string& path, bool nodes) {
  std::FILE* file = std::fopen(path.c_str(), "wb");
  if (!file) return Error{"record: cannot write '" + path + "'"};
  return std::unique_ptr<StepRecorder::Writer>(std::make_unique<NpzRecord>(File(file), path, nodes));
}

}  // namespace tandem
