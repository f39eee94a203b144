// Recording a run, step by step, to a CSV file that loads straight into numpy or pandas.
//
// One header line, then one row per rigid body per step (and, with nodes, one row per
// deformable node per step), all with the same columns:
//
//   step,time,kind,name,index,x,y,z,qw,qx,qy,qz,vx,vy,vz,wx,wy,wz
//
// kind is "rigid" or "node"; name is the body's name; index is the rigid body's index or the
// node's index in its deformable; x,y,z the position (m); qw..qz the orientation (rigid only);
// vx,vy,vz the linear velocity (m/s); wx,wy,wz the angular velocity (rad/s, world frame, rigid
// only). Fields that do not apply are empty. Numbers are written to the last bit (%.17g).
#pragma once

#include <tandem/export.h>
#include <tandem/world.h>

#include <cstdio>
#include <memory>
#include <string>

namespace tandem {

class TANDEM_API StepRecorder {
 public:
  // Opens (truncates) `path` and writes the header.
  static Result<StepRecorder> open(const std::string& path, bool nodes);

  // Appends the world's present state as the rows of its present step.
  Status write(const World& world);
  // Writes out what is buffered and closes the file; a full disk or a failed write is reported
  // here, so call it (the destructor closes without telling).
  Status close();

 private:
  struct FileCloser {
    void operator()(std::FILE* file) const { std::fclose(file); }
  };
  StepRecorder(std::FILE* file, std::string path, bool nodes) : m_file(file), m_path(std::move(path)), m_nodes(nodes) {}

  std::unique_ptr<std::FILE, FileCloser> m_file;
  std::string m_path;
  bool m_nodes = false;
};

}  // namespace tandem
