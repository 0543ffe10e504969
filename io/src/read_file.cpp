#include <lzma.h>

#include <cerrno>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "dtlab/io/point_readers.hpp"

namespace dtlab::io {
namespace {

bool ends_with(const std::string& s, std::string_view suffix) {
  return s.size() >= suffix.size() &&
         s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}

std::string decompress_xz(const std::string& packed, const std::string& path) {
  lzma_stream stream = LZMA_STREAM_INIT;
  if (lzma_stream_decoder(&stream, UINT64_MAX, LZMA_CONCATENATED) != LZMA_OK) {
    throw InputError(path + ": cannot start the xz decoder");
  }
  std::string out;
  std::string chunk(1 << 20, '\0');
  stream.next_in = reinterpret_cast<const std::uint8_t*>(packed.data());
  stream.avail_in = packed.size();
  lzma_ret ret = LZMA_OK;
  while (ret == LZMA_OK) {
    stream.next_out = reinterpret_cast<std::uint8_t*>(chunk.data());
    stream.avail_out = chunk.size();
    ret = lzma_code(&stream, LZMA_FINISH);
    out.append(chunk.data(), chunk.size() - stream.avail_out);
  }
  lzma_end(&stream);
  if (ret != LZMA_STREAM_END) {
    throw InputError(path + ": corrupt or truncated xz data (liblzma error " +
                     std::to_string(static_cast<int>(ret)) + ")");
  }
  return out;
}

}  // namespace

std::string read_file_bytes(const std::string& path) {
  // A directory opens, and reads as empty: the error would be about 0 points.
  std::error_code error;
  if (std::filesystem::is_directory(path, error)) {
    throw InputError(path + ": is a directory, not a file");
  }
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path + ": cannot open: " + std::strerror(errno));
  std::ostringstream buffer;
  buffer << in.rdbuf();
  if (in.bad()) throw InputError(path + ": read error");
  std::string bytes = std::move(buffer).str();
  if (ends_with(path, ".xz")) return decompress_xz(bytes, path);
  return bytes;
}

std::vector<Point3> read_points(const std::string& path) {
  std::string name = path;
  if (ends_with(name, ".xz")) name.resize(name.size() - 3);
  auto has = [&](std::string_view ext) { return ends_with(name, ext); };
  if (!has(".xyz") && !has(".ply") && !has(".off") && !has(".node") && !has(".txt")) {
    throw InputError(path +
                     ": unknown point format (expected .xyz, .ply, .off or .node, "
                     "optionally .xz-compressed, or a generator spec such as uniform:1000)");
  }
  const std::string bytes = read_file_bytes(path);
  if (has(".ply")) return parse_ply(bytes, path);
  if (has(".off")) return parse_off(bytes, path);
  if (has(".node")) return parse_node(bytes, path);
  return parse_xyz(bytes, path);
}

}  // namespace dtlab::io
