#pragma once
// numpy arrays in and out of the engine's vectors. The Python layer (dtlab/__init__.py) has
// already checked shapes and converted dtypes, so these take exactly float64 (n, 3) points and
// int64 (m, 4) simplices, C-contiguous.
#include <pybind11/numpy.h>

#include <array>
#include <climits>
#include <cstdint>
#include <cstring>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <vector>

#include "dtlab/engine/tetrahedron.hpp"
#include "dtlab/predicates/point.hpp"

namespace dtlab::python {

namespace py = pybind11;
using PointArray = py::array_t<double, py::array::c_style>;
using IdArray = py::array_t<std::int64_t, py::array::c_style>;

static_assert(sizeof(predicates::Point3) == 3 * sizeof(double) &&
                  std::is_trivially_copyable_v<predicates::Point3>,
              "an (n, 3) float64 row is one Point3");

// The engine's copy of the points (the one working copy a run makes; no conversion).
inline std::vector<predicates::Point3> to_points(const PointArray& xyz) {
  if (xyz.ndim() != 2 || xyz.shape(1) != 3) throw std::invalid_argument("points must be (n, 3)");
  std::vector<predicates::Point3> points(static_cast<std::size_t>(xyz.shape(0)));
  if (!points.empty()) std::memcpy(points.data(), xyz.data(), points.size() * sizeof(points[0]));
  return points;
}

inline std::vector<engine::Tetrahedron> to_tetrahedra(const IdArray& ids, std::size_t points) {
  if (ids.ndim() != 2 || ids.shape(1) != 4) {
    throw std::invalid_argument("simplices must be an (m, 4) integer array");
  }
  const auto m = static_cast<std::size_t>(ids.shape(0));
  std::vector<engine::Tetrahedron> tets(m);
  const std::int64_t* id = ids.data();
  for (std::size_t t = 0; t < m; ++t) {
    for (std::size_t j = 0; j < 4; ++j) {
      const std::int64_t v = id[t * 4 + j];
      if (v < 0 || static_cast<std::uint64_t>(v) >= points) {
        throw std::invalid_argument("simplex " + std::to_string(t) + " has vertex id " +
                                    std::to_string(v) + ", not in [0, " + std::to_string(points) +
                                    ")");
      }
      tets[t][j] = static_cast<std::uint32_t>(v);
    }
  }
  return tets;
}

// An (rows, N) int32 array of `rows` std::array<T, N> (int32: scipy's dtype for simplices).
template <class T, std::size_t N>
py::array_t<std::int32_t> to_int32_rows(const std::vector<std::array<T, N>>& rows) {
  for (const auto& row : rows) {
    for (const T v : row) {
      if (static_cast<std::int64_t>(v) > INT32_MAX) {
        throw std::invalid_argument("an id above 2^31 - 1 does not fit the int32 arrays");
      }
    }
  }
  py::array_t<std::int32_t> out(
      {static_cast<py::ssize_t>(rows.size()), static_cast<py::ssize_t>(N)});
  std::int32_t* o = out.mutable_data();
  for (std::size_t r = 0; r < rows.size(); ++r) {
    for (std::size_t j = 0; j < N; ++j) o[r * N + j] = static_cast<std::int32_t>(rows[r][j]);
  }
  return out;
}

}  // namespace dtlab::python
