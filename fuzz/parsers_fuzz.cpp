// Parsers: any bytes as .xyz, .ply, .off and .node: a clear InputError or finite points, never a
// crash; and the points any of them read, written as write_xyz writes them, read back by the .xyz
// parser bit for bit (a parsed file round-trips).
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <string_view>

#include "dtlab/io/mesh_writers.hpp"
#include "dtlab/io/point_readers.hpp"

namespace {

bool same_bits(double a, double b) {
  return std::bit_cast<std::uint64_t>(a) == std::bit_cast<std::uint64_t>(b);
}

void check_round_trip(const std::vector<dtlab::io::Point3>& points) {
  std::string text;
  for (const auto& p : points) text += dtlab::io::format_xyz_line(p);
  std::vector<dtlab::io::Point3> again;
  try {
    again = dtlab::io::parse_xyz(text, "round trip");
  } catch (const dtlab::io::InputError& e) {
    std::fprintf(stderr, "parsers_fuzz: the .xyz written back was refused: %s\n", e.what());
    std::abort();
  }
  bool same = again.size() == points.size();
  for (std::size_t i = 0; same && i < points.size(); ++i) {
    same = same_bits(again[i].x, points[i].x) && same_bits(again[i].y, points[i].y) &&
           same_bits(again[i].z, points[i].z);
  }
  if (!same) {
    std::fprintf(stderr, "parsers_fuzz: %zu points did not round-trip through .xyz\n",
                 points.size());
    std::abort();
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view bytes(reinterpret_cast<const char*>(data), size);
  using Parser = std::vector<dtlab::io::Point3> (*)(std::string_view, const std::string&);
  for (const Parser parse :
       {static_cast<Parser>(dtlab::io::parse_xyz), static_cast<Parser>(dtlab::io::parse_ply),
        static_cast<Parser>(dtlab::io::parse_off), static_cast<Parser>(dtlab::io::parse_node)}) {
    std::vector<dtlab::io::Point3> points;
    try {
      points = parse(bytes, "fuzz");
    } catch (const dtlab::io::InputError&) {
      continue;
    }
    for (const auto& p : points) {
      if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z)) std::abort();
    }
    check_round_trip(points);
  }
  return 0;
}
