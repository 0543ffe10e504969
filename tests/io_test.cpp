// Readers and writers: bit-exact round trips, every format's variants, every bad-input case.
#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cctype>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>

#include <zlib.h>

#include "dtlab/generators/generators.hpp"
#include "dtlab/io/mesh_writers.hpp"
#include "dtlab/io/point_readers.hpp"

namespace dtlab::test {
namespace {

using io::InputError;
using predicates::Point3;
namespace fs = std::filesystem;

class IoTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("dtlab_io_test_" + std::to_string(::getpid()));
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::string path(const std::string& name) const { return (dir_ / name).string(); }
  std::string write(const std::string& name, const std::string& contents) const {
    std::ofstream out(path(name), std::ios::binary);
    out << contents;
    return path(name);
  }
  fs::path dir_;
};

std::vector<Point3> awkward_points() {
  std::vector<Point3> p = generators::generate("uniform", 200, 7).points;
  p.push_back({0.1, -0.0, 1e-300});
  p.push_back({1e300, -1e-310, 0.30000000000000004});
  p.push_back({5e-324, std::nextafter(1.0, 2.0), -123456789.125});
  p.push_back(p[3]);  // a duplicate
  return p;
}

void expect_bitwise_equal(const std::vector<Point3>& a, const std::vector<Point3>& b) {
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t i = 0; i < a.size(); ++i) {
    EXPECT_EQ(std::bit_cast<std::uint64_t>(a[i].x), std::bit_cast<std::uint64_t>(b[i].x)) << i;
    EXPECT_EQ(std::bit_cast<std::uint64_t>(a[i].y), std::bit_cast<std::uint64_t>(b[i].y)) << i;
    EXPECT_EQ(std::bit_cast<std::uint64_t>(a[i].z), std::bit_cast<std::uint64_t>(b[i].z)) << i;
  }
}

TEST_F(IoTest, XyzRoundTripIsBitExact) {
  const auto p = awkward_points();
  io::write_xyz(path("a.xyz"), p);
  expect_bitwise_equal(p, io::read_points(path("a.xyz")));
}

TEST_F(IoTest, NodeRoundTripIsBitExact) {
  const auto p = awkward_points();
  io::write_node(path("a.node"), p);
  expect_bitwise_equal(p, io::read_points(path("a.node")));
  EXPECT_EQ(io::node_index_base(path("a.node")), 0);
}

TEST_F(IoTest, EleRoundTrip) {
  const std::vector<io::Tetrahedron> tets{{0, 1, 2, 3}, {4, 3, 2, 1}};
  io::write_ele(path("a.ele"), tets);
  EXPECT_EQ(io::read_ele(path("a.ele"), 5, 0), tets);
  EXPECT_THROW(io::read_ele(path("a.ele"), 4, 0), InputError);  // id 4 out of range
}

