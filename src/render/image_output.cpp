#include "render/image_output.h"

#include <stb_image_write.h>

#include <cstdlib>
#include <filesystem>

namespace tandem::render {

Status writePng(const std::string& path, int width, int height, const std::vector<uint8_t>& rgb) {
  if (rgb.size() != static_cast<size_t>(width) * height * 3) return Error{"png '" + path + "': wrong pixel count"};
  if (!stbi_write_png(path.c_str(), width, height, 3, rgb.data(), width * 3))
    return Error{"png '" + path + "': cannot write the file (does its folder exist?)"};
  return {};
}

namespace {
// Single quotes for the shell, with any single quote inside closed, escaped and reopened.
std::string shellQuoted(const std::string& text) {
  std::string quoted = "'";
  for (char c : text) quoted += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return quoted + "'";
}
}  // namespace

Result<std::unique_ptr<VideoWriter>> VideoWriter::open(const std::string& path, int width, int height, double fps) {
  if (std::system("command -v ffmpeg > /dev/null 2>&1") != 0)
    return Error{"video '" + path + "': ffmpeg is not installed (Debian: apt-get install ffmpeg)"};
  const std::filesystem::path parent = std::filesystem::path(path).parent_path();
  if (!parent.empty() && !std::filesystem::is_directory(parent))
    return Error{"video '" + path + "': folder '" + parent.string() + "' does not exist"};
  // yuv420p (what players expect) needs even sizes: an odd one is padded by a pixel.
  const std::string command = "ffmpeg -y -loglevel error -f rawvideo -pix_fmt rgb24 -s " + std::to_string(width) +
                              "x" + std::to_string(height) + " -r " + std::to_string(fps) +
                              " -i - -vf 'pad=ceil(iw/2)*2:ceil(ih/2)*2' -c:v libx264 -pix_fmt yuv420p -crf 20 " +
                              shellQuoted(path);
  std::unique_ptr<VideoWriter> writer(new VideoWriter());
  writer->m_pipe = popen(command.c_str(), "w");
  if (!writer->m_pipe) return Error{"video '" + path + "': cannot start ffmpeg"};
  writer->m_path = path;
  writer->m_frameBytes = static_cast<size_t>(width) * height * 3;
  return writer;
}

Status VideoWriter::write(const std::vector<uint8_t>& rgb) {
  if (!m_pipe) return Error{"video '" + m_path + "': already closed"};
  if (rgb.size() != m_frameBytes) return Error{"video '" + m_path + "': wrong frame size"};
  if (std::fwrite(rgb.data(), 1, rgb.size(), m_pipe) != rgb.size())
    return Error{"video '" + m_path + "': ffmpeg stopped taking frames"};
  return {};
}

Status VideoWriter::close() {
  if (!m_pipe) return {};
  const int status = pclose(m_pipe);
  m_pipe = nullptr;
  if (status != 0) return Error{"video '" + m_path + "': ffmpeg failed (exit status " + std::to_string(status) + ")"};
  return {};
}

VideoWriter::~VideoWriter() { (void)close(); }

}  // namespace tandem::render
