#include <tandem/record.h>

#include "record_writer.h"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cstring>

namespace tandem {

Status closeRecordFile(std::FILE* file, const std::string& path) {
  const bool written = std::fflush(file) == 0 && !std::ferror(file);
  const int error = errno;
  if (std::fclose(file) != 0 || !written)
    return Error{"record: writing '" + path + "' failed: " + std::strerror(written ? errno : error)};
  return {};
}

RecordFormat recordFormatOf(const std::string& path) {
  std::string extension = path.size() >= 4 ? path.substr(path.size() - 4) : std::string();
  std::transform(extension.begin(), extension.end(), extension.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return extension == ".npz" ? RecordFormat::Npz : RecordFormat::Csv;
}

Result<StepRecorder> StepRecorder::open(const std::string& path, bool nodes) {
  return open(path, nodes, recordFormatOf(path));
}

Result<StepRecorder> StepRecorder::open(const std::string& path, bool nodes, RecordFormat format) {
  Result<std::unique_ptr<Writer>> writer = format == RecordFormat::Npz ? openNpzRecord(path, nodes) : openCsvRecord(path, nodes);
  if (!writer) return Error{writer.message()};
  return StepRecorder(std::move(writer).value());
}

StepRecorder::StepRecorder(std::unique_ptr<Writer> writer) : m_writer(std::move(writer)) {}
StepRecorder::StepRecorder(StepRecorder&&) noexcept = default;
StepRecorder& StepRecorder::operator=(StepRecorder&&) noexcept = default;
StepRecorder::~StepRecorder() = default;

Status StepRecorder::write(const World& world) {
  if (!m_writer) return Error{"record: writing to a recorder that was moved from"};
  return m_writer->write(world);
}

Status StepRecorder::close() {
  if (!m_writer) return Error{"record: closing a recorder that was moved from"};
  return m_writer->close();
}

}  // namespace tandem
