#include "star_pieces.hpp"

#include <gmpxx.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numeric>

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

// The vertices in a uniform grid of cells, for nearest-vertex searches in growing shells.
class VertexGrid {
 public:
  VertexGrid(const std::vector<Point3>& points, const std::vector<VertexId>& vertices)
      : points_(points) {
    lo_ = hi_ = points[vertices.front()];
    for (const VertexId v : vertices) {
      const Point3& p = points[v];
      lo_ = {std::min(lo_.x, p.x), std::min(lo_.y, p.y), std::min(lo_.z, p.z)};
      hi_ = {std::max(hi_.x, p.x), std::max(hi_.y, p.y), std::max(hi_.z, p.z)};
    }
    cells_ =
        std::clamp(static_cast<int>(std::cbrt(static_cast<double>(vertices.size()) / 2)), 1, 128);
    // The narrowest cell along an axis the points spread over: a point r shells away from a
    // query's cell is at least (r - 1) such widths away (one width spent on rounding).
    min_width_ = std::numeric_limits<double>::infinity();
    for (const double span : {hi_.x - lo_.x, hi_.y - lo_.y, hi_.z - lo_.z}) {
      if (span > 0 && std::isfinite(span)) min_width_ = std::min(min_width_, span / cells_);
    }
    first_.assign(static_cast<std::size_t>(cells_) * cells_ * cells_ + 1, 0);
    for (const VertexId v : vertices) ++first_[cell_id(cell(points[v])) + 1];
    std::partial_sum(first_.begin(), first_.end(), first_.begin());
    members_.resize(vertices.size());
    std::vector<std::uint32_t> fill(first_.begin(), first_.end() - 1);
    for (const VertexId v : vertices) members_[fill[cell_id(cell(points[v]))]++] = v;
  }

  // The nearest vertex to x whose piece differs from x's, or none.
  template <class PieceOf>
  Pair nearest_across(VertexId x, const PieceOf& piece_of) const {
    const std::array<int, 3> c = cell(points_[x]);
    const VertexId mine = piece_of(x);
    Pair best;
    for (int r = 0; r < cells_; ++r) {
      for (int i = std::max(c[0] - r, 0); i <= std::min(c[0] + r, cells_ - 1); ++i) {
        for (int j = std::max(c[1] - r, 0); j <= std::min(c[1] + r, cells_ - 1); ++j) {
          for (int k = std::max(c[2] - r, 0); k <= std::min(c[2] + r, cells_ - 1); ++k) {
            if (std::max({std::abs(i - c[0]), std::abs(j - c[1]), std::abs(k - c[2])}) != r) {
              continue;
            }
            const std::size_t id = cell_id({i, j, k});
            for (std::uint32_t m = first_[id]; m < first_[id + 1]; ++m) {
              const VertexId y = members_[m];
              if (piece_of(y) == mine) continue;
              const Pair candidate{x, y, squared_distance(points_[x], points_[y])};
              if (nearer(points_, candidate, best)) best = candidate;
            }
          }
        }
      }
      // Every vertex of the next shells is at least r widths away, r - 1 to allow for the
      // rounding of the cells' bounds: stop when the best is nearer.
      const double reach = std::max(r - 1, 0) * min_width_;
      if (best.inside != kInfiniteVertex && best.approximate * (1 + 0x1p-30) < reach * reach) break;
    }
    return best;
  }

 private:
  [[nodiscard]] std::array<int, 3> cell(const Point3& p) const {
    auto axis = [&](double x, double l, double h) {
      const double span = h - l;
      if (!(span > 0) || !std::isfinite(span)) return 0;
      const double t = (x - l) / span * cells_;
      return t <= 0 ? 0 : t >= cells_ ? cells_ - 1 : static_cast<int>(t);
    };
    return {axis(p.x, lo_.x, hi_.x), axis(p.y, lo_.y, hi_.y), axis(p.z, lo_.z, hi_.z)};
  }
  [[nodiscard]] std::size_t cell_id(const std::array<int, 3>& c) const {
    const auto n = static_cast<std::size_t>(cells_);
    return (static_cast<std::size_t>(c[0]) * n + static_cast<std::size_t>(c[1])) * n +
           static_cast<std::size_t>(c[2]);
  }

  const std::vector<Point3>& points_;
  Point3 lo_{};
  Point3 hi_{};
  int cells_ = 1;
  double min_width_ = 0.0;
  std::vector<std::uint32_t> first_;
  std::vector<VertexId> members_;
};

}  // namespace

std::vector<std::pair<VertexId, VertexId>> bridges_between_pieces(
    const std::vector<Point3>& points, const std::vector<VertexId>& vertices,
    const StarSplayer& splayer) {
  Pieces pieces(points.size());
  for (const VertexId v : vertices) {
    for (const Quad& q : splayer.star(v).tetrahedra()) {
      for (const VertexId u : q) {
        if (u != kInfiniteVertex) pieces.join(v, u);
      }
    }
  }
  std::vector<VertexId> piece(points.size(), kInfiniteVertex);
  std::vector<std::size_t> size(points.size(), 0);
  for (const VertexId v : vertices) ++size[piece[v] = pieces.find(v)];
  VertexId largest = piece[vertices.front()];
  for (const VertexId v : vertices) {
    if (size[piece[v]] > size[largest]) largest = piece[v];
  }
  if (size[largest] == vertices.size()) return {};
  // Each smaller piece's closest pair across: the nearest vertex of another piece from each of
  // its vertices, the nearest of those. The largest piece needs no search of its own: every
  // other piece's bridge reaches another piece, so each round at least halves their number.
  const VertexGrid grid(points, vertices);
  std::vector<Pair> best(points.size());
  for (const VertexId v : vertices) {
    if (piece[v] == largest) continue;
    const Pair p = grid.nearest_across(v, [&](VertexId y) { return piece[y]; });
    if (nearer(points, p, best[piece[v]])) best[piece[v]] = p;
  }
  std::vector<std::pair<VertexId, VertexId>> bridges;
  for (const VertexId v : vertices) {
    if (piece[v] == v && v != largest) bridges.emplace_back(best[v].inside, best[v].outside);
  }
  return bridges;
}

}  // namespace dtlab::engine
