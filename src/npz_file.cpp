#include "npz_file.h"

#include <array>
#include <bit>
#include <cerrno>
#include <cstring>

namespace tandem {
namespace {

static_assert(std::endian::native == std::endian::little, "the .npy and zip fields are written as they lie in memory");

constexpr std::array<uint32_t, 256> makeCrcTable() {
  std::array<uint32_t, 256> table{};
  for (uint32_t i = 0; i < 256; ++i) {
    uint32_t c = i;
    for (int bit = 0; bit < 8; ++bit) c = (c & 1u) ? 0xEDB88320u ^ (c >> 1) : c >> 1;
    table[i] = c;
  }
  return table;
}
constexpr std::array<uint32_t, 256> kCrcTable = makeCrcTable();

constexpr uint32_t kLocalHeaderSignature = 0x04034b50;
constexpr uint32_t kCentralHeaderSignature = 0x02014b50;
constexpr uint32_t kEndSignature = 0x06054b50;
constexpr uint32_t kZip64EndSignature = 0x06064b50;
constexpr uint32_t kZip64LocatorSignature = 0x07064b50;
constexpr uint16_t kZip64ExtraTag = 0x0001;
constexpr uint16_t kVersionStored = 20;  // 2.0: stored entries
constexpr uint16_t kVersionZip64 = 45;   // 4.5: ZIP64
constexpr uint16_t kDosDate1980 = (0 << 9) | (1 << 5) | 1;  // 1980-01-01: the same bytes for the same run
constexpr uint32_t kMax32 = 0xFFFFFFFFu;
constexpr size_t kCopyChunk = 1 << 20;

}  // namespace

uint32_t crc32Update(uint32_t crc, const void* data, size_t bytes) {
  const auto* p = static_cast<const unsigned char*>(data);
  uint32_t c = ~crc;
  for (size_t i = 0; i < bytes; ++i) c = kCrcTable[(c ^ p[i]) & 0xFFu] ^ (c >> 8);
  return ~c;
}

std::string NpzWriter::npyHeader(const std::string& descr, const std::vector<int64_t>& shape) {
  std::string dims;
  for (int64_t n : shape) dims += std::to_string(n) + ", ";
  if (shape.size() > 1) dims.resize(dims.size() - 2);  // (S, B, 3); one dimension keeps its comma: (S,)
  else if (shape.size() == 1) dims.pop_back();
  std::string dict = "{'descr': '" + descr + "', 'fortran_order': False, 'shape': (" + dims + "), }";
  constexpr size_t kPrefix = 10;  // magic (6), version (2), header length (2)
  const size_t total = (kPrefix + dict.size() + 1 + 63) / 64 * 64;
  dict.append(total - kPrefix - dict.size() - 1, ' ');
  dict += '\n';
  const auto length = static_cast<uint16_t>(dict.size());
  std::string header = "\x93NUMPY";
  header += '\x01';
  header += '\x00';
  header += static_cast<char>(length & 0xFF);
  header += static_cast<char>(length >> 8);
  return header + dict;
}

Status NpzWriter::addArray(const std::string& name, const std::string& descr, const std::vector<int64_t>& shape,
                           const void* data, uint64_t bytes) {
  const std::string header = npyHeader(descr, shape);
  const uint32_t crc = crc32Update(crc32Update(0, header.data(), header.size()), data, bytes);
  return addEntry(name, header, crc, bytes, data, nullptr);
}

Status NpzWriter::addArray(const std::string& name, const std::string& descr, const std::vector<int64_t>& shape,
                           std::FILE* source, uint64_t bytes) {
  const std::string header = npyHeader(descr, shape);
  uint32_t crc = crc32Update(0, header.data(), header.size());
  std::vector<char> chunk(kCopyChunk);
  std::rewind(source);
  for (uint64_t left = bytes; left > 0;) {
    const size_t n = std::fread(chunk.data(), 1, static_cast<size_t>(std::min<uint64_t>(left, kCopyChunk)), source);
    if (n == 0) return Error{"record: reading back the temporary data of '" + name + "' for '" + m_path + "' failed"};
    crc = crc32Update(crc, chunk.data(), n);
    left -= n;
  }
  return addEntry(name, header, crc, bytes, nullptr, source);
}

bool NpzWriter::needsZip64(uint64_t size, uint64_t offset) const {
  return m_forceZip64 || size >= kMax32 || offset >= kMax32;
}

Status NpzWriter::addEntry(const std::string& arrayName, const std::string& header, uint32_t crc, uint64_t dataBytes,
                           const void* data, std::FILE* source) {
  Entry entry{arrayName + ".npy", crc, header.size() + dataBytes, m_offset};
  const bool zip64 = needsZip64(entry.size, 0);  // the local header's extra holds sizes only
  put32(kLocalHeaderSignature);
  put16(zip64 ? kVersionZip64 : kVersionStored);
  put16(0);  // flags
  put16(0);  // stored
  put16(0);  // time
  put16(kDosDate1980);
  put32(entry.crc);
  put32(zip64 ? kMax32 : static_cast<uint32_t>(entry.size));  // compressed size
  put32(zip64 ? kMax32 : static_cast<uint32_t>(entry.size));  // uncompressed size
  put16(static_cast<uint16_t>(entry.name.size()));
  put16(zip64 ? 20 : 0);  // extra field length
  put(entry.name.data(), entry.name.size());
  if (zip64) {
    put16(kZip64ExtraTag);
    put16(16);
    put64(entry.size);  // uncompressed
    put64(entry.size);  // compressed
  }
  put(header.data(), header.size());
  if (!source) {
    if (dataBytes > 0) put(data, static_cast<size_t>(dataBytes));
  } else {
    std::vector<char> chunk(kCopyChunk);
    std::rewind(source);
    for (uint64_t left = dataBytes; left > 0;) {
      const size_t n = std::fread(chunk.data(), 1, static_cast<size_t>(std::min<uint64_t>(left, kCopyChunk)), source);
      if (n == 0) return Error{"record: reading back the temporary data of '" + arrayName + "' for '" + m_path + "' failed"};
      put(chunk.data(), n);
      left -= n;
    }
  }
  m_entries.push_back(std::move(entry));
  if (std::ferror(m_file)) return failed("writing");
  return {};
}

Status NpzWriter::finish() {
  const uint64_t directoryStart = m_offset;
  bool anyZip64 = m_forceZip64;
  for (const Entry& entry : m_entries) {
    const bool zip64 = needsZip64(entry.size, entry.offset);
    anyZip64 |= zip64;
    put32(kCentralHeaderSignature);
    put16(kVersionZip64);  // made by
    put16(zip64 ? kVersionZip64 : kVersionStored);
    put16(0);
    put16(0);
    put16(0);
    put16(kDosDate1980);
    put32(entry.crc);
    put32(zip64 ? kMax32 : static_cast<uint32_t>(entry.size));
    put32(zip64 ? kMax32 : static_cast<uint32_t>(entry.size));
    put16(static_cast<uint16_t>(entry.name.size()));
    put16(zip64 ? 28 : 0);  // extra field length
    put16(0);               // comment length
    put16(0);               // disk number
    put16(0);               // internal attributes
    put32(0);               // external attributes
    put32(zip64 ? kMax32 : static_cast<uint32_t>(entry.offset));
    put(entry.name.data(), entry.name.size());
    if (zip64) {  // every 32-bit field set to 0xFFFFFFFF above, in the order of the standard
      put16(kZip64ExtraTag);
      put16(24);
      put64(entry.size);
      put64(entry.size);
      put64(entry.offset);
    }
  }
  const uint64_t directorySize = m_offset - directoryStart;
  const uint64_t count = m_entries.size();
  anyZip64 |= directoryStart >= kMax32 || directorySize >= kMax32 || count >= 0xFFFF;
  if (anyZip64) {
    const uint64_t zip64End = m_offset;
    put32(kZip64EndSignature);
    put64(44);  // size of the rest of this record
    put16(kVersionZip64);
    put16(kVersionZip64);
    put32(0);  // this disk
    put32(0);  // the directory's disk
    put64(count);
    put64(count);
    put64(directorySize);
    put64(directoryStart);
    put32(kZip64LocatorSignature);
    put32(0);
    put64(zip64End);
    put32(1);  // disks
  }
  put32(kEndSignature);
  put16(0);
  put16(0);
  put16(anyZip64 ? 0xFFFF : static_cast<uint16_t>(count));
  put16(anyZip64 ? 0xFFFF : static_cast<uint16_t>(count));
  put32(anyZip64 ? kMax32 : static_cast<uint32_t>(directorySize));
  put32(anyZip64 ? kMax32 : static_cast<uint32_t>(directoryStart));
  put16(0);  // comment length
  if (std::ferror(m_file)) return failed("writing");
  return {};
}

void NpzWriter::put(const void* data, size_t bytes) {
  std::fwrite(data, 1, bytes, m_file);
  m_offset += bytes;
}
void NpzWriter::put16(uint16_t value) { put(&value, sizeof value); }
void NpzWriter::put32(uint32_t value) { put(&value, sizeof value); }
void NpzWriter::put64(uint64_t value) { put(&value, sizeof value); }

Status NpzWriter::failed(const std::string& what) const {
  return Error{"record: " + what + " '" + m_path + "' failed: " + std::strerror(errno)};
}

std::vector<char32_t> npyUnicode(const std::vector<std::string>& strings, std::string& descr) {
  std::vector<std::u32string> decoded;
  size_t longest = 1;
  for (const std::string& text : strings) {
    std::u32string points;
    for (size_t i = 0; i < text.size();) {
      const auto lead = static_cast<unsigned char>(text[i]);
      const int length = lead < 0x80 ? 1 : (lead >> 5) == 0x6 ? 2 : (lead >> 4) == 0xE ? 3 : (lead >> 3) == 0x1E ? 4 : 0;
      char32_t point = length == 1 ? lead : length == 2 ? lead & 0x1Fu : length == 3 ? lead & 0x0Fu : lead & 0x07u;
      bool valid = length > 0 && i + static_cast<size_t>(length) <= text.size();
      for (int k = 1; valid && k < length; ++k) {
        const auto next = static_cast<unsigned char>(text[i + static_cast<size_t>(k)]);
        valid = (next & 0xC0) == 0x80;
        point = (point << 6) | (next & 0x3Fu);
      }
      points += valid ? point : U'\uFFFD';  // a byte that is no UTF-8 becomes the replacement character
      i += valid ? static_cast<size_t>(length) : 1;
    }
    longest = std::max(longest, points.size());
    decoded.push_back(std::move(points));
  }
  descr = "<U" + std::to_string(longest);
  std::vector<char32_t> items(decoded.size() * longest, U'\0');
  for (size_t s = 0; s < decoded.size(); ++s) std::copy(decoded[s].begin(), decoded[s].end(), items.begin() + static_cast<std::ptrdiff_t>(s * longest));
  return items;
}

}  // namespace tandem
