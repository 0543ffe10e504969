// .xyz, .off and TetGen .node parsers.
#include "dtlab/io/point_readers.hpp"
#include "text_scanner.hpp"

namespace dtlab::io {
namespace {

using detail::TextScanner;

// Reads "x y z" from the start of `line` (further tokens are left in `line`).
Point3 parse_xyz_fields(std::string_view& line, const TextScanner& scan) {
  std::string_view tx;
  std::string_view ty;
  std::string_view tz;
  if (!TextScanner::next_token(line, tx) || !TextScanner::next_token(line, ty) ||
      !TextScanner::next_token(line, tz)) {
    scan.fail("expected three coordinates 'x y z'");
  }
  return {scan.parse_double(tx, "x"), scan.parse_double(ty, "y"), scan.parse_double(tz, "z")};
}

}  // namespace

std::vector<Point3> parse_xyz(std::string_view text, const std::string& name) {
  TextScanner scan(text, name);
  std::vector<Point3> points;
  std::string_view line;
  while (scan.next_content_line(line)) {
    // Further columns (normals, colours) are allowed and ignored.
    points.push_back(parse_xyz_fields(line, scan));
  }
  return points;
}

std::vector<Point3> parse_off(std::string_view text, const std::string& name) {
  TextScanner scan(text, name);
  std::string_view line;
  if (!scan.next_content_line(line)) scan.fail("empty file, expected an OFF header");
  std::string_view keyword;
  TextScanner::next_token(line, keyword);
  if (keyword.size() < 3 || keyword.substr(keyword.size() - 3) != "OFF") {
    scan.fail("not an OFF file (first keyword '" + std::string(keyword) + "')");
  }
  if (keyword.find('4') != std::string_view::npos || keyword.find("n") == 0) {
    scan.fail("only 3D OFF files are supported");
  }
  // The counts may follow the keyword on the same line or stand on the next one.
  std::string_view counts = line;
  std::string_view token;
  if (!TextScanner::next_token(counts, token)) {
    if (!scan.next_content_line(line)) scan.fail("missing vertex/face/edge counts");
    counts = line;
    TextScanner::next_token(counts, token);
  }
  const std::int64_t vertex_count = scan.parse_integer(token, "vertex count");
  if (vertex_count < 0) scan.fail("negative vertex count");
  std::vector<Point3> points;
  points.reserve(static_cast<std::size_t>(std::min<std::int64_t>(vertex_count, 1 << 24)));
  for (std::int64_t i = 0; i < vertex_count; ++i) {
    if (!scan.next_content_line(line)) {
      scan.fail("truncated: header announces " + std::to_string(vertex_count) +
                " vertices, file ends after " + std::to_string(i));
    }
    points.push_back(parse_xyz_fields(line, scan));
  }
  return points;
}

std::vector<Point3> parse_node(std::string_view text, const std::string& name) {
  TextScanner scan(text, name);
  std::string_view line;
  if (!scan.next_content_line(line)) scan.fail("empty file, expected a .node header");
  std::string_view token;
  TextScanner::next_token(line, token);
  const std::int64_t count = scan.parse_integer(token, "point count");
  std::int64_t dimension = 3;
  std::int64_t attributes = 0;
  std::int64_t markers = 0;
  if (TextScanner::next_token(line, token)) dimension = scan.parse_integer(token, "dimension");
  if (TextScanner::next_token(line, token)) attributes = scan.parse_integer(token, "attributes");
  if (TextScanner::next_token(line, token)) markers = scan.parse_integer(token, "marker flag");
  if (count < 0) scan.fail("negative point count");
  if (dimension != 3) scan.fail("dimension must be 3, got " + std::to_string(dimension));
  (void)attributes;
  (void)markers;
  std::vector<Point3> points;
  points.reserve(static_cast<std::size_t>(std::min<std::int64_t>(count, 1 << 24)));
  std::int64_t base = 0;
  for (std::int64_t i = 0; i < count; ++i) {
    if (!scan.next_content_line(line)) {
      scan.fail("truncated: header announces " + std::to_string(count) +
                " points, file ends after " + std::to_string(i));
    }
    if (!TextScanner::next_token(line, token)) scan.fail("missing point index");
    const std::int64_t index = scan.parse_integer(token, "point index");
    if (i == 0) {
      if (index != 0 && index != 1) scan.fail("first point index must be 0 or 1");
      base = index;
    } else if (index != base + i) {
      scan.fail("point index " + std::to_string(index) + " out of sequence (expected " +
                std::to_string(base + i) + ")");
    }
    points.push_back(parse_xyz_fields(line, scan));
  }
  return points;
}

}  // namespace dtlab::io
