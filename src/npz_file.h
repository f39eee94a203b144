// Writing NumPy's .npz layout: a zip archive whose entries are .npy arrays, stored (not
// compressed), so that numpy.load reads it with nothing of Tandem's.
//
// An .npy array (NumPy's format 1.0) is the magic "\x93NUMPY", version 1 0, a little-endian
// uint16 header length, then a header that is a Python dict literal,
//   {'descr': '<f8', 'fortran_order': False, 'shape': (S, B, 3), }
// padded with spaces and ended by '\n' so that the data starts at a multiple of 64 bytes, then
// the data in C order. The zip around it (PKWARE APPNOTE 6.3): per entry a local header, the
// data; then a central directory and its end record. Entries or offsets past 4 GiB get ZIP64
// extra fields and a ZIP64 end record; smaller files are plain zip that any reader takes.
//
// Entries are written one after another, each whole: a caller that gathers arrays over time
// keeps them in its own (temporary) files and adds them at the end.
#pragma once

#include <tandem/types.h>

#include <cstdint>
#include <cstdio>
#include <string>
#include <vector>

namespace tandem {

// The CRC-32 of zip (polynomial 0xEDB88320), continued from `crc` over `bytes`.
uint32_t crc32Update(uint32_t crc, const void* data, size_t bytes);

class NpzWriter {
 public:
  // Writes to `file` (not owned; left open) from its start. `forceZip64` writes ZIP64 fields for
  // every entry, as for a file past 4 GiB (for tests).
  NpzWriter(std::FILE* file, std::string path, bool forceZip64 = false)
      : m_file(file), m_path(std::move(path)), m_forceZip64(forceZip64) {}

  // An array `name` (".npy" is appended) of NumPy type `descr` ("<f8", "<i8", "<U12") and
  // `shape`, its data in C order from memory, or the first `bytes` bytes of `source` (rewound).
  Status addArray(const std::string& name, const std::string& descr, const std::vector<int64_t>& shape, const void* data,
                  uint64_t bytes);
  Status addArray(const std::string& name, const std::string& descr, const std::vector<int64_t>& shape, std::FILE* source,
                  uint64_t bytes);
  // Writes the central directory. The file is complete when this returns ok.
  Status finish();

  static std::string npyHeader(const std::string& descr, const std::vector<int64_t>& shape);

 private:
  struct Entry {
    std::string name;
    uint32_t crc = 0;
    uint64_t size = 0;
    uint64_t offset = 0;
  };
  Status addEntry(const std::string& name, const std::string& header, uint32_t dataCrc, uint64_t dataBytes,
                  const void* data, std::FILE* source);
  bool needsZip64(uint64_t size, uint64_t offset) const;
  void put(const void* data, size_t bytes);
  void put16(uint16_t value);
  void put32(uint32_t value);
  void put64(uint64_t value);
  Status failed(const std::string& what) const;

  std::FILE* m_file;
  std::string m_path;
  bool m_forceZip64 = false;
  uint64_t m_offset = 0;
  std::vector<Entry> m_entries;
};

// A NumPy unicode array's items: each string as UTF-32LE code points, padded with zeros to the
// longest; returns the bytes and sets `descr` ("<U{longest}").
std::vector<char32_t> npyUnicode(const std::vector<std::string>& strings, std::string& descr);

}  // namespace tandem
