// ns per predicate call for fast, adaptive, filtered and exact, on random and near-degenerate
// inputs.
#include <benchmark/benchmark.h>

#include <cmath>
#include <random>
#include <vector>

#include "dtlab/predicates/kernels.hpp"

namespace {

using dtlab::predicates::AdaptiveKernel;
using dtlab::predicates::ExactKernel;
using dtlab::predicates::FastKernel;
using dtlab::predicates::FilteredKernel;
using dtlab::predicates::Point3;

std::vector<Point3> inputs(bool near_degenerate) {
  std::mt19937_64 rng(99);
  auto unit = [&] { return std::ldexp(static_cast<double>(rng() >> 11), -53); };
  std::vector<Point3> p;
  for (int i = 0; i < 4096; ++i) {
    if (!near_degenerate) {
      p.push_back({unit(), unit(), unit()});
    } else {
      // Points on a common sphere (rounded): insphere and orient3d near zero.
      const double theta = 2 * M_PI * unit();
      const double z = 2 * unit() - 1;
      const double s = std::sqrt(1 - z * z);
      p.push_back(
          {0.5 + 0.5 * s * std::cos(theta), 0.5 + 0.5 * s * std::sin(theta), 0.5 + 0.5 * z});
    }
  }
  return p;
}

template <class K>
void orient3d(benchmark::State& state) {
  const auto p = inputs(state.range(0) != 0);
  std::size_t i = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(K::orient3d(p[i], p[i + 1], p[i + 2], p[i + 3]));
    i = (i + 4) & 4091;
  }
}

template <class K>
void insphere(benchmark::State& state) {
  const auto p = inputs(state.range(0) != 0);
  std::size_t i = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(K::insphere(p[i], p[i + 1], p[i + 2], p[i + 3], p[i + 4]));
    i = (i + 5) & 4090;
  }
}

// Arg 0: random points; arg 1: near-cospherical points.
BENCHMARK(orient3d<FastKernel>)->Arg(0)->Arg(1);
BENCHMARK(orient3d<AdaptiveKernel>)->Arg(0)->Arg(1);
BENCHMARK(orient3d<FilteredKernel>)->Arg(0)->Arg(1);
BENCHMARK(orient3d<ExactKernel>)->Arg(0)->Arg(1);
BENCHMARK(insphere<FastKernel>)->Arg(0)->Arg(1);
BENCHMARK(insphere<AdaptiveKernel>)->Arg(0)->Arg(1);
BENCHMARK(insphere<FilteredKernel>)->Arg(0)->Arg(1);
BENCHMARK(insphere<ExactKernel>)->Arg(0)->Arg(1);

}  // namespace

BENCHMARK_MAIN();
