// The .npz writer (src/npz_file.h): archives written here, plain and with ZIP64 fields, are read
// back by NumPy itself (numpy.load, and zipfile's CRC check), which prints what it read.
#include "npz_file.h"

#include <gtest/gtest.h>

#include "process_temp_folder.h"

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace tandem {
namespace {

namespace fs = std::filesystem;

fs::path tempDir() { return processTempFolder("tandem_npz_tests"); }

std::string runPython(const std::string& name, const std::string& script, int& status) {
  const fs::path file = tempDir() / (name + ".py");  // one per test: ctest runs them at once
  std::ofstream(file) << script;
  FILE* pipe = popen((std::string(TANDEM_PYTHON3) + " " + file.string() + " 2>&1").c_str(), "r");
  std::string output;
  if (!pipe) {
    status = -1;
    return output;
  }
  char buffer[512];
  while (size_t n = fread(buffer, 1, sizeof buffer, pipe)) output.append(buffer, n);
  status = pclose(pipe);
  return output;
}

TEST(NpzFile, CrcIsZipsCrc32) {
  const std::string check = "123456789";  // the standard check value of CRC-32
  EXPECT_EQ(crc32Update(0, check.data(), check.size()), 0xCBF43926u);
  // Continued over two pieces, the same as over the whole.
  EXPECT_EQ(crc32Update(crc32Update(0, check.data(), 4), check.data() + 4, 5), 0xCBF43926u);
}

TEST(NpzFile, NpyHeaderIsNumpysVersionOneAlignedTo64) {
  const std::string header = NpzWriter::npyHeader("<f8", {7, 2, 3});
  EXPECT_EQ(header.size() % 64, 0u);
  EXPECT_EQ(header.substr(0, 8), std::string("\x93NUMPY\x01\x00", 8));
  EXPECT_EQ(static_cast<size_t>(static_cast<unsigned char>(header[8]) | static_cast<unsigned char>(header[9]) << 8),
            header.size() - 10);
  EXPECT_NE(header.find("{'descr': '<f8', 'fortran_order': False, 'shape': (7, 2, 3), }"), std::string::npos);
  EXPECT_EQ(header.back(), '\n');
  EXPECT_NE(NpzWriter::npyHeader("<i8", {5}).find("'shape': (5,)"), std::string::npos);
}

TEST(NpzFile, UnicodeNamesAreUtf32PaddedToTheLongest) {
  std::string descr;
  const std::vector<char32_t> items = npyUnicode({"ab", "\xc3\xa9t\xc3\xa9", ""}, descr);  // "ab", "été", ""
  EXPECT_EQ(descr, "<U3");
  EXPECT_EQ(items, (std::vector<char32_t>{U'a', U'b', 0, U'\u00e9', U't', U'\u00e9', 0, 0, 0}));
  npyUnicode({"bad \xff byte"}, descr);
  EXPECT_EQ(descr, "<U10");  // the stray byte is one replacement character
}

// Writes four arrays (one from a file, as the record does) and has NumPy print them back.
void writeAndReadBack(bool zip64) {
  const fs::path path = tempDir() / (zip64 ? "zip64.npz" : "plain.npz");
  std::FILE* file = std::fopen(path.c_str(), "wb");
  ASSERT_NE(file, nullptr);
  NpzWriter npz(file, path.string(), zip64);
  const std::vector<double> values{0.1, -2.5, 1e-300, 3.0e300, 0.0, 7.25};
  const std::vector<int64_t> counts{-1, 0, 1LL << 40};
  ASSERT_TRUE(npz.addArray("values", "<f8", {2, 3}, values.data(), values.size() * sizeof(double)).ok());
  ASSERT_TRUE(npz.addArray("counts", "<i8", {3}, counts.data(), counts.size() * sizeof(int64_t)).ok());
  std::string descr;
  const std::vector<char32_t> names = npyUnicode({"box", "flange front", "\xc3\xa9t\xc3\xa9"}, descr);
  ASSERT_TRUE(npz.addArray("names", descr, {3}, names.data(), names.size() * sizeof(char32_t)).ok());
  std::FILE* rows = std::tmpfile();
  ASSERT_NE(rows, nullptr);
  for (int i = 0; i < 1000; ++i) {
    const double row[3] = {static_cast<double>(i), 0.5 * i, -static_cast<double>(i)};
    std::fwrite(row, sizeof row, 1, rows);
  }
  ASSERT_TRUE(npz.addArray("rows", "<f8", {1000, 3}, rows, 1000 * 3 * sizeof(double)).ok());
  std::fclose(rows);
  ASSERT_TRUE(npz.addArray("empty", "<f8", {0, 4, 3}, static_cast<const void*>(nullptr), 0).ok());
  ASSERT_TRUE(npz.finish().ok());
  ASSERT_EQ(std::fclose(file), 0);

  int status = 0;
  const std::string output = runPython(
      zip64 ? "read_zip64" : "read_plain",
      "import zipfile, numpy as np\n"
      "path = '" + path.string() + "'\n"
      "with zipfile.ZipFile(path) as z:\n"
      "    assert z.testzip() is None, 'bad CRC'\n"
      "    print('compressed', [i.compress_type for i in z.infolist()])\n"
      "    print('zip64', [len(i.extra) > 0 for i in z.infolist()])\n"
      "d = np.load(path)\n"
      "print('files', sorted(d.files))\n"
      "print('values', d['values'].shape, d['values'].dtype, repr(d['values'].tolist()))\n"
      "print('counts', d['counts'].dtype, d['counts'].tolist())\n"
      "print('names', d['names'].dtype, list(d['names']) == ['box', 'flange front', '\\u00e9t\\u00e9'])\n"
      "r = d['rows']\n"
      "print('rows', r.shape, r[999].tolist(), float(r[:, 1].sum()))\n"
      "print('empty', d['empty'].shape)\n",
      status);
  ASSERT_EQ(status, 0) << output;
  EXPECT_NE(output.find("compressed [0, 0, 0, 0, 0]"), std::string::npos) << output;
  EXPECT_NE(output.find(zip64 ? "zip64 [True, True, True, True, True]" : "zip64 [False, False, False, False, False]"),
            std::string::npos)
      << output;
  EXPECT_NE(output.find("files ['counts', 'empty', 'names', 'rows', 'values']"), std::string::npos) << output;
  EXPECT_NE(output.find("values (2, 3) float64 [[0.1, -2.5, 1e-300], [3e+300, 0.0, 7.25]]"), std::string::npos) << output;
  EXPECT_NE(output.find("counts int64 [-1, 0, 1099511627776]"), std::string::npos) << output;
  EXPECT_NE(output.find("names <U12 True"), std::string::npos) << output;
  EXPECT_NE(output.find("rows (1000, 3) [999.0, 499.5, -999.0] 249750.0"), std::string::npos) << output;
  EXPECT_NE(output.find("empty (0, 4, 3)"), std::string::npos) << output;
}

TEST(NpzFile, NumpyReadsAPlainArchive) { writeAndReadBack(false); }
TEST(NpzFile, NumpyReadsAnArchiveWithZip64Fields) { writeAndReadBack(true); }

TEST(NpzFile, AFullDiskIsAnError) {
  std::FILE* file = std::fopen("/dev/full", "wb");
  ASSERT_NE(file, nullptr);
  std::setvbuf(file, nullptr, _IONBF, 0);  // unbuffered: the write itself fails
  NpzWriter npz(file, "/dev/full");
  const std::vector<double> values(1000, 1.0);
  const Status added = npz.addArray("values", "<f8", {1000}, values.data(), values.size() * sizeof(double));
  std::fclose(file);
  EXPECT_FALSE(added.ok());
  EXPECT_NE(added.message().find("'/dev/full' failed"), std::string::npos) << added.message();
}

}  // namespace
}  // namespace tandem
