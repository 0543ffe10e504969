#pragma once
// The validator's global check where the boundary is not convex, so that the hull's volume cannot
// decide: probe points, each strictly inside the tetrahedron it was made from, must lie in no other
// tetrahedron. Positively oriented tetrahedra with consistent faces cover each point as many times
// as their boundary winds around it; a mesh that overlaps itself (e.g. winds twice round an axis)
// puts interior points of its own tetrahedra in two of them. Every test is an exact orient3d.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <vector>

#include "dtlab/engine/tetrahedron.hpp"
#include "dtlab/predicates/point.hpp"

namespace dtlab::engine::detail {

struct ProbeCoverage {
  std::uint64_t probes = 0;         // probes tested
  std::uint64_t covered_twice = 0;  // probes inside (or on) a second tetrahedron
  bool complete = true;             // false: the work budget ran out (long thin tetrahedra)
};

// The barycentric weights of the probes made from one tetrahedron: the centroid, and points
// pulled towards each vertex and each edge (overlaps start at vertices and edges of the boundary).
inline const std::vector<std::array<double, 4>>& probe_weights(bool all) {
  static const std::vector<std::array<double, 4>> centroid{{0.25, 0.25, 0.25, 0.25}};
  static const std::vector<std::array<double, 4>> every = [] {
    std::vector<std::array<double, 4>> w{{0.25, 0.25, 0.25, 0.25}};
    for (std::size_t v = 0; v < 4; ++v) {
      std::array<double, 4> near_vertex{0.125, 0.125, 0.125, 0.125};
      near_vertex[v] = 0.625;
      w.push_back(near_vertex);
    }
    for (std::size_t a = 0; a < 4; ++a) {
      for (std::size_t b = a + 1; b < 4; ++b) {
        std::array<double, 4> near_edge{0.0625, 0.0625, 0.0625, 0.0625};
        near_edge[a] = near_edge[b] = 0.4375;
        w.push_back(near_edge);
      }
    }
    return w;
  }();
  return all ? every : centroid;
}

// `usable[i]`: tetrahedron i has valid, distinct vertex ids and is positively oriented.
// `near_reflex[v]`: v is a vertex of a reflex boundary edge or a reflex boundary vertex; the
// tetrahedra at those vertices get every probe, the others (a stride sample up to `max_probes`)
// their centroid.
template <class K>
ProbeCoverage probe_coverage(const std::vector<predicates::Point3>& pts,
                             const std::vector<Tetrahedron>& tets, const std::vector<char>& usable,
                             const std::vector<char>& near_reflex, std::size_t max_probes) {
  using predicates::Point3;
  auto strictly_inside = [&](const Tetrahedron& t, const Point3& q) {
    const Point3 &a = pts[t[0]], &b = pts[t[1]], &c = pts[t[2]], &d = pts[t[3]];
    return K::orient3d(q, b, c, d) > 0 && K::orient3d(a, q, c, d) > 0 &&
           K::orient3d(a, b, q, d) > 0 && K::orient3d(a, b, c, q) > 0;
  };
  struct Probe {
    Point3 at;
    std::uint32_t source;
    std::uint32_t count = 1;  // the source tetrahedron
  };
  std::vector<Probe> probes;
  auto add_probes = [&](std::size_t i, bool all) {
    const Tetrahedron& t = tets[i];
    for (const auto& w : probe_weights(all)) {
      if (probes.size() >= max_probes) return;
      // Weights are powers of two or their sums: each product is exact unless it underflows; the
      // sum rounds, and the exact test below keeps only probes strictly inside their source.
      auto mix = [&](auto coordinate) {
        double s = 0.0;
        for (std::size_t k = 0; k < 4; ++k) s += w[k] * coordinate(pts[t[k]]);
        return s;
      };
      const Point3 q{mix([](const Point3& p) { return p.x; }),
                     mix([](const Point3& p) { return p.y; }),
                     mix([](const Point3& p) { return p.z; })};
      if (std::isfinite(q.x) && std::isfinite(q.y) && std::isfinite(q.z) && strictly_inside(t, q)) {
        probes.push_back({q, static_cast<std::uint32_t>(i)});
      }
    }
  };
  std::vector<char> taken(tets.size(), 0);
  for (std::size_t i = 0; i < tets.size() && probes.size() < max_probes; ++i) {
    if (usable[i] == 0) continue;
    const Tetrahedron& t = tets[i];
    if (near_reflex[t[0]] != 0 || near_reflex[t[1]] != 0 || near_reflex[t[2]] != 0 ||
        near_reflex[t[3]] != 0) {
      add_probes(i, true);
      taken[i] = 1;
    }
  }
  const std::size_t room = max_probes > probes.size() ? max_probes - probes.size() : 0;
  // Rounded up, so that the sample spreads over every index range of the mesh.
  const std::size_t stride =
      room == 0 ? tets.size() + 1 : std::max<std::size_t>(1, (tets.size() + room - 1) / room);
  for (std::size_t i = 0; i < tets.size() && probes.size() < max_probes; i += stride) {
    if (usable[i] != 0 && taken[i] == 0) add_probes(i, false);
  }
  ProbeCoverage result;
  if (probes.empty()) return result;

  // Probes bucketed in a uniform grid over their bounding box. cell() is monotone in x (rounded
  // subtraction and multiplication are), so a probe inside a tetrahedron's box has its cell
  // inside the box's cell range.
  Point3 lo = probes[0].at;
  Point3 hi = probes[0].at;
  for (const Probe& p : probes) {
    lo = {std::min(lo.x, p.at.x), std::min(lo.y, p.at.y), std::min(lo.z, p.at.z)};
    hi = {std::max(hi.x, p.at.x), std::max(hi.y, p.at.y), std::max(hi.z, p.at.z)};
  }
  const int g = std::clamp(static_cast<int>(std::cbrt(static_cast<double>(probes.size()))), 1, 64);
  auto scale = [&](double low, double high) {
    const double span = high - low;
    return span > 0 && std::isfinite(span) ? g / span : 0.0;
  };
  const std::array<double, 3> low{lo.x, lo.y, lo.z};
  const std::array<double, 3> inv{scale(lo.x, hi.x), scale(lo.y, hi.y), scale(lo.z, hi.z)};
  auto cell = [&](double x, std::size_t axis) {
    const double c = (x - low[axis]) * inv[axis];
    if (!(c > 0)) return 0;
    return c >= g ? g - 1 : static_cast<int>(c);
  };
  auto cell_id = [&](const Point3& p) {
    return (cell(p.x, 0) * g + cell(p.y, 1)) * g + cell(p.z, 2);
  };
  std::vector<std::uint32_t> order(probes.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = static_cast<std::uint32_t>(i);
  std::sort(order.begin(), order.end(), [&](std::uint32_t a, std::uint32_t b) {
    return cell_id(probes[a].at) < cell_id(probes[b].at);
  });
  std::vector<std::uint32_t> first(static_cast<std::size_t>(g) * g * g + 1, 0);
  for (const std::uint32_t p : order) ++first[static_cast<std::size_t>(cell_id(probes[p].at)) + 1];
  for (std::size_t c = 1; c < first.size(); ++c) first[c] += first[c - 1];

  // Cell visits and exact tests are bounded: long thin tetrahedra (fans on sphere data) cross
  // many cells. Past the budget the count stops and says it is incomplete.
  const std::uint64_t budget = std::uint64_t{1} << 28;
  std::uint64_t work = 0;
  // Tests tetrahedron i against the probes in its box; false when the budget ran out.
  auto scan = [&](std::size_t i) {
    const Tetrahedron& t = tets[i];
    Point3 tlo = pts[t[0]];
    Point3 thi = pts[t[0]];
    for (std::size_t k = 1; k < 4; ++k) {
      const Point3& p = pts[t[k]];
      tlo = {std::min(tlo.x, p.x), std::min(tlo.y, p.y), std::min(tlo.z, p.z)};
      thi = {std::max(thi.x, p.x), std::max(thi.y, p.y), std::max(thi.z, p.z)};
    }
    const Point3 &a = pts[t[0]], &b = pts[t[1]], &c = pts[t[2]], &d = pts[t[3]];
    for (int cx = cell(tlo.x, 0); cx <= cell(thi.x, 0); ++cx) {
      for (int cy = cell(tlo.y, 1); cy <= cell(thi.y, 1); ++cy) {
        for (int cz = cell(tlo.z, 2); cz <= cell(thi.z, 2); ++cz) {
          const auto id = static_cast<std::size_t>((cx * g + cy) * g + cz);
          if (++work > budget) return false;
          for (std::uint32_t k = first[id]; k < first[id + 1]; ++k) {
            Probe& probe = probes[order[k]];
            const Point3& q = probe.at;
            if (probe.source == i || q.x < tlo.x || q.x > thi.x || q.y < tlo.y || q.y > thi.y ||
                q.z < tlo.z || q.z > thi.z) {
              continue;
            }
            if (++work > budget) return false;
            // The probe is strictly inside its source; inside or on the boundary of this
            // full-dimensional tetrahedron too, the two interiors overlap.
            if (K::orient3d(q, b, c, d) >= 0 && K::orient3d(a, q, c, d) >= 0 &&
                K::orient3d(a, b, q, d) >= 0 && K::orient3d(a, b, c, q) >= 0) {
              ++probe.count;
            }
          }
        }
      }
    }
    return true;
  };
  for (std::size_t i = 0; i < tets.size() && result.complete; ++i) {
    if (usable[i] != 0) result.complete = scan(i);
  }
  for (const Probe& p : probes) {
    ++result.probes;
    if (p.count >= 2) ++result.covered_twice;
  }
  return result;
}

}  // namespace dtlab::engine::detail
