#include "repair/star_pieces.hpp"

#include <gmpxx.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numeric>

#include "repair/vertex_grid.hpp"

namespace dtlab::engine {
namespace {

using predicates::Point3;

// Disjoint sets over vertex ids, with path halving.
class Pieces {
 public:
  explicit Pieces(std::size_t n) : parent_(n) { std::iota(parent_.begin(), parent_.end(), 0U); }
  VertexId find(VertexId v) {
    while (parent_[v] != v) {
      parent_[v] = parent_[parent_[v]];
      v = parent_[v];
    }
    return v;
  }
  void join(VertexId a, VertexId b) {
    a = find(a);
    b = find(b);
    if (a != b) parent_[std::max(a, b)] = std::min(a, b);
  }

 private:
  std::vector<VertexId> parent_;
};

double squared_distance(const Point3& a, const Point3& b) {
  const double dx = a.x - b.x;
  const double dy = a.y - b.y;
  const double dz = a.z - b.z;
  return dx * dx + dy * dy + dz * dz;
}

mpq_class exact_squared_distance(const Point3& a, const Point3& b) {
  const mpq_class dx = mpq_class(a.x) - mpq_class(b.x);
  const mpq_class dy = mpq_class(a.y) - mpq_class(b.y);
  const mpq_class dz = mpq_class(a.z) - mpq_class(b.z);
  return dx * dx + dy * dy + dz * dz;
}

// A pair and its squared distance in floating point (for the search's pruning only).
struct Pair {
  VertexId inside = kInfiniteVertex;
  VertexId outside = kInfiniteVertex;
  double approximate = std::numeric_limits<double>::infinity();
};

// Whether pair p is nearer than pair q: exact squared distances (each rounded one is within a
// few units in the last place of the true value, so a relative gap of 2^-40 decides in floating
// point where nothing overflowed or underflowed; GMP decides the rest), ties broken by the ids.
bool nearer(const std::vector<Point3>& points, const Pair& p, const Pair& q) {
  if (q.inside == kInfiniteVertex) return p.inside != kInfiniteVertex;
  if (p.inside == kInfiniteVertex) return false;
  const double a = p.approximate;
  const double b = q.approximate;
  constexpr double kGap = 0x1p-40;
  constexpr double kSafe = 0x1p-900;  // far above the subnormals, where squares lose bits
  if (std::isfinite(a) && std::isfinite(b) && a > kSafe && b > kSafe) {
    if (a < b * (1 - kGap)) return true;
    if (b < a * (1 - kGap)) return false;
  }
  const int order = cmp(exact_squared_distance(points[p.inside], points[p.outside]),
                        exact_squared_distance(points[q.inside], points[q.outside]));
  if (order != 0) return order < 0;
  return std::pair(p.inside, p.outside) < std::pair(q.inside, q.outside);
}

// The nearest vertex to x whose piece differs from x's among the grid's shells around x's cell,
// searched until nothing in the shells beyond can be nearer than the better of what was found and
// `bound` (x's piece's best pair so far, or none). So the result is x's nearest across wherever
// that beats `bound`; otherwise it may be none or a farther one, which the caller, keeping the
// piece's best, discards. With the bound, only the vertices near the piece's border search far.
Pair nearest_across(const std::vector<Point3>& points, const VertexGrid& grid,
                    const std::vector<VertexId>& piece, VertexId x, const Pair& bound) {
  const std::array<int, 3> c = grid.cell(points[x]);
  Pair best;
  for (int r = 0; r < grid.cells(); ++r) {
    grid.for_shell(c, r, [&](VertexId y) {
      if (piece[y] == piece[x]) return;
      const Pair candidate{x, y, squared_distance(points[x], points[y])};
      if (nearer(points, candidate, best)) best = candidate;
    });
    // Every vertex of the next shells is at least r widths away, r - 1 to allow for the rounding
    // of the cells' bounds. Where reach^2 is far above the subnormals, a squared distance below
    // it (with a margin for its rounding) is nearer than all of them.
    const double reach = std::max(r - 1, 0) * grid.min_width();
    const double limit = std::min(best.approximate, bound.approximate);
    if (reach * reach > 0x1p-900 && limit * (1 + 0x1p-30) < reach * reach) break;
  }
  return best;
}

}  // namespace

std::vector<VertexId> pieces_of_stars(std::size_t point_count,
                                      const std::vector<VertexId>& vertices,
                                      const StarSplayer& splayer) {
  Pieces pieces(point_count);
  for (const VertexId v : vertices) {
    for (const Quad& q : splayer.star(v).tetrahedra()) {
      for (const VertexId u : q) {
        if (u != kInfiniteVertex) pieces.join(v, u);
      }
    }
  }
  std::vector<VertexId> piece(point_count, kInfiniteVertex);
  for (const VertexId v : vertices) piece[v] = pieces.find(v);
  return piece;
}

std::vector<std::pair<VertexId, VertexId>> closest_pairs_across(
    const std::vector<Point3>& points, const std::vector<VertexId>& vertices,
    const std::vector<VertexId>& piece) {
  std::vector<std::size_t> size(points.size(), 0);
  for (const VertexId v : vertices) ++size[piece[v]];
  VertexId largest = piece[vertices.front()];
  for (const VertexId v : vertices) {
    if (size[piece[v]] > size[largest] || (size[piece[v]] == size[largest] && piece[v] < largest)) {
      largest = piece[v];
    }
  }
  if (size[largest] == vertices.size()) return {};
  // Each smaller piece's closest pair across: the nearest vertex of another piece from each of
  // its vertices, the nearest of those. The largest piece needs no search of its own: every
  // other piece's pair reaches another piece.
  const VertexGrid grid(points, vertices);
  std::vector<Pair> best(points.size());
  for (const VertexId v : vertices) {
    if (piece[v] == largest) continue;
    const Pair p = nearest_across(points, grid, piece, v, best[piece[v]]);
    if (nearer(points, p, best[piece[v]])) best[piece[v]] = p;
  }
  std::vector<std::pair<VertexId, VertexId>> bridges;
  for (const VertexId v : vertices) {
    if (piece[v] == v && v != largest) bridges.emplace_back(best[v].inside, best[v].outside);
  }
  return bridges;
}

}  // namespace dtlab::engine
