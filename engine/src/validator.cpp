#include "dtlab/engine/validator.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <nlohmann/json.hpp>
#include <stdexcept>

#include "dtlab/engine/point_set_info.hpp"
#include "dtlab/engine/tet_mesh.hpp"
#include "dtlab/predicates/kernels.hpp"
#include "exact_volume.hpp"
#include "probe_coverage.hpp"

namespace dtlab::engine {
namespace {

struct FaceEntry {
  std::array<std::uint32_t, 3> key;  // sorted vertex ids
  std::uint32_t tet;
  std::uint8_t face;
  std::uint8_t parity;  // parity of the permutation from the sorted key to the outward triple
};

std::uint8_t permutation_parity(const std::array<std::uint32_t, 3>& triple) {
  int inversions = 0;
  for (int i = 0; i < 3; ++i) {
    for (int j = i + 1; j < 3; ++j) {
      if (triple[static_cast<std::size_t>(i)] > triple[static_cast<std::size_t>(j)]) ++inversions;
    }
  }
  return static_cast<std::uint8_t>(inversions & 1);
}

std::array<std::uint32_t, 3> oriented_face(const Tetrahedron& t, int f) {
  const auto& fv = kFaceVertex[static_cast<std::size_t>(f)];
  return {t[static_cast<std::size_t>(fv[0])], t[static_cast<std::size_t>(fv[1])],
          t[static_cast<std::size_t>(fv[2])]};
}

template <class K>
void check(const std::vector<Point3>& pts, const std::vector<Tetrahedron>& tets,
           ValidationReport& r) {
  const std::size_t n = pts.size();
  std::vector<bool> usable(tets.size(), true);
  std::vector<bool> positive(tets.size(), false);  // usable and positively oriented
  std::vector<char> near_reflex(n, 0);             // a vertex where the boundary is not convex
  for (std::size_t i = 0; i < tets.size(); ++i) {
    const Tetrahedron& t = tets[i];
    bool ok = true;
    for (int a = 0; a < 4; ++a) {
      if (t[static_cast<std::size_t>(a)] >= n) ok = false;
      for (int b = a + 1; b < 4; ++b) {
        if (t[static_cast<std::size_t>(a)] == t[static_cast<std::size_t>(b)]) ok = false;
      }
    }
    if (!ok) {
      ++r.invalid_tetrahedra;
      usable[i] = false;
      continue;
    }
    if (K::orient3d(pts[t[0]], pts[t[1]], pts[t[2]], pts[t[3]]) <= 0) {
      ++r.non_positive_orientation;
    } else {
      positive[i] = true;
    }
  }

  std::vector<FaceEntry> faces;
  faces.reserve(4 * tets.size());
  for (std::size_t i = 0; i < tets.size(); ++i) {
    if (!usable[i]) continue;
    for (int f = 0; f < 4; ++f) {
      const auto triple = oriented_face(tets[i], f);
      auto key = triple;
      std::sort(key.begin(), key.end());
      faces.push_back({key, static_cast<std::uint32_t>(i), static_cast<std::uint8_t>(f),
                       permutation_parity(triple)});
    }
  }
  std::sort(faces.begin(), faces.end(),
            [](const FaceEntry& a, const FaceEntry& b) { return a.key < b.key; });

  r.non_delaunay_flags.assign(tets.size(), 0);
  std::vector<std::array<std::uint32_t, 3>> boundary;  // outward-oriented boundary faces
  std::size_t distinct_faces = 0;
  for (std::size_t i = 0; i < faces.size();) {
    std::size_t j = i;
    while (j < faces.size() && faces[j].key == faces[i].key) ++j;
    ++distinct_faces;
    const std::size_t count = j - i;
    if (count == 1) {
      ++r.boundary_faces;
      boundary.push_back(oriented_face(tets[faces[i].tet], faces[i].face));
    } else if (count == 2) {
      ++r.interior_faces;
      const FaceEntry& a = faces[i];
      const FaceEntry& b = faces[i + 1];
      if (a.parity == b.parity) ++r.inconsistent_faces;
      const Tetrahedron& ta = tets[a.tet];
      const std::uint32_t opposite = tets[b.tet][b.face];
      if (K::insphere(pts[ta[0]], pts[ta[1]], pts[ta[2]], pts[ta[3]], pts[opposite]) > 0) {
        ++r.non_delaunay_faces;
        r.non_delaunay_flags[a.tet] = 1;
        r.non_delaunay_flags[b.tet] = 1;
      }
    } else {
      r.non_manifold_faces += 1;
    }
    i = j;
  }

  // Boundary edges: each must be on exactly two boundary faces, and there convex.
  struct EdgeEntry {
    std::array<std::uint32_t, 2> key;
    std::uint32_t face;
  };
  std::vector<EdgeEntry> edges;
  edges.reserve(3 * boundary.size());
  for (std::size_t f = 0; f < boundary.size(); ++f) {
    for (int e = 0; e < 3; ++e) {
      std::uint32_t a = boundary[f][static_cast<std::size_t>(e)];
      std::uint32_t b = boundary[f][static_cast<std::size_t>((e + 1) % 3)];
      if (a > b) std::swap(a, b);
      edges.push_back({{a, b}, static_cast<std::uint32_t>(f)});
    }
  }
  std::sort(edges.begin(), edges.end(),
            [](const EdgeEntry& a, const EdgeEntry& b) { return a.key < b.key; });
  for (std::size_t i = 0; i < edges.size();) {
    std::size_t j = i;
    while (j < edges.size() && edges[j].key == edges[i].key) ++j;
    if (j - i != 2) {
      ++r.open_boundary_edges;
    } else {
      const auto& f1 = boundary[edges[i].face];
      const auto& f2 = boundary[edges[i + 1].face];
      std::uint32_t apex = f2[0];
      for (const std::uint32_t v : f2) {
        if (v != edges[i].key[0] && v != edges[i].key[1]) apex = v;
      }
      // Outward triples have the interior on their negative side... of the tetrahedron's
      // orientation: orient3d(triple, interior vertex) < 0, so a convex boundary keeps every
      // other boundary vertex at orient3d <= 0.
      if (K::orient3d(pts[f1[0]], pts[f1[1]], pts[f1[2]], pts[apex]) > 0) {
        ++r.reflex_boundary_edges;
        near_reflex[edges[i].key[0]] = near_reflex[edges[i].key[1]] = 1;
      }
    }
    i = j;
  }

  // Boundary vertices: convex edges do not make a convex surface (a fan that winds twice round an
  // axis has convex edges), so the surface must be locally convex at every vertex too: every
  // vertex of v's link lies on the inner side of, or on, every boundary face at v. A closed,
  // connected, locally convex surface bounds a convex body (van Heijenoort), which the volume check
  // below then compares with the hull.
  std::vector<std::array<std::uint32_t, 2>> incidence;  // (vertex, boundary face)
  incidence.reserve(3 * boundary.size());
  for (std::size_t f = 0; f < boundary.size(); ++f) {
    for (const std::uint32_t v : boundary[f])
      incidence.push_back({v, static_cast<std::uint32_t>(f)});
  }
  std::sort(incidence.begin(), incidence.end());
  std::vector<std::uint32_t> link;
  for (std::size_t i = 0; i < incidence.size();) {
    std::size_t j = i;
    link.clear();
    while (j < incidence.size() && incidence[j][0] == incidence[i][0]) {
      for (const std::uint32_t w : boundary[incidence[j][1]]) {
        if (w != incidence[i][0]) link.push_back(w);
      }
      ++j;
    }
    std::sort(link.begin(), link.end());
    link.erase(std::unique(link.begin(), link.end()), link.end());
    bool convex = true;
    for (std::size_t k = i; k < j && convex; ++k) {
      const auto& f = boundary[incidence[k][1]];
      for (const std::uint32_t w : link) {
        if (w == f[0] || w == f[1] || w == f[2]) continue;
        if (K::orient3d(pts[f[0]], pts[f[1]], pts[f[2]], pts[w]) > 0) {
          convex = false;
          break;
        }
      }
    }
    if (!convex) {
      ++r.reflex_boundary_vertices;
      near_reflex[incidence[i][0]] = 1;
    }
    i = j;
  }

  // Vertex coverage: every distinct point is a vertex, each duplicate set exactly once.
  std::vector<bool> used(n, false);
  std::size_t vertex_count = 0;
  for (std::size_t i = 0; i < tets.size(); ++i) {
    if (!usable[i]) continue;
    for (const std::uint32_t v : tets[i]) {
      if (!used[v]) ++vertex_count;
      used[v] = true;
    }
  }
  std::vector<std::uint32_t> by_point(n);
  for (std::size_t i = 0; i < n; ++i) by_point[i] = static_cast<std::uint32_t>(i);
  std::sort(by_point.begin(), by_point.end(), [&](std::uint32_t a, std::uint32_t b) {
    return predicates::lexicographically_less(pts[a], pts[b]);
  });
  for (std::size_t i = 0; i < n;) {
    std::size_t j = i;
    int uses = 0;
    while (j < n && pts[by_point[j]] == pts[by_point[i]]) uses += used[by_point[j++]] ? 1 : 0;
    if (uses == 0) ++r.missing_points;
    if (uses > 1) ++r.repeated_duplicates;
    i = j;
  }

  // Euler characteristic of the complex.
  std::vector<std::array<std::uint32_t, 2>> all_edges;
  all_edges.reserve(6 * tets.size());
  for (std::size_t i = 0; i < tets.size(); ++i) {
    if (!usable[i]) continue;
    for (int a = 0; a < 4; ++a) {
      for (int b = a + 1; b < 4; ++b) {
        std::uint32_t u = tets[i][static_cast<std::size_t>(a)];
        std::uint32_t v = tets[i][static_cast<std::size_t>(b)];
        if (u > v) std::swap(u, v);
        all_edges.push_back({u, v});
      }
    }
  }
  std::sort(all_edges.begin(), all_edges.end());
  const auto edge_count = static_cast<std::int64_t>(
      std::unique(all_edges.begin(), all_edges.end()) - all_edges.begin());
  std::int64_t usable_tets = 0;
  for (const bool u : usable) usable_tets += u ? 1 : 0;
  r.euler_characteristic = static_cast<std::int64_t>(vertex_count) - edge_count +
                           static_cast<std::int64_t>(distinct_faces) - usable_tets;

  // Global: positively oriented, locally consistent tetrahedra with a closed boundary cover the
  // hull a constant number of times; equal exact volumes pin that number to one.
  const ExactGrid grid(pts);
  const auto mesh_volume = six_mesh_volume(pts, tets, usable, grid);
  const auto hull_volume = six_hull_volume(pts, grid);
  r.volume_mismatch = mesh_volume == hull_volume ? 0 : 1;
  // Tetrahedra on input points that do not overlap fill at most the hull: more is an exact proof
  // of overlap, whatever the boundary.
  r.volume_excess = mesh_volume > hull_volume ? 1 : 0;
  // Where the boundary is not convex the volumes differ by construction: probe points instead.
  if (r.reflex_boundary_edges > 0 || r.reflex_boundary_vertices > 0) {
    constexpr std::size_t kMaxProbes = std::size_t{1} << 16;
    const detail::ProbeCoverage coverage =
        detail::probe_coverage<K>(pts, tets, positive, near_reflex, kMaxProbes);
    r.probe_points = coverage.probes;
    r.probes_covered_twice = coverage.covered_twice;
    r.probe_check_complete = coverage.complete;
  }
}

}  // namespace

bool ValidationReport::consistent() const {
  return invalid_tetrahedra == 0 && non_positive_orientation == 0 && non_manifold_faces == 0 &&
         inconsistent_faces == 0 && open_boundary_edges == 0 && reflex_boundary_edges == 0 &&
         reflex_boundary_vertices == 0 && missing_points == 0 && repeated_duplicates == 0 &&
         euler_characteristic == 1 && volume_mismatch == 0;
}

// With a convex boundary the volumes must match. A reflex boundary edge or vertex means the union
// of the tetrahedra is not the hull, so the volumes differ by construction; there the global check
// is the probe count: no probe point inside two tetrahedra.
bool ValidationReport::mesh_consistent() const {
  const bool convex = reflex_boundary_edges == 0 && reflex_boundary_vertices == 0;
  return invalid_tetrahedra == 0 && non_positive_orientation == 0 && non_manifold_faces == 0 &&
         inconsistent_faces == 0 && open_boundary_edges == 0 && missing_points == 0 &&
         repeated_duplicates == 0 && euler_characteristic == 1 && volume_excess == 0 &&
         (convex ? volume_mismatch == 0 : probes_covered_twice == 0);
}

bool ValidationReport::valid() const {
  return consistent() && non_delaunay_faces == 0;
}

std::string ValidationReport::json() const {
  nlohmann::ordered_json j;
  j["valid"] = valid();
  j["consistent"] = consistent();
  j["mesh_consistent"] = mesh_consistent();
  j["points"] = points;
  j["tetrahedra"] = tetrahedra;
  j["interior_faces"] = interior_faces;
  j["boundary_faces"] = boundary_faces;
  j["invalid_tetrahedra"] = invalid_tetrahedra;
  j["non_positive_orientation"] = non_positive_orientation;
  j["non_manifold_faces"] = non_manifold_faces;
  j["inconsistent_faces"] = inconsistent_faces;
  j["non_delaunay_faces"] = non_delaunay_faces;
  j["open_boundary_edges"] = open_boundary_edges;
  j["reflex_boundary_edges"] = reflex_boundary_edges;
  j["reflex_boundary_vertices"] = reflex_boundary_vertices;
  j["missing_points"] = missing_points;
  j["repeated_duplicates"] = repeated_duplicates;
  j["euler_characteristic"] = euler_characteristic;
  j["volume_mismatch"] = volume_mismatch;
  j["volume_excess"] = volume_excess;
  j["probe_points"] = probe_points;
  j["probe_check_complete"] = probe_check_complete;
  j["probes_covered_twice"] = probes_covered_twice;
  j["kernel"] = kernel;
  return j.dump(2);
}

const char* to_string(ValidateWith k) {
  return k == ValidateWith::Exact ? "exact" : "adaptive";
}

ValidationReport validate(const std::vector<Point3>& points, const std::vector<Tetrahedron>& tets,
                          ValidateWith kernel) {
  ValidationReport r;
  r.points = points.size();
  r.tetrahedra = tets.size();
  double max_abs = 0.0;
  double min_abs = 0.0;
  bool finite = true;
  for (const Point3& p : points) {
    for (const double c : {p.x, p.y, p.z}) {
      finite = finite && std::isfinite(c);
      const double m = std::fabs(c);
      max_abs = std::max(max_abs, m);
      if (m > 0.0 && (min_abs == 0.0 || m < min_abs)) min_abs = m;
    }
  }
  // Non-finite points are refused by the readers and by triangulate(); here they cannot be judged.
  if (!finite) throw std::invalid_argument("validate: a coordinate is NaN or infinite");
  r.kernel = to_string(kernel);
  if (kernel == ValidateWith::Exact) {
    check<predicates::ExactKernel>(points, tets, r);  // the independent reference
    return r;
  }
  // The adaptive kernel is exact for every finite double (GMP fallback outside the expansion
  // range); the same lossless power-of-two scaling as the engine keeps most calls off that path.
  const RangeScaling scaling = adaptive_range_scaling(max_abs, min_abs);
  if (scaling.lossless) {
    std::vector<Point3> scaled = points;
    for (Point3& p : scaled) {
      p = {std::ldexp(p.x, scaling.exponent), std::ldexp(p.y, scaling.exponent),
           std::ldexp(p.z, scaling.exponent)};
    }
    check<predicates::AdaptiveKernel>(scaled, tets, r);
  } else {
    check<predicates::AdaptiveKernel>(points, tets, r);
  }
  return r;
}

}  // namespace dtlab::engine
