// The CSV record (include/tandem/record.h): a row per rigid body (and node) per step, %.17g.
#include "record_writer.h"

#include <cerrno>
#include <cstdio>
#include <cstring>

namespace tandem {
namespace {

// A name with a comma, quote or line break is quoted, quotes doubled (RFC 4180).
std::string csvField(const std::string& text) {
  if (text.find_first_of(",\"\n\r") == std::string::npos) return text;
  std::string quoted = "\"";
  for (char c : text) quoted += c == '"' ? std::string("\"\"") : std::string(1, c);
  return quoted + "\"";
}

class CsvRecord final : public StepRecorder::Writer {
 public:
  CsvRecord(std::FILE* file, std::string path, bool nodes) : m_file(file), m_path(std::move(path)), m_nodes(nodes) {}

  Status write(const World& world) override {
    std::FILE* f = m_file.get();
    if (!f) return Error{"record: '" + m_path + "' is already closed"};
    const long long step = world.stepCount();
    const double time = world.time();
    for (int b = 0; b < world.rigidBodyCount(); ++b) {
      const RigidBodyId id{b};
      const Vec3 x = world.rigidPosition(id), v = world.rigidLinearVelocity(id), w = world.rigidAngularVelocity(id);
      const Quat q = world.rigidOrientation(id);
      std::fprintf(f, "%lld,%.17g,rigid,%s,%d,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g\n",
                   step, time, csvField(world.rigidName(id)).c_str(), b, x.x(), x.y(), x.z(), q.w(), q.x(), q.y(), q.z(),
                   v.x(), v.y(), v.z(), w.x(), w.y(), w.z());
    }
    if (m_nodes) {
      for (int d = 0; d < world.deformableCount(); ++d) {
        const DeformableId id{d};
        const std::string name = csvField(world.deformableName(id));
        const std::span<const Vec3> x = world.nodePositions(id), v = world.nodeVelocities(id);
        for (size_t n = 0; n < x.size(); ++n)
          std::fprintf(f, "%lld,%.17g,node,%s,%zu,%.17g,%.17g,%.17g,,,,,%.17g,%.17g,%.17g,,,\n", step, time, name.c_str(), n,
                       x[n].x(), x[n].y(), x[n].z(), v[n].x(), v[n].y(), v[n].z());
      }
    }
    if (std::ferror(f)) return Error{"record: writing '" + m_path + "' failed"};
    return {};
  }

  Status close() override {
    std::FILE* f = m_file.release();
    if (!f) return Error{"record: '" + m_path + "' is already closed"};
    return closeRecordFile(f, m_path);
  }

 private:
  struct FileCloser {
    void operator()(std::FILE* file) const { std::fclose(file); }
  };
  std::unique_ptr<std::FILE, FileCloser> m_file;
  std::string m_path;
  bool m_nodes = false;
};

}  // namespace

Result<std::unique_ptr<StepRecorder::Writer>> openCsvRecord(const std::string& path, bool nodes) {
  std::FILE* file = std::fopen(path.c_str(), "w");
  if (!file) return Error{"record: cannot write '" + path + "'"};
  std::fputs("step,time,kind,name,index,x,y,z,qw,qx,qy,qz,vx,vy,vz,wx,wy,wz\n", file);
  return std::unique_ptr<StepRecorder::Writer>(std::make_unique<CsvRecord>(file, path, nodes));
}

}  // namespace tandem
