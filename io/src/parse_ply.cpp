// PLY parser: ASCII, binary_little_endian and binary_big_endian; reads the vertex element's
// x, y, z (float or double) and skips every other property and element.
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <optional>

#include "dtlab/io/point_readers.hpp"
#include "text_scanner.hpp"

namespace dtlab::io {
namespace {

// The longest list a PLY row may declare (each entry is read, so a longer one is no real file).
constexpr double kMaxListLength = 2147483648.0;

using detail::TextScanner;

enum class Encoding { Ascii, LittleEndian, BigEndian };

struct ScalarType {
  int size = 0;
  bool is_float = false;
  bool is_signed = false;
};

std::optional<ScalarType> scalar_type(std::string_view name) {
  if (name == "char" || name == "int8") return ScalarType{1, false, true};
  if (name == "uchar" || name == "uint8") return ScalarType{1, false, false};
  if (name == "short" || name == "int16") return ScalarType{2, false, true};
  if (name == "ushort" || name == "uint16") return ScalarType{2, false, false};
  if (name == "int" || name == "int32") return ScalarType{4, false, true};
  if (name == "uint" || name == "uint32") return ScalarType{4, false, false};
  if (name == "float" || name == "float32") return ScalarType{4, true, true};
  if (name == "double" || name == "float64") return ScalarType{8, true, true};
  return std::nullopt;
}

struct Property {
  std::string name;
  ScalarType type;
  bool is_list = false;
  ScalarType count_type;
};

struct Element {
  std::string name;
  std::int64_t count = 0;
  std::vector<Property> properties;
};

class BinaryReader {
 public:
  BinaryReader(std::string_view bytes, bool big_endian, const std::string& name)
      : bytes_(bytes), big_endian_(big_endian), name_(name) {}

  double read(const ScalarType& t, const std::string& where) {
    if (pos_ + static_cast<std::size_t>(t.size) > bytes_.size()) {
      throw InputError(name_ + ": truncated binary data in " + where);
    }
    unsigned char raw[8];
    std::memcpy(raw, bytes_.data() + pos_, static_cast<std::size_t>(t.size));
    pos_ += static_cast<std::size_t>(t.size);
    const bool swap = big_endian_ != (std::endian::native == std::endian::big);
    if (swap) {
      for (int i = 0; i < t.size / 2; ++i) std::swap(raw[i], raw[t.size - 1 - i]);
    }
    if (t.is_float) {
      if (t.size == 4) {
        float f = 0;
        std::memcpy(&f, raw, 4);
        return f;
      }
      double d = 0;
      std::memcpy(&d, raw, 8);
      return d;
    }
    std::uint64_t u = 0;
    for (int i = 0; i < t.size; ++i) {
      u |= static_cast<std::uint64_t>(raw[i])
           << (8 * (std::endian::native == std::endian::little ? i : t.size - 1 - i));
    }
    if (t.is_signed && t.size < 8 && (u >> (8 * t.size - 1)) != 0) {
      u |= ~std::uint64_t{0} << (8 * t.size);
    }
    return t.is_signed ? static_cast<double>(static_cast<std::int64_t>(u)) : static_cast<double>(u);
  }

 private:
  std::string_view bytes_;
  std::size_t pos_ = 0;
  bool big_endian_;
  const std::string& name_;
};

// Token stream over the ASCII body (records may be laid out on lines in any way).
class AsciiReader {
 public:
  AsciiReader(std::string_view body, std::size_t first_line, const std::string& name)
      : rest_(body), line_(first_line), name_(name) {}

