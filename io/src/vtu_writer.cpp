// VTK XML unstructured grid (.vtu), inline: text, base64 binary, or base64 zlib blocks.
// The binary layouts (VTK's "XML file formats" document): every DataArray's bytes are preceded
// by a header of UInt64 words. Uncompressed: one word, the byte count, encoded in one base64 run
// with the data. Compressed: [blocks, block size, last block's size, compressed size of each
// block], encoded as its own base64 run, then the compressed blocks as a second run.
#include <zlib.h>

#include <algorithm>
#include <bit>
#include <climits>
#include <cstring>
#include <ostream>
#include <stdexcept>
#include <vector>

#include "atomic_file.hpp"
#include "dtlab/io/mesh_writers.hpp"

namespace dtlab::io {
namespace {

constexpr std::size_t kBlockBytes = 32768;

// Base64 text written to a stream as it is made (the arrays can be hundreds of megabytes).
class Base64 {
 public:
  explicit Base64(std::ostream& out) : out_(out) {}
  Base64(const Base64&) = delete;
  Base64& operator=(const Base64&) = delete;
  ~Base64() { out_.write(text_.data(), static_cast<std::streamsize>(text_.size())); }
  void add(const void* data, std::size_t size) {
    const auto* bytes = static_cast<const unsigned char*>(data);
    for (std::size_t i = 0; i < size; ++i) {
      pending_[count_++] = bytes[i];
      if (count_ == 3) emit();
    }
  }
  void finish() {
    if (count_ == 0) return;
    const std::size_t real = count_;
    while (count_ < 3) pending_[count_++] = 0;
    emit();
    for (std::size_t i = real + 1; i < 4; ++i) text_[text_.size() - 4 + i] = '=';
  }

