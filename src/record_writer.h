// The formats a StepRecorder writes (include/tandem/record.h): each is a Writer.
#pragma once

#include <tandem/record.h>

#include <cstdio>
#include <memory>
#include <string>

namespace tandem {

class StepRecorder::Writer {
 public:
  virtual ~Writer() = default;
  virtual Status write(const World& world) = 0;
  virtual Status close() = 0;
};

// Flushes and closes a record's file; a failure of either (a full disk) is an error naming it.
Status closeRecordFile(std::FILE* file, const std::string& path);

// src/record_csv.cpp
Result<std::unique_ptr<StepRecorder::Writer>> openCsvRecord(const std::string& path, bool nodes);
// src/record_npz.cpp
Result<std::unique_ptr<StepRecorder::Writer>> openNpzRecord(const std::string& path, bool nodes);

}  // namespace tandem
