#include "input_file.h"

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace tandem {
namespace {
std::string withArticle(const char* noun) {
  return (std::strchr("AEIOUaeiou", noun[0]) ? "an " : "a ") + std::string(noun);
}
}  // namespace

Result<std::string> readInputFile(const std::string& path, int64_t maxBytes, const char* what, const char* limitName) {
  namespace fs = std::filesystem;
  std::error_code error;
  const fs::file_status status = fs::status(path, error);
  if (error || !fs::exists(status)) return Error{path + ": cannot open the " + what};
  if (fs::is_directory(status)) return Error{path + ": is a folder, not " + withArticle(what)};
  if (!fs::is_regular_file(status))
    return Error{path + ": is not a regular file (a device, pipe or socket); " + what + "s must be regular files"};
  const uintmax_t size = fs::file_size(path, error);
  if (error) return Error{path + ": cannot read the " + what + ": " + error.message()};
  if (size > static_cast<uintmax_t>(maxBytes))
    return Error{path + ": the " + std::string(what) + " has " + std::to_string(size) + " bytes, more than the limit of " +
                 std::to_string(maxBytes) + " (" + limitName + "; the API can raise it)"};
  std::ifstream in(path, std::ios::binary);
  if (!in) return Error{path + ": cannot open the " + what + ": " + std::strerror(errno)};
  std::string text(static_cast<size_t>(size), '\0');
  in.read(text.data(), static_cast<std::streamsize>(size));
  if (in.bad() || in.gcount() != static_cast<std::streamsize>(size))
    return Error{path + ": cannot read the " + what + " (it changed while being read?)"};
  return text;
}

}  // namespace tandem
