#pragma once
// The validator's checks of the boundary (validator.cpp): the outward-oriented boundary faces,
// each boundary edge on exactly two of them and convex, and the surface locally convex at every
// vertex. Flat edges are decided as the engine's infinite tetrahedra decide them (perturbed).
#include <algorithm>
#include <array>
#include <cstdint>
#include <vector>

#include "dtlab/engine/validator.hpp"
#include "dtlab/predicates/perturbation.hpp"

namespace dtlab::engine::detail {

using Triangle = std::array<std::uint32_t, 3>;

// Boundary edges: each must be on exactly two boundary faces, and there convex. `near_reflex`
// gets the vertices of reflex edges; `list_violations`: the rejected faces' vertices go to the
// report.
template <class K>
void check_boundary_edges(const std::vector<predicates::Point3>& pts,
                          const std::vector<Triangle>& boundary, bool list_violations,
                          ValidationReport& r, std::vector<char>& near_reflex) {
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
      const int side = K::orient3d(pts[f1[0]], pts[f1[1]], pts[f1[2]], pts[apex]);
      // A flat edge: the apex against the vertex at infinity over f1 (beyond f1, on the outward
      // triple's positive side), as the engine's infinite tetrahedra test it.
      bool rejected = side > 0;
      if (side == 0) {
        ++r.flat_boundary_edges;
        if (predicates::infinite_insphere_perturbed<K>(pts[f1[0]], pts[f1[1]], pts[f1[2]],
                                                       pts[apex]) > 0) {
          ++r.flat_boundary_edges_against_perturbation;
          rejected = true;
        }
      }
      if (side > 0) {
        ++r.reflex_boundary_edges;
        near_reflex[edges[i].key[0]] = near_reflex[edges[i].key[1]] = 1;
      }
      if (rejected) {  // the face between the infinite tetrahedra over f1 and f2
        ++r.perturbed_violations;
        if (list_violations) {
          std::vector<std::uint32_t>& all = r.perturbed_violation_vertices;
          all.insert(all.end(), f1.begin(), f1.end());
          all.insert(all.end(), f2.begin(), f2.end());
        }
      }
    }
    i = j;
  }
}

template <class K>
void check_boundary_vertices(const std::vector<predicates::Point3>& pts,
                             const std::vector<Triangle>& boundary, ValidationReport& r,
                             std::vector<char>& near_reflex) {
  // Boundary vertices: convex edges do not make a convex surface (a fan that winds twice round an
  // axis has convex edges), so the surface must be locally convex at every vertex too: every
  // vertex of v's link lies on the inner side of, or on, every boundary face at v. A closed,
  // connected, locally convex surface bounds a convex body (van Heijenoort), which the volume
  // check below then compares with the hull.
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
}

}  // namespace dtlab::engine::detail
