#pragma once
// What every method runs on and returns: the contract between the driver (driver/triangulate.cpp:
// checks, orders, scales and bounds the points) and a method (sequential.cpp, pessimistic.cpp,
// optimistic_detect.cpp, ...), each one function registered in methods/registry.cpp.
#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "dtlab/engine/triangulate.hpp"

namespace dtlab::engine {

struct MethodInput {
  // Scaled, in storage order (the walk mode's BRIO order renumbers them), the auxiliary
  // tetrahedron's four points after the input's when there is one.
  const std::vector<Point3>& points;
  std::size_t input_count;  // ids below this are input points
  // The insertion order of the ids, or empty for the identity (the walk mode stores the points in
  // the order they are inserted).
  const std::vector<std::uint32_t>& order;
  std::array<std::uint32_t, 4> first;  // the first tetrahedron
  bool skip_first;  // first's points are input points, inserted by start(): not again
  const TriangulateOptions& options;
};

// A method's run: inserts every point, repairs as options.repair asks, fills `stats`, and returns
// the finite tetrahedra below input_count in the engine's numbering (duplicates named by their
// lowest index).
using MethodRun = std::vector<Tetrahedron> (*)(const MethodInput& input, TriangulationStats& stats);

// The methods (one file each) for the registry.
std::vector<Tetrahedron> run_sequential(const MethodInput& input, TriangulationStats& stats);
std::vector<Tetrahedron> run_pessimistic(const MethodInput& input, TriangulationStats& stats);
std::vector<Tetrahedron> run_optimistic_detect(const MethodInput& input, TriangulationStats& stats);
std::vector<Tetrahedron> run_optimistic_prevent(const MethodInput& input,
                                                TriangulationStats& stats);
std::vector<Tetrahedron> run_burglary(const MethodInput& input, TriangulationStats& stats);
std::vector<Tetrahedron> run_batch(const MethodInput& input, TriangulationStats& stats);
std::vector<Tetrahedron> run_partitioned(const MethodInput& input, TriangulationStats& stats);
std::vector<Tetrahedron> run_lock_grid(const MethodInput& input, TriangulationStats& stats);

}  // namespace dtlab::engine