  double read(const std::string& where) {
    std::string_view token;
    while (true) {
      while (!rest_.empty() && (TextScanner::is_space(rest_.front()) || rest_.front() == '\n')) {
        // A row ends at "\n", "\r\n" or a lone "\r", as in TextScanner::line_end.
        const bool lone_cr = rest_.front() == '\r' && (rest_.size() < 2 || rest_[1] != '\n');
        if (rest_.front() == '\n' || lone_cr) ++line_;
        rest_.remove_prefix(1);
      }
      if (rest_.empty()) throw InputError(name_ + ": truncated ASCII data in " + where);
      std::size_t n = 0;
      while (n < rest_.size() && !TextScanner::is_space(rest_[n]) && rest_[n] != '\n') ++n;
      token = rest_.substr(0, n);
      rest_.remove_prefix(n);
      break;
    }
    double v = 0.0;
    const char* first = token.data() + ((!token.empty() && token.front() == '+') ? 1 : 0);
    const auto [ptr, ec] = std::from_chars(first, token.data() + token.size(), v);
    if (ec != std::errc() || ptr != token.data() + token.size()) {
      throw InputError(name_ + ":" + std::to_string(line_) + ": expected a number in " + where +
                       ", got '" + std::string(token) + "'");
    }
    return v;
  }

