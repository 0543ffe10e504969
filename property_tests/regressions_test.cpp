// Every counterexample ever found, kept as an input named after what found it, replayed by an
// ordinary test: property_tests/regressions/*.xyz (minimized point sets) and specs.txt (generator
// specs with seed and kernel). Adaptive, filtered and exact results must validate; the fast kernel
// must finish (its result may be invalid).
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "dtlab/engine/triangulate.hpp"
#include "dtlab/engine/validator.hpp"
#include "dtlab/generators/generators.hpp"
#include "dtlab/io/point_readers.hpp"

namespace dtlab::property {
namespace {

TEST(Regressions, AllKeptCounterexamplesValidate) {
  const std::filesystem::path dir = DTLAB_REGRESSION_DIR;
  int replayed = 0;
  for (const auto& entry : std::filesystem::directory_iterator(dir)) {
    if (entry.path().extension() != ".xyz") continue;
    const auto points = io::read_points(entry.path().string());
    for (const auto kernel :
         {engine::KernelKind::Adaptive, engine::KernelKind::Filtered, engine::KernelKind::Exact}) {
      engine::TriangulateOptions options;
      options.kernel = kernel;
      const auto report = engine::validate(points, engine::triangulate(points, options).tetrahedra);
      EXPECT_TRUE(report.valid()) << entry.path() << " " << engine::to_string(kernel)
                                  << report.json();
    }
    engine::TriangulateOptions fast;
    fast.kernel = engine::KernelKind::Fast;
    try {
      (void)engine::triangulate(points, fast);  // may be wrong or refuse; must not crash
    } catch (const engine::TriangulationError&) {
    }
    ++replayed;
  }
  std::ifstream specs(dir / "specs.txt");
  std::string line;
  while (std::getline(specs, line)) {
    if (line.empty() || line[0] == '#') continue;
    std::istringstream fields(line);
    std::string spec;
    std::uint64_t seed = 1;
    std::string kernel;
    fields >> spec >> seed >> kernel;
    std::string family;
    std::int64_t n = 0;
    ASSERT_TRUE(generators::parse_spec(spec, family, n)) << line;
    const auto points = generators::generate(family, n, seed).points;
    engine::TriangulateOptions options;
    options.seed = seed;
    options.kernel = kernel == "fast"       ? engine::KernelKind::Fast
                     : kernel == "exact"    ? engine::KernelKind::Exact
                     : kernel == "filtered" ? engine::KernelKind::Filtered
                                            : engine::KernelKind::Adaptive;
    const auto result = engine::triangulate(points, options);
    EXPECT_EQ(result.stats.inserted + result.stats.duplicates + result.stats.abandoned_insertions,
              points.size());
    if (options.kernel != engine::KernelKind::Fast) {
      EXPECT_TRUE(engine::validate(points, result.tetrahedra).valid()) << line;
    }
    ++replayed;
  }
  EXPECT_GT(replayed, 0);
}

}  // namespace
}  // namespace dtlab::property
