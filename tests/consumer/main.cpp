// Triangulates 1000 uniform points with an installed dtlab and validates the result.
#include <cstdio>

#include "dtlab/engine/triangulate.hpp"
#include "dtlab/engine/validator.hpp"
#include "dtlab/generators/generators.hpp"

int main() {
  const auto points = dtlab::generators::generate("uniform", 1000, 1).points;
  const auto result = dtlab::engine::triangulate(points, {});
  const bool valid = dtlab::engine::validate(points, result.tetrahedra).valid();
  std::printf("consumer: %zu tetrahedra, valid %d\n", result.tetrahedra.size(), valid);
  return valid ? 0 : 1;
}