 private:
  std::string_view rest_;
  std::size_t line_;
  const std::string& name_;
};

// Where the body starts: after the header's first line whose keyword is end_header (the words
// may also stand in a comment line, and in a binary body), or npos when no line is.
std::size_t ply_body_start(std::string_view bytes) {
  TextScanner::LineEnds ends;
  for (std::size_t at = 0; at < bytes.size();) {
    std::size_t next = 0;
    std::string_view line = bytes.substr(at, TextScanner::line_end(bytes, at, next, ends) - at);
    std::string_view keyword;
    if (TextScanner::next_token(line, keyword) && keyword == "end_header") return next;
    at = next;
  }
  return std::string_view::npos;
}

}  // namespace

std::vector<Point3> parse_ply(std::string_view bytes, const std::string& name) {
  if (bytes.substr(0, 3) != "ply") throw InputError(name + ": not a PLY file (no 'ply' magic)");
  const std::size_t body_start = ply_body_start(bytes);
  if (body_start == std::string_view::npos) {
    throw InputError(name + ": PLY header has no end_header line");
  }
  TextScanner scan(bytes.substr(0, body_start), name);

  std::optional<Encoding> encoding;
  std::vector<Element> elements;
  std::string_view line;
  scan.next_content_line(line);  // "ply"
  while (scan.next_content_line(line)) {
    std::string_view keyword;
    TextScanner::next_token(line, keyword);
    if (keyword == "end_header") break;
    if (keyword == "comment" || keyword == "obj_info") continue;
    std::string_view a;
    std::string_view b;
    if (keyword == "format") {
      TextScanner::next_token(line, a);
      if (a == "ascii")
        encoding = Encoding::Ascii;
      else if (a == "binary_little_endian")
        encoding = Encoding::LittleEndian;
      else if (a == "binary_big_endian")
        encoding = Encoding::BigEndian;
      else
        scan.fail("unknown PLY format '" + std::string(a) + "'");
    } else if (keyword == "element") {
      if (!TextScanner::next_token(line, a) || !TextScanner::next_token(line, b)) {
        scan.fail("element line needs a name and a count");
      }
      const std::int64_t count = scan.parse_integer(b, "element count");
      if (count < 0) scan.fail("negative element count");
      elements.push_back({std::string(a), count, {}});
    } else if (keyword == "property") {
      if (elements.empty()) scan.fail("property before any element");
      Property p;
      TextScanner::next_token(line, a);
      if (a == "list") {
        std::string_view count_type;
        std::string_view item_type;
        std::string_view pname;
        if (!TextScanner::next_token(line, count_type) ||
            !TextScanner::next_token(line, item_type) || !TextScanner::next_token(line, pname)) {
          scan.fail("list property needs a count type, an item type and a name");
        }
        const auto ct = scalar_type(count_type);
        const auto it = scalar_type(item_type);
        if (!ct || !it || ct->is_float) scan.fail("bad list property types");
        p = {std::string(pname), *it, true, *ct};
      } else {
        const auto t = scalar_type(a);
        if (!t) scan.fail("unknown property type '" + std::string(a) + "'");
        if (!TextScanner::next_token(line, b)) scan.fail("property without a name");
        p = {std::string(b), *t, false, {}};
      }
      elements.back().properties.push_back(p);
    } else {
      scan.fail("unexpected PLY header keyword '" + std::string(keyword) + "'");
    }
  }
  if (!encoding) throw InputError(name + ": PLY header has no format line");

  const Element* vertex = nullptr;
  std::size_t vertex_index = 0;
  for (std::size_t i = 0; i < elements.size(); ++i) {
    if (elements[i].name == "vertex") {
      vertex = &elements[i];
      vertex_index = i;
      break;
    }
  }
  if (vertex == nullptr) throw InputError(name + ": PLY file has no vertex element");
  int ix = -1;
  int iy = -1;
  int iz = -1;
  for (std::size_t i = 0; i < vertex->properties.size(); ++i) {
    const Property& p = vertex->properties[i];
    const int k = static_cast<int>(i);
    if (p.name == "x") ix = k;
    if (p.name == "y") iy = k;
    if (p.name == "z") iz = k;
  }
  if (ix < 0 || iy < 0 || iz < 0) throw InputError(name + ": vertex element lacks x, y or z");
  for (const int k : {ix, iy, iz}) {
    const Property& p = vertex->properties[static_cast<std::size_t>(k)];
    if (p.is_list || !p.type.is_float) {
      throw InputError(name + ": vertex property " + p.name + " must be float or double");
    }
  }

  const std::string_view body = bytes.substr(body_start);
  std::vector<Point3> points;
  points.reserve(static_cast<std::size_t>(std::min<std::int64_t>(vertex->count, 1 << 24)));
  auto read_elements = [&](auto&& read_scalar) {
    for (std::size_t e = 0; e <= vertex_index; ++e) {
      const Element& el = elements[e];
      // Rows without properties hold no data: skipped, or a count of 10^11 would spin (a hang
      // found by fuzz_parsers).
      if (el.properties.empty()) continue;
      for (std::int64_t r = 0; r < el.count; ++r) {
        const std::string where = "element " + el.name + " #" + std::to_string(r);
        double xyz[3] = {0, 0, 0};
        for (std::size_t k = 0; k < el.properties.size(); ++k) {
          const Property& p = el.properties[k];
          if (p.is_list) {
            const double n = read_scalar(p.count_type, where);
            if (n < 0) throw InputError(name + ": negative list length in " + where);
            // A count read as a float or from text may be NaN, fractional or beyond any integer
            // type: converting those is undefined (UBSan under clang, from the parsers' corpus).
            if (!(n <= kMaxListLength) || n != std::floor(n)) {
              throw InputError(name + ": list length in " + where +
                               " is not a whole number up to 2^31");
            }
            for (std::int64_t j = 0; j < static_cast<std::int64_t>(n); ++j)
              read_scalar(p.type, where);
            continue;
          }
          const double v = read_scalar(p.type, where);
          const int kk = static_cast<int>(k);
          if (e == vertex_index && (kk == ix || kk == iy || kk == iz)) {
            if (!std::isfinite(v)) {
              throw InputError(name + ": vertex #" + std::to_string(r) + " has a non-finite " +
                               p.name);
            }
            xyz[kk == ix ? 0 : (kk == iy ? 1 : 2)] = v;
          }
        }
        if (e == vertex_index) points.push_back({xyz[0], xyz[1], xyz[2]});
      }
    }
  };
  if (*encoding == Encoding::Ascii) {
    AsciiReader reader(body, scan.line_number() + 1, name);
    read_elements([&](const ScalarType&, const std::string& where) { return reader.read(where); });
  } else {
    BinaryReader reader(body, *encoding == Encoding::BigEndian, name);
    read_elements(
        [&](const ScalarType& t, const std::string& where) { return reader.read(t, where); });
  }
  return points;
}

}  // namespace dtlab::io
