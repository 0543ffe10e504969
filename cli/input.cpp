#include "input.hpp"

#include <cstdio>
#include <stdexcept>

#include "dtlab/generators/generators.hpp"
#include "dtlab/io/point_readers.hpp"

namespace dtlab::cli {

std::vector<predicates::Point3> load_input(const std::string& input, std::uint64_t seed) {
  std::string family;
  std::int64_t n = 0;
  if (generators::parse_spec(input, family, n)) {
    generators::GeneratedPoints g = generators::generate(family, n, seed);
    if (!g.note.empty()) std::fprintf(stderr, "dtlab: %s\n", g.note.c_str());
    return std::move(g.points);
  }
  return io::read_points(input);
}

}  // namespace dtlab::cli