TEST_F(IoTest, VtuHasPointsCellsAndCellData) {
  const std::vector<Point3> p{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  io::write_vtu(path("a.vtu"), p, {{0, 1, 2, 3}}, {{"non_delaunay", {1}}});
  const std::string text = io::read_file_bytes(path("a.vtu"));
  EXPECT_NE(text.find("NumberOfPoints=\"4\" NumberOfCells=\"1\""), std::string::npos);
  EXPECT_NE(text.find("Name=\"non_delaunay\""), std::string::npos);
  EXPECT_NE(text.find("</VTKFile>"), std::string::npos);
}

// Base64 decoded by the alphabet's definition (RFC 4648), independently of the writer's encoder.
std::string from_base64(const std::string& text) {
  const std::string alphabet = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  unsigned bits = 0;
  int count = 0;
  for (const char c : text) {
    if (c == '=') break;
    const auto v = alphabet.find(c);
    if (v == std::string::npos) continue;
    bits = (bits << 6U) | static_cast<unsigned>(v);
    count += 6;
    if (count >= 8) {
      count -= 8;
      out.push_back(static_cast<char>((bits >> static_cast<unsigned>(count)) & 0xFFU));
    }
  }
  return out;
}

// The bytes of the .vtu DataArray whose tag contains `marker`, decoded from the
// binary layout: one base64 run with a UInt64 byte count (binary), or a base64 header run
// [blocks, block size, last size, compressed sizes...] and a run of zlib blocks (zlib).
std::string vtu_array_bytes(const std::string& text, const std::string& marker, bool zlib) {
  const auto open = text.find('>', text.find(marker)) + 1;
  const auto close = text.find("</DataArray>", open);
  std::string body = text.substr(open, close - open);
  body.erase(std::remove_if(body.begin(), body.end(), [](char c) { return std::isspace(c); }),
             body.end());
  if (!zlib) {
    const std::string raw = from_base64(body);
    std::uint64_t size = 0;
    std::memcpy(&size, raw.data(), 8);
    EXPECT_EQ(size, raw.size() - 8);
    return raw.substr(8);
  }
  std::uint64_t words[3];
  std::memcpy(words, from_base64(body.substr(0, 32)).data(), 24);  // 24 bytes: 32 characters
  const std::uint64_t blocks = words[0];
  const std::size_t header_chars = 4 * ((8 * (3 + blocks) + 2) / 3);
  const std::string header = from_base64(body.substr(0, header_chars));
  const std::string data = from_base64(body.substr(header_chars));
  std::string out;
  std::size_t at = 0;
  for (std::uint64_t b = 0; b < blocks; ++b) {
    std::uint64_t compressed = 0;
    std::memcpy(&compressed, header.data() + 8 * (3 + b), 8);
    const std::uint64_t expected = b + 1 == blocks ? words[2] : words[1];
    std::string block(expected, '\0');
    uLongf size = expected;
    EXPECT_EQ(uncompress(reinterpret_cast<Bytef*>(block.data()), &size,
                         reinterpret_cast<const Bytef*>(data.data() + at), compressed),
              Z_OK);
    EXPECT_EQ(size, expected);
    out += block;
    at += compressed;
  }
  EXPECT_EQ(at, data.size());
  return out;
}

TEST_F(IoTest, VtuBinaryAndZlibArraysDecodeToTheMesh) {
  // Enough tetrahedra for several 32 KiB zlib blocks in the connectivity.
  const auto points = generators::generate("uniform", 3000, 1).points;
  std::vector<io::Tetrahedron> tets;
  std::vector<std::int32_t> flags;
  for (std::uint32_t i = 0; i + 3 < 3000 * 4; ++i) {
    tets.push_back({i % 3000, (i * 7 + 1) % 3000, (i * 13 + 2) % 3000, (i * 31 + 3) % 3000});
    flags.push_back(static_cast<std::int32_t>(i % 3));
  }
  for (const bool zlib : {false, true}) {
    io::write_vtu(path("a.vtu"), points, tets, {{"non_delaunay", flags}},
                  zlib ? io::VtuEncoding::Zlib : io::VtuEncoding::Binary);
    const std::string text = io::read_file_bytes(path("a.vtu"));
    EXPECT_EQ(text.find("vtkZLibDataCompressor") != std::string::npos, zlib);
    const std::string xyz = vtu_array_bytes(text, "NumberOfComponents=\"3\"", zlib);
    ASSERT_EQ(xyz.size(), points.size() * 24);
    EXPECT_EQ(std::memcmp(xyz.data(), points.data(), xyz.size()), 0);
    const std::string ids = vtu_array_bytes(text, "Name=\"connectivity\"", zlib);
    ASSERT_EQ(ids.size(), tets.size() * 16);  // Int32
    for (std::size_t t = 0; t < tets.size(); ++t) {
      for (std::size_t j = 0; j < 4; ++j) {
        std::int32_t v = 0;
        std::memcpy(&v, ids.data() + 4 * (4 * t + j), 4);
        ASSERT_EQ(static_cast<std::uint32_t>(v), tets[t][j]);
      }
    }
    const std::string offsets = vtu_array_bytes(text, "Name=\"offsets\"", zlib);
    std::int32_t last = 0;
    std::memcpy(&last, offsets.data() + offsets.size() - 4, 4);
    EXPECT_EQ(last, static_cast<std::int32_t>(4 * tets.size()));
    const std::string cell = vtu_array_bytes(text, "Name=\"non_delaunay\"", zlib);
    ASSERT_EQ(cell.size(), flags.size() * 4);
    EXPECT_EQ(std::memcmp(cell.data(), flags.data(), cell.size()), 0);
  }
}

std::string ply_header(const std::string& format, std::size_t n, const std::string& type) {
  return "ply\nformat " + format +
         " 1.0\ncomment test\nelement face 1\nproperty list uchar int vertex_indices\n"
         "element vertex " +
         std::to_string(n) + "\nproperty " + type + " x\nproperty " + type +
         " y\nproperty uchar red\nproperty " + type + " z\nend_header\n";
}

template <class T>
std::string binary_body(const std::vector<Point3>& p, bool big_endian) {
  std::string out;
  auto put = [&](const void* data, std::size_t size) {
    std::string bytes(static_cast<const char*>(data), size);
    if (big_endian != (std::endian::native == std::endian::big))
      std::reverse(bytes.begin(), bytes.end());
    out += bytes;
  };
  const unsigned char count = 3;
  const std::int32_t index = 0;
  out.push_back(static_cast<char>(count));
  for (int i = 0; i < 3; ++i) put(&index, 4);
  for (const Point3& q : p) {
    const T x = static_cast<T>(q.x), y = static_cast<T>(q.y), z = static_cast<T>(q.z);
    put(&x, sizeof(T));
    put(&y, sizeof(T));
    out.push_back('\x07');
    put(&z, sizeof(T));
  }
  return out;
}

TEST_F(IoTest, PlyBinaryLittleAndBigEndianDoubleAndFloat) {
  const auto p = generators::generate("uniform", 50, 3).points;
  for (const bool big : {false, true}) {
    const std::string fmt = big ? "binary_big_endian" : "binary_little_endian";
    write("d.ply", ply_header(fmt, p.size(), "double") + binary_body<double>(p, big));
    expect_bitwise_equal(p, io::read_points(path("d.ply")));
    write("f.ply", ply_header(fmt, p.size(), "float") + binary_body<float>(p, big));
    const auto f = io::read_points(path("f.ply"));
    ASSERT_EQ(f.size(), p.size());
    EXPECT_EQ(f[5].x, static_cast<double>(static_cast<float>(p[5].x)));
  }
}

TEST_F(IoTest, PlyAscii) {
  write("a.ply", ply_header("ascii", 2, "float") + "3 0 1 2\n1.5 2.5 9 3.5\n-1 -2 0 -3\n");
  const auto p = io::read_points(path("a.ply"));
  ASSERT_EQ(p.size(), 2u);
  EXPECT_EQ(p[0].x, 1.5);
  EXPECT_EQ(p[0].z, 3.5);
  EXPECT_EQ(p[1].y, -2);
}

// A list length that is no whole number (NaN, fractional, beyond 2^31: an ASCII file's text is
// read as a number whatever the declared type) is refused with a message; converting it to an
// integer was undefined (found by UBSan under clang in the parsers' corpus).
TEST_F(IoTest, PlyListLengthMustBeAWholeNumber) {
  for (const std::string count : {"nan", "2.5", "1e30"}) {
    write("l.ply",
          "ply\nformat ascii 1.0\nelement face 1\nproperty list uchar int vertex_indices\n"
          "element vertex 1\nproperty float x\nproperty float y\nproperty float z\n"
          "end_header\n" +
              count + " 0 1 2\n1 2 3\n");
    try {
      (void)io::read_points(path("l.ply"));
      ADD_FAILURE() << count << ": accepted";
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find("is not a whole number up to 2^31"), std::string::npos)
          << count << ": " << e.what();
    }
  }
}

