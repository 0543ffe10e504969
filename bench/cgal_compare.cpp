// dtlab's sequential engine and CGAL's Delaunay_triangulation_3 on the same points, in the same
// run: seconds (median of --repeat runs), tetrahedra, and the machine.
// Usage: cgal_compare INPUT [--seed S] [--repeat R]
#include <CGAL/Delaunay_triangulation_3.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <string>
#include <thread>
#include <vector>

#include "dtlab/engine/triangulate.hpp"
#include "dtlab/generators/generators.hpp"
#include "dtlab/io/point_readers.hpp"

using Epick = CGAL::Exact_predicates_inexact_constructions_kernel;

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: cgal_compare INPUT [--seed S] [--repeat R]\n");
    return 2;
  }
  const std::string input = argv[1];
  std::uint64_t seed = 1;
  int repeat = 3;
  for (int i = 2; i + 1 < argc; i += 2) {
    if (std::strcmp(argv[i], "--seed") == 0) seed = std::stoull(argv[i + 1]);
    if (std::strcmp(argv[i], "--repeat") == 0) repeat = std::stoi(argv[i + 1]);
  }
  std::vector<dtlab::predicates::Point3> points;
  std::string family;
  std::int64_t n = 0;
  if (dtlab::generators::parse_spec(input, family, n)) {
    points = dtlab::generators::generate(family, n, seed).points;
  } else {
    points = dtlab::io::read_points(input);
  }
  std::vector<double> ours;
  std::vector<double> theirs;
  std::size_t our_tets = 0;
  std::size_t their_tets = 0;
  dtlab::engine::TriangulationStats last;
  for (int r = 0; r < repeat; ++r) {
    dtlab::engine::TriangulateOptions options;
    options.seed = seed;
    const auto result = dtlab::engine::triangulate(points, options);
    ours.push_back(result.stats.seconds.total);
    our_tets = result.tetrahedra.size();
    last = result.stats;

    std::vector<Epick::Point_3> cgal_points;
    cgal_points.reserve(points.size());
    const auto t0 = std::chrono::steady_clock::now();
    for (const auto& p : points) cgal_points.emplace_back(p.x, p.y, p.z);
    CGAL::Delaunay_triangulation_3<Epick> dt(cgal_points.begin(), cgal_points.end());
    theirs.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
    their_tets = dt.number_of_finite_cells();
  }
  std::printf("input %s, %zu points, seed %llu, %d repeats, %u hardware threads\n", input.c_str(),
              points.size(), static_cast<unsigned long long>(seed), repeat,
              std::thread::hardware_concurrency());
  std::printf("%-34s %10s %12s\n", "engine", "median s", "tetrahedra");
  std::printf("%-34s %10.3f %12zu\n", "dtlab sequential (adaptive, DAG)", median(ours), our_tets);
  std::printf("%-34s %10.3f %12zu\n", "CGAL Delaunay_triangulation_3", median(theirs), their_tets);
  std::printf("ratio dtlab / CGAL: %.2f\n", median(ours) / median(theirs));
  std::printf(
      "dtlab phases (last run): location %.3f, subdivision %.3f, legalization %.3f, other %.3f s; "
      "flips S23 %llu S32 %llu S22 %llu S44 %llu; DAG nodes %llu; peak RSS %.0f MiB\n",
      last.seconds.location, last.seconds.subdivision, last.seconds.legalization,
      last.seconds.other, static_cast<unsigned long long>(last.flips.s23),
      static_cast<unsigned long long>(last.flips.s32),
      static_cast<unsigned long long>(last.flips.s22),
      static_cast<unsigned long long>(last.flips.s44),
      static_cast<unsigned long long>(last.dag_nodes),
      static_cast<double>(last.peak_rss_bytes) / 1048576.0);
  return 0;
}