 private:
  void emit() {
    static constexpr char kDigits[] =
        "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    const unsigned word = (pending_[0] << 16U) | (pending_[1] << 8U) | pending_[2];
    if (text_.size() >= kFlushAt) {
      out_.write(text_.data(), static_cast<std::streamsize>(text_.size()));
      text_.clear();
    }
    text_ += kDigits[(word >> 18U) & 63U];
    text_ += kDigits[(word >> 12U) & 63U];
    text_ += kDigits[(word >> 6U) & 63U];
    text_ += kDigits[word & 63U];
    count_ = 0;
  }
  static constexpr std::size_t kFlushAt = 1 << 16;
  std::ostream& out_;
  std::string text_;
  unsigned char pending_[3] = {0, 0, 0};
  std::size_t count_ = 0;
};

// The array's bytes (little-endian: static_assert below) in the chosen binary layout.
void encode(std::ostream& out, const std::string& bytes, VtuEncoding encoding) {
  if (encoding == VtuEncoding::Binary) {
    const std::uint64_t size = bytes.size();
    Base64 run(out);
    run.add(&size, sizeof size);
    run.add(bytes.data(), bytes.size());
    run.finish();
    return;
  }
  const std::size_t blocks = (bytes.size() + kBlockBytes - 1) / kBlockBytes;
  std::vector<std::uint64_t> header{blocks, kBlockBytes,
                                    bytes.size() - (blocks == 0 ? 0 : (blocks - 1) * kBlockBytes)};
  if (blocks == 0) header[1] = 0;
  std::string compressed;
  std::vector<unsigned char> block(compressBound(kBlockBytes));
  for (std::size_t b = 0; b < blocks; ++b) {
    const std::size_t size = std::min(kBlockBytes, bytes.size() - b * kBlockBytes);
    uLongf out_size = block.size();
    // Level 1: most of the gain on ids and offsets, little time; coordinates barely compress.
    if (compress2(block.data(), &out_size,
                  reinterpret_cast<const Bytef*>(bytes.data() + b * kBlockBytes), size,
                  1) != Z_OK) {
      throw std::runtime_error("zlib failed to compress a .vtu block");
    }
    header.push_back(out_size);
    compressed.append(reinterpret_cast<const char*>(block.data()), out_size);
  }
  {
    Base64 header_run(out);
    header_run.add(header.data(), header.size() * sizeof(std::uint64_t));
    header_run.finish();
  }
  Base64 data_run(out);
  data_run.add(compressed.data(), compressed.size());
  data_run.finish();
}

template <class T>
void append_bytes(std::string& bytes, T value) {
  char raw[sizeof(T)];
  std::memcpy(raw, &value, sizeof(T));
  bytes.append(raw, sizeof(T));
}

// One DataArray: `fill(bytes, text)` appends each value to both the binary buffer and the text.
template <class Fill>
void data_array(std::ostream& out, const char* type, const std::string& name, int components,
                VtuEncoding encoding, Fill&& fill) {
  out << "<DataArray type=\"" << type << '"';
  if (!name.empty()) out << " Name=\"" << name << '"';
  if (components > 1) out << " NumberOfComponents=\"" << components << '"';
  out << " format=\"" << (encoding == VtuEncoding::Ascii ? "ascii" : "binary") << "\">\n";
  std::string bytes;
  std::string text;
  fill(bytes, text, encoding == VtuEncoding::Ascii);
  if (encoding == VtuEncoding::Ascii) {
    out << text;
  } else {
    encode(out, bytes, encoding);
    out << '\n';
  }
  out << "</DataArray>\n";
}

}  // namespace

static_assert(std::endian::native == std::endian::little, "the .vtu says LittleEndian");

void write_vtu(const std::string& path, const std::vector<Point3>& points,
               const std::vector<Tetrahedron>& tets, const std::vector<CellArray>& cell_data,
               VtuEncoding encoding) {
  for (const CellArray& array : cell_data) {
    if (array.values.size() != tets.size()) {
      throw std::invalid_argument("cell array " + array.name + " has " +
                                  std::to_string(array.values.size()) + " values for " +
                                  std::to_string(tets.size()) + " tetrahedra");
    }
  }
  detail::AtomicFile file(path);
  auto& out = file.stream();
  out << "<?xml version=\"1.0\"?>\n"
         "<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\"LittleEndian\" "
         "header_type=\"UInt64\"";
  if (encoding == VtuEncoding::Zlib) out << " compressor=\"vtkZLibDataCompressor\"";
  out << ">\n<UnstructuredGrid>\n<Piece NumberOfPoints=\"" << points.size() << "\" NumberOfCells=\""
      << tets.size() << "\">\n<Points>\n";
  data_array(
      out, "Float64", "", 3, encoding, [&](std::string& bytes, std::string& text, bool ascii) {
        for (const Point3& p : points) {
          if (ascii) {
            text += format_double(p.x) + ' ' + format_double(p.y) + ' ' + format_double(p.z) + '\n';
          } else {
            append_bytes(bytes, p.x);
            append_bytes(bytes, p.y);
            append_bytes(bytes, p.z);
          }
        }
      });
  out << "</Points>\n<Cells>\n";
  // 32-bit ids and offsets where they fit, else 64-bit (VTK's signed types).
  const bool wide_ids = points.size() > static_cast<std::size_t>(INT32_MAX);
  const bool wide_offsets = 4 * tets.size() > static_cast<std::size_t>(INT32_MAX);
  data_array(out, wide_ids ? "Int64" : "Int32", "connectivity", 1, encoding,
             [&](std::string& bytes, std::string& text, bool ascii) {
               for (const Tetrahedron& t : tets) {
                 if (ascii) {
                   text += std::to_string(t[0]) + ' ' + std::to_string(t[1]) + ' ' +
                           std::to_string(t[2]) + ' ' + std::to_string(t[3]) + '\n';
                 } else {
                   for (const std::uint32_t v : t) {
                     if (wide_ids) {
                       append_bytes(bytes, static_cast<std::int64_t>(v));
                     } else {
                       append_bytes(bytes, static_cast<std::int32_t>(v));
                     }
                   }
                 }
               }
             });
  data_array(out, wide_offsets ? "Int64" : "Int32", "offsets", 1, encoding,
             [&](std::string& bytes, std::string& text, bool ascii) {
               for (std::size_t i = 0; i < tets.size(); ++i) {
                 const auto offset = static_cast<std::int64_t>(4 * (i + 1));
                 if (ascii) {
                   text += std::to_string(offset) + '\n';
                 } else if (wide_offsets) {
                   append_bytes(bytes, offset);
                 } else {
                   append_bytes(bytes, static_cast<std::int32_t>(offset));
                 }
               }
             });
  data_array(out, "UInt8", "types", 1, encoding,
             [&](std::string& bytes, std::string& text, bool ascii) {
               constexpr std::uint8_t kTetra = 10;  // VTK_TETRA
               for (std::size_t i = 0; i < tets.size(); ++i) {
                 if (ascii) {
                   text += "10\n";
                 } else {
                   append_bytes(bytes, kTetra);
                 }
               }
             });
  out << "</Cells>\n";
  if (!cell_data.empty()) {
    out << "<CellData>\n";
    for (const CellArray& array : cell_data) {
      data_array(out, "Int32", array.name, 1, encoding,
                 [&](std::string& bytes, std::string& text, bool ascii) {
                   for (const std::int32_t v : array.values) {
                     if (ascii) {
                       text += std::to_string(v) + '\n';
                     } else {
                       append_bytes(bytes, v);
                     }
                   }
                 });
    }
    out << "</CellData>\n";
  }
  out << "</Piece>\n</UnstructuredGrid>\n</VTKFile>\n";
  file.commit();
}

}  // namespace dtlab::io
