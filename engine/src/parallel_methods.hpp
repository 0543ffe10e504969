#pragma once
// The lock methods over shared-memory threads (docs/design.md, "Lock methods").
#include <vector>

#include "dtlab/engine/triangulate.hpp"
#include "shared_mesh.hpp"

namespace dtlab::engine {

// Inserts `order` (all input ids, or empty for the identity, as in walk mode, whose points are
// stored in BRIO and Hilbert order; the four of `first` already form the first tetrahedron when
// skip_first) into a mesh built from `points` with options.method on options.threads threads.
// Returns the finite tetrahedra below `input_count`, fills stats.
template <class K>
std::vector<Tetrahedron> run_parallel(const std::vector<Point3>& points, std::size_t input_count,
                                      const std::vector<std::uint32_t>& order,
                                      const std::array<std::uint32_t, 4>& first, bool skip_first,
                                      const TriangulateOptions& options, TriangulationStats& stats);

// Every kernel the drivers are instantiated for: X(K) for each.
#define DTLAB_FOR_EACH_KERNEL(X)                     \
  X(predicates::FastKernel)                          \
  X(predicates::AdaptiveKernel)                      \
  X(predicates::FilteredKernel)                      \
  X(predicates::ExactKernel)                         \
  X(predicates::Audited<predicates::FastKernel>)     \
  X(predicates::Audited<predicates::AdaptiveKernel>) \
  X(predicates::Audited<predicates::FilteredKernel>) \
  X(predicates::Audited<predicates::ExactKernel>)

// The sequential engine on the same arguments (engine/src/triangulate.cpp); an empty order
// inserts 0 .. input_count - 1.
template <class K>
std::vector<Tetrahedron> run_sequential(const std::vector<Point3>& points, std::size_t input_count,
                                        const std::vector<std::uint32_t>& order,
                                        const std::array<std::uint32_t, 4>& first, bool skip_first,
                                        const TriangulateOptions& options,
                                        TriangulationStats& stats);

// The points of `order` split among `threads` per the distribution (static, strips, blocks;
// dynamic is handled by the caller with a shared index, and auto resolved by
// effective_distribution). Each part keeps the random order.
std::vector<std::vector<std::uint32_t>> distribute(const std::vector<Point3>& points,
                                                   const std::vector<std::uint32_t>& order,
                                                   Distribution distribution, int threads);

}  // namespace dtlab::engine
