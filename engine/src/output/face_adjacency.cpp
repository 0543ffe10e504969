// Face adjacency of a tetrahedron list (dtlab/engine/face_adjacency.hpp): every face is filed
// under its smallest vertex (a counting sort into one array), then each vertex's few faces are
// sorted by their other two vertices, where the two copies of an interior face meet. Linear in
// the tetrahedra apart from those small sorts, with no hash table.
#include "dtlab/engine/face_adjacency.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "dtlab/predicates/kernels.hpp"

namespace dtlab::engine {
namespace {

// The face opposite vertex i, in the order that faces out of a positively oriented tetrahedron:
// (j, k, l, i) is an odd permutation of (0, 1, 2, 3), so orient3d(v_j, v_k, v_l, v_i) < 0: v_i lies
// on the side of the face away from which (b - a) x (c - a) points (kernels.hpp's convention).
constexpr std::array<std::array<int, 3>, 4> kOutwardFace{
    {{1, 2, 3}, {0, 3, 2}, {0, 1, 3}, {0, 2, 1}}};

struct FiledFace {
  std::uint32_t second;  // the face's middle vertex id
  std::uint32_t third;   // its largest
  std::uint32_t slot;    // tetrahedron * 4 + the opposite vertex's position
  bool operator<(const FiledFace& o) const {
    return second != o.second ? second < o.second
           : third != o.third ? third < o.third
                              : slot < o.slot;
  }
};

std::array<std::uint32_t, 3> sorted_face(const Tetrahedron& t, int opposite) {
  std::array<std::uint32_t, 3> f{};
  int k = 0;
  for (int j = 0; j < 4; ++j) {
    if (j != opposite) f[static_cast<std::size_t>(k++)] = t[static_cast<std::size_t>(j)];
  }
  std::sort(f.begin(), f.end());
  return f;
}

}  // namespace

FaceAdjacency face_adjacency(const std::vector<Tetrahedron>& tets, std::size_t point_count) {
  if (tets.size() > static_cast<std::size_t>(std::numeric_limits<std::int32_t>::max() / 4)) {
    throw std::invalid_argument("too many tetrahedra for 32-bit neighbour ids");
  }
  for (const Tetrahedron& t : tets) {
    for (const std::uint32_t v : t) {
      if (v >= point_count) {
        throw std::invalid_argument("vertex id " + std::to_string(v) + " is not below the " +
                                    std::to_string(point_count) + " points");
      }
    }
  }
  // Counting sort of the faces by their smallest vertex.
  std::vector<std::size_t> begin(point_count + 1, 0);
  for (const Tetrahedron& t : tets) {
    for (int i = 0; i < 4; ++i) ++begin[sorted_face(t, i)[0] + 1];
  }
  for (std::size_t v = 0; v < point_count; ++v) begin[v + 1] += begin[v];
  std::vector<FiledFace> filed(tets.size() * 4);
  std::vector<std::size_t> next(begin.begin(), begin.end() - 1);
  for (std::size_t t = 0; t < tets.size(); ++t) {
    for (int i = 0; i < 4; ++i) {
      const auto f = sorted_face(tets[t], i);
      filed[next[f[0]]++] = {f[1], f[2],
                             static_cast<std::uint32_t>(t * 4 + static_cast<std::size_t>(i))};
    }
  }

  FaceAdjacency adjacency;
  adjacency.neighbors.assign(tets.size(), {-1, -1, -1, -1});
  std::vector<std::uint32_t> boundary_slots;
  for (std::size_t v = 0; v < point_count; ++v) {
    const auto first = filed.begin() + static_cast<std::ptrdiff_t>(begin[v]);
    const auto last = filed.begin() + static_cast<std::ptrdiff_t>(begin[v + 1]);
    std::sort(first, last);
    for (auto it = first; it != last;) {
      auto same = it + 1;
      while (same != last && same->second == it->second && same->third == it->third) ++same;
      const auto copies = same - it;
      if (copies > 2) {
        throw std::invalid_argument("the face (" + std::to_string(v) + ", " +
                                    std::to_string(it->second) + ", " + std::to_string(it->third) +
                                    ") is on " + std::to_string(copies) + " tetrahedra");
      }
      if (copies == 2) {
        const std::uint32_t a = it->slot;
        const std::uint32_t b = (it + 1)->slot;
        adjacency.neighbors[a / 4][a % 4] = static_cast<std::int32_t>(b / 4);
        adjacency.neighbors[b / 4][b % 4] = static_cast<std::int32_t>(a / 4);
      } else {
        boundary_slots.push_back(it->slot);
      }
      it = same;
    }
  }
  std::sort(boundary_slots.begin(), boundary_slots.end());
  adjacency.boundary_faces.reserve(boundary_slots.size());
  adjacency.boundary_face_tetrahedra.reserve(boundary_slots.size());
  for (const std::uint32_t slot : boundary_slots) {
    const Tetrahedron& t = tets[slot / 4];
    const auto& corners = kOutwardFace[slot % 4];
    adjacency.boundary_faces.push_back({t[static_cast<std::size_t>(corners[0])],
                                        t[static_cast<std::size_t>(corners[1])],
                                        t[static_cast<std::size_t>(corners[2])]});
    adjacency.boundary_face_tetrahedra.push_back(slot / 4);
  }
  return adjacency;
}

std::uint64_t orient_positively(const std::vector<predicates::Point3>& points,
                                std::vector<Tetrahedron>& tets) {
  for (const predicates::Point3& p : points) {
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z)) {
      throw std::invalid_argument("input has a NaN or infinite coordinate");
    }
  }
  std::uint64_t turned = 0;
  for (Tetrahedron& t : tets) {
    if (t[0] >= points.size() || t[1] >= points.size() || t[2] >= points.size() ||
        t[3] >= points.size()) {
      continue;  // the validator reports it as an invalid tetrahedron
    }
    if (predicates::AdaptiveKernel::orient3d(points[t[0]], points[t[1]], points[t[2]],
                                             points[t[3]]) < 0) {
      std::swap(t[2], t[3]);
      ++turned;
    }
  }
  return turned;
}

}  // namespace dtlab::engine
