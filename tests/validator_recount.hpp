#pragma once
// An independent recount of the validator's per-tetrahedron and per-face counters, for meshes
// the fast kernel may have got wrong: GMP signs (ExactKernel, no scaling), a map of faces instead
// of the validator's sorted face list, and a geometric side test instead of its permutation
// parities. Tests compare engine::validate()'s counters with it.
#include <algorithm>
#include <array>
#include <cstdint>
#include <map>
#include <utility>
#include <vector>

#include "dtlab/engine/validator.hpp"
#include "dtlab/predicates/kernels.hpp"

namespace dtlab::test {

struct ExactRecount {
  std::uint64_t invalid_tetrahedra = 0;        // vertex id out of range or repeated
  std::uint64_t non_positive_orientation = 0;  // exact orient3d <= 0
  std::uint64_t non_manifold_faces = 0;        // a face of more than two tetrahedra
  std::uint64_t interior_faces = 0;            // a face of exactly two tetrahedra
  std::uint64_t boundary_faces = 0;            // a face of one tetrahedron
  // Decided only when every tetrahedron is positively oriented (then a face's two tetrahedra are
  // consistent exactly when their opposite vertices lie on opposite sides of it, and the insphere
  // test of a face is the same from either side):
  std::uint64_t inconsistent_faces = 0;  // both opposite vertices on the same side of the face
  std::uint64_t non_delaunay_faces = 0;  // opposite vertex strictly inside the circumsphere
};

inline ExactRecount exact_recount(const std::vector<predicates::Point3>& pts,
                                  const std::vector<engine::Tetrahedron>& tets) {
  using K = predicates::ExactKernel;
  ExactRecount r;
  // Sorted face -> (tetrahedron, the vertex opposite the face in it).
  std::map<std::array<std::uint32_t, 3>, std::vector<std::pair<std::size_t, std::uint32_t>>> faces;
  for (std::size_t i = 0; i < tets.size(); ++i) {
    const auto& t = tets[i];
    auto ids = t;
    std::sort(ids.begin(), ids.end());
    if (ids[3] >= pts.size() || std::adjacent_find(ids.begin(), ids.end()) != ids.end()) {
      ++r.invalid_tetrahedra;
      continue;
    }
    if (K::orient3d(pts[t[0]], pts[t[1]], pts[t[2]], pts[t[3]]) <= 0) ++r.non_positive_orientation;
    for (std::size_t f = 0; f < 4; ++f) {
      std::array<std::uint32_t, 3> key{};
      std::size_t k = 0;
      for (std::size_t v = 0; v < 4; ++v) {
        if (v != f) key[k++] = t[v];
      }
      std::sort(key.begin(), key.end());
      faces[key].push_back({i, t[f]});
    }
  }
  for (const auto& [key, owners] : faces) {
    if (owners.size() == 1) ++r.boundary_faces;
    if (owners.size() > 2) ++r.non_manifold_faces;
    if (owners.size() != 2) continue;
    ++r.interior_faces;
    if (r.non_positive_orientation != 0) continue;
    const auto& a = pts[key[0]];
    const auto& b = pts[key[1]];
    const auto& c = pts[key[2]];
    const auto& d = pts[owners[0].second];
    const auto& e = pts[owners[1].second];
    if (K::orient3d(a, b, c, d) * K::orient3d(a, b, c, e) > 0) ++r.inconsistent_faces;
    const auto& t = tets[owners[0].first];
    if (K::insphere(pts[t[0]], pts[t[1]], pts[t[2]], pts[t[3]], e) > 0) ++r.non_delaunay_faces;
  }
  return r;
}

// Whether the validator's counters equal the recount's: the per-tetrahedron and per-face ones
// always, the inconsistent and non-Delaunay faces where the recount decides them (no tetrahedron
// inverted).
inline bool counters_agree(const engine::ValidationReport& report, const ExactRecount& exact) {
  const bool always = report.invalid_tetrahedra == exact.invalid_tetrahedra &&
                      report.non_positive_orientation == exact.non_positive_orientation &&
                      report.non_manifold_faces == exact.non_manifold_faces &&
                      report.interior_faces == exact.interior_faces &&
                      report.boundary_faces == exact.boundary_faces;
  return always && (exact.non_positive_orientation != 0 ||
                    (report.inconsistent_faces == exact.inconsistent_faces &&
                     report.non_delaunay_faces == exact.non_delaunay_faces));
}

}  // namespace dtlab::test