TEST_F(IoTest, OffAndXyzComments) {
  write("a.off", "OFF\n# comment\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n");
  EXPECT_EQ(io::read_points(path("a.off")).size(), 3u);
  write("b.xyz", "# header\n\n1 2 3\n4 5 6 # trailing\n  7 8 9 0.1 0.2 0.3\n");
  const auto p = io::read_points(path("b.xyz"));
  ASSERT_EQ(p.size(), 3u);
  EXPECT_EQ(p[2].z, 9);
}

void expect_error(const std::string& file, const std::string& fragment) {
  try {
    io::read_points(file);
    ADD_FAILURE() << "no error for " << file;
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find(fragment), std::string::npos) << e.what();
  }
}

// The header ends at its end_header line, not at the words in a comment before it (the file was
// refused as having no vertex element until 2026-11-30); a binary body that holds the words is
// read as numbers.
TEST_F(IoTest, PlyHeaderEndsAtItsEndHeaderLineNotAtTheWords) {
  write("c.ply",
        "ply\nformat ascii 1.0\ncomment written before end_header here\nelement vertex 2\n"
        "property float x\nproperty float y\nproperty float z\nend_header\n1 2 3\n4 5 6\n");
  const auto p = io::read_points(path("c.ply"));
  ASSERT_EQ(p.size(), 2U);
  EXPECT_EQ(p[1].x, 4);
  // A binary file whose comment holds the words, and whose header ends "\r\n": the body starts
  // after the end_header line's "\n" (the old search began it inside the comment's line).
  const double x = 0.25;
  std::string body(3 * sizeof(double), '\0');
  std::memcpy(body.data(), &x, sizeof x);
  write("b.ply",
        "ply\r\nformat binary_little_endian 1.0\r\ncomment end_header is not here\r\n"
        "element vertex 1\r\nproperty double x\r\nproperty double y\r\nproperty double z\r\n"
        "end_header\r\n" +
            body);
  const auto b = io::read_points(path("b.ply"));
  ASSERT_EQ(b.size(), 1U);
  EXPECT_EQ(b[0].x, 0.25);
  EXPECT_EQ(b[0].y, 0.0);
}

