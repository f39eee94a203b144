// A folder of its own under the system's temporary folder for this test process: ctest runs a
// test file's tests as separate processes side by side, so files they write must not share a path.
#pragma once

#include <unistd.h>

#include <filesystem>
#include <string>

namespace tandem {

inline std::filesystem::path processTempFolder(const std::string& name) {
  const std::filesystem::path dir = std::filesystem::temp_directory_path() / (name + "_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  return dir;
}

}  // namespace tandem
