// Where rendered frames go: PNG files (stb_image_write) or an H.264 video (ffmpeg with
// libx264, fed raw frames through a pipe).
#pragma once

#include <tandem/types.h>

#include <cstdint>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

namespace tandem::render {

// `rgb`: width × height × 3 bytes, top row first.
Status writePng(const std::string& path, int width, int height, const std::vector<uint8_t>& rgb);

class VideoWriter {
 public:
  // Starts ffmpeg; an error says when it is missing or refuses.
  static Result<std::unique_ptr<VideoWriter>> open(const std::string& path, int width, int height, double fps);
  ~VideoWriter();
  VideoWriter(const VideoWriter&) = delete;
  VideoWriter& operator=(const VideoWriter&) = delete;

  Status write(const std::vector<uint8_t>& rgb);
  Status close();  // waits for ffmpeg; an error when it failed

 private:
  VideoWriter() = default;
  std::FILE* m_pipe = nullptr;
  std::string m_path;
  size_t m_frameBytes = 0;
};

}  // namespace tandem::render