// Rows end at "\n", "\r\n" or a lone "\r" (old Mac files): read as one line until 2026-11-30,
// such a file's rows after the first were dropped as extra columns, silently.
TEST_F(IoTest, TextRowsEndAtAnyLineEnding) {
  for (const std::string end : {"\n", "\r\n", "\r"}) {
    const std::string name = end == "\r" ? "CR" : end == "\n" ? "LF" : "CRLF";
    const std::string rows = "0 0 0" + end + "1 0 0" + end + "0 1 0" + end + "0 0 1.5" + end;
    const auto p = io::read_points(write("e.xyz", rows));
    ASSERT_EQ(p.size(), 4U) << name;
    EXPECT_EQ(p[3].z, 1.5) << name;
    // A message's line number counts each row once, "\r\n" too; in an ASCII PLY body as well.
    expect_error(write("bad.xyz", "0 0 0" + end + "1 0 0" + end + "x 0 0" + end), "bad.xyz:3:");
    const std::string ply = "ply" + end + "format ascii 1.0" + end + "element vertex 2" + end +
                            "property float x" + end + "property float y" + end +
                            "property float z" + end + "end_header" + end + "1 2 3" + end +
                            "4 x 6" + end;
    expect_error(write("bad.ply", ply), "bad.ply:9:");
  }
}

TEST_F(IoTest, ADirectoryIsNamedAsOne) {
  fs::create_directories(path("folder.xyz"));
  expect_error(path("folder.xyz"), "is a directory");
}

