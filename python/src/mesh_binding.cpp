// dtlab._dtlab's functions over a finished tetrahedron list: validate, repair, face adjacency,
// and the generators. Each releases the GIL while the engine works.
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <string>

#include "arrays.hpp"
#include "dtlab/engine/face_adjacency.hpp"
#include "dtlab/engine/repair.hpp"
#include "dtlab/engine/stats.hpp"
#include "dtlab/engine/validator.hpp"
#include "dtlab/generators/generators.hpp"
#include "option_names.hpp"

namespace dtlab::python {
namespace {

// The validator's report as JSON (the CLI's `dtlab validate` output) and how many tetrahedra
// were turned first (oriented=False).
py::tuple validate(const PointArray& xyz, const IdArray& ids, bool oriented,
                   const std::string& kernel, int threads) {
  const auto points = to_points(xyz);
  auto tets = to_tetrahedra(ids, points.size());
  const auto with = named<engine::ValidateWith>(kernel, 2, "kernel");
  std::uint64_t turned = 0;
  std::string report;
  {
    py::gil_scoped_release unlocked;
    if (!oriented) turned = engine::orient_positively(points, tets);
    report = engine::validate(points, tets, with, threads).json();
  }
  return py::make_tuple(report, turned);
}

py::tuple repair(const PointArray& xyz, const IdArray& ids, int threads) {
  const auto points = to_points(xyz);
  const auto tets = to_tetrahedra(ids, points.size());
  engine::SplayStats stats;
  std::vector<engine::Tetrahedron> repaired;
  {
    py::gil_scoped_release unlocked;
    repaired = engine::repair(points, tets, stats, threads);
  }
  return py::make_tuple(
      to_int32_rows(repaired),
      engine::repair_stats_json(stats, points.size(), tets.size(), repaired.size()));
}

py::tuple face_adjacency(const IdArray& ids, std::size_t points) {
  const auto tets = to_tetrahedra(ids, points);
  engine::FaceAdjacency adjacency;
  {
    py::gil_scoped_release unlocked;
    adjacency = engine::face_adjacency(tets, points);
  }
  return py::make_tuple(to_int32_rows(adjacency.neighbors),
                        to_int32_rows(adjacency.boundary_faces));
}

py::array_t<double> generate(const std::string& family, std::int64_t n, std::uint64_t seed) {
  generators::GeneratedPoints g;
  {
    py::gil_scoped_release unlocked;
    g = generators::generate(family, n, seed);
  }
  py::array_t<double> out({static_cast<py::ssize_t>(g.points.size()), py::ssize_t{3}});
  double* o = out.mutable_data();
  for (std::size_t i = 0; i < g.points.size(); ++i) {
    o[3 * i] = g.points[i].x;
    o[3 * i + 1] = g.points[i].y;
    o[3 * i + 2] = g.points[i].z;
  }
  return out;
}

}  // namespace

void bind_mesh(py::module_& m) {
  m.def("validate", &validate, py::arg("points"), py::arg("simplices"), py::arg("oriented"),
        py::arg("kernel"), py::arg("threads"));
  m.def("repair", &repair, py::arg("points"), py::arg("simplices"), py::arg("threads"));
  m.def("face_adjacency", &face_adjacency, py::arg("simplices"), py::arg("points"));
  m.def("generate", &generate, py::arg("family"), py::arg("n"), py::arg("seed"));
  m.def("families", [] { return generators::families(); });
}

}  // namespace dtlab::python
