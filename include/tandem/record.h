// Recording a run, step by step, to a file that loads straight into numpy or pandas: CSV text,
// or NumPy's binary .npz (docs/scene-format.md, "Records").
//
// CSV: one header line, then one row per rigid body per step (and, with nodes, one row per
// deformable node per step), all with the same columns:
//
//   step,time,kind,name,index,x,y,z,qw,qx,qy,qz,vx,vy,vz,wx,wy,wz
//
// kind is "rigid" or "node"; name is the body's name; index is the rigid body's index or the
// node's index in its deformable; x,y,z the position (m); qw..qz the orientation (rigid only);
// vx,vy,vz the linear velocity (m/s); wx,wy,wz the angular velocity (rad/s, world frame, rigid
// only). Fields that do not apply are empty. Numbers are written to the last bit (%.17g).
//
// NPZ: a zip archive (stored, uncompressed) of .npy arrays that numpy.load reads without Tandem.
// S is the number of recorded steps (step 0, the start, included), B the rigid bodies, D the
// deformables, N their nodes in all:
//
//   step (S,) int64            time (S,) float64 s
//   rigid_name (B,) unicode    rigid_position (S,B,3) m        rigid_orientation (S,B,4) w,x,y,z
//   rigid_linear_velocity (S,B,3) m/s                          rigid_angular_velocity (S,B,3) rad/s
// and with nodes:
//   deformable_name (D,) unicode    deformable_node_start (D+1,) int64: deformable d's nodes are
//   node_position[:, start[d]:start[d+1]]    node_position (S,N,3) m    node_velocity (S,N,3) m/s
//
// The numbers are the same doubles as the CSV's, 8 bytes each instead of up to 24 characters.
#pragma once

#include <tandem/export.h>
#include <tandem/world.h>

#include <memory>
#include <string>

namespace tandem {

enum class RecordFormat { Csv, Npz };

// Npz for a name ending in .npz (any case), Csv for any other.
TANDEM_API RecordFormat recordFormatOf(const std::string& path);

class TANDEM_API StepRecorder {
 public:
  // Opens (truncates) `path`; CSV writes its header now. The format follows the file's extension
  // unless given.
  static Result<StepRecorder> open(const std::string& path, bool nodes);
  static Result<StepRecorder> open(const std::string& path, bool nodes, RecordFormat format);

  StepRecorder(StepRecorder&&) noexcept;
  StepRecorder& operator=(StepRecorder&&) noexcept;
  ~StepRecorder();

  // Appends the world's present state as the rows of its present step. The world's bodies and
  // nodes must stay the same through a record.
  Status write(const World& world);
  // Writes out what is buffered (an .npz file is written whole here) and closes the file; a full
  // disk or a failed write is reported here, so call it (the destructor closes without telling,
  // and leaves an .npz file empty).
  Status close();

  class Writer;  // one per format (src/record_writer.h)

 private:
  explicit StepRecorder(std::unique_ptr<Writer> writer);
  std::unique_ptr<Writer> m_writer;
};

}  // namespace tandem