TEST_F(IoTest, BadInputGetsClearErrors) {
  expect_error(path("missing.xyz"), "cannot open");
  expect_error(write("nan.xyz", "1 2 3\n4 nan 6\n"), "nan.xyz:2");
  expect_error(write("inf.xyz", "1 2 inf\n"), "not finite");
  expect_error(write("short.xyz", "1 2 3\n4 5\n"), "short.xyz:2: expected three coordinates");
  expect_error(write("word.xyz", "1 2 x3\n"), "expected a number");
  expect_error(write("big.xyz", "1 2 1e999\n"), "out of the range");
  expect_error(write("t.ply", ply_header("binary_little_endian", 10, "double") + "\x03"),
               "truncated");
  expect_error(write("ta.ply", ply_header("ascii", 3, "double") + "3 0 1 2\n1 2 3 4\n"),
               "truncated");
  expect_error(write("nomagic.ply", "plx\n"), "not a PLY file");
  expect_error(write("noend.ply", "ply\nformat ascii 1.0\n"), "end_header");
  expect_error(write("novert.ply", "ply\nformat ascii 1.0\nelement face 0\nend_header\n"),
               "no vertex element");
  expect_error(write("n.ply", ply_header("ascii", 1, "double") + "3 0 1 2\nnan 1 1 1\n"),
               "non-finite");
  expect_error(write("a.off", "OFF\n5 0 0\n0 0 0\n"), "truncated");
  // An element whose rows hold nothing, with a count no file could hold: skipped, not spun over.
  const std::string empty_rows =
      "ply\nformat ascii 1.0\nelement nothing 392222222222\nelement vertex 1\n"
      "property double x\nproperty double y\nproperty double z\nend_header\n1 2 3\n";
  const auto one = io::read_points(write("empty_rows.ply", empty_rows));
  ASSERT_EQ(one.size(), 1U);
  EXPECT_EQ(one[0].z, 3.0);
  expect_error(write("empty_rows_short.ply", empty_rows.substr(0, empty_rows.size() - 6)),
               "truncated");
  expect_error(write("b.node", "3 3 0 0\n0 0 0 0\n2 1 1 1\n"), "out of sequence");
  expect_error(write("c.node", "2 2 0 0\n"), "dimension must be 3");
  expect_error(write("x.obj", "v 1 2 3\n"), "unknown point format");
  expect_error(write("bad.xyz.xz", "not xz data"), "xz");
}

TEST_F(IoTest, XzCompressedInputIsRead) {
  const auto p = awkward_points();
  io::write_xyz(path("c.xyz"), p);
  const std::string cmd = "xz -k -f '" + path("c.xyz") + "'";
  ASSERT_EQ(std::system(cmd.c_str()), 0);
  expect_bitwise_equal(p, io::read_points(path("c.xyz.xz")));
}

// A write that fails leaves neither the target nor its temporary (PATH.tmp-PID, beside the
// target): one that cannot open its temporary (no such folder), and one that wrote the whole
// temporary and could not rename it into place (the target is a folder with a file in it), whose
// temporary is in the folder scanned.
TEST_F(IoTest, FailedWriteLeavesNoFile) {
  const std::string target = path("no_such_dir/out.ele");
  EXPECT_ANY_THROW(io::write_ele(target, {{0, 1, 2, 3}}));
  EXPECT_FALSE(fs::exists(target));
  fs::create_directory(path("occupied.ele"));
  write("occupied.ele/keep", "x");
  try {
    io::write_ele(path("occupied.ele"), {{0, 1, 2, 3}});
    ADD_FAILURE() << "a write onto a folder succeeded";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("cannot rename"), std::string::npos) << e.what();
  }
  EXPECT_TRUE(fs::is_directory(path("occupied.ele")));
  for (const auto& entry : fs::directory_iterator(dir_)) {
    EXPECT_EQ(entry.path().string().find(".tmp-"), std::string::npos) << entry.path();
  }
}

}  // namespace
}  // namespace dtlab::test
