#include "repair/star_splaying.hpp"

#include <algorithm>
#include <stdexcept>
#include <utility>

#include "dtlab/predicates/kernels.hpp"
#include "support/parallel_ranges.hpp"

namespace dtlab::engine {

using Exact = predicates::AdaptiveKernel;

StarSplayer::StarSplayer(const std::vector<predicates::Point3>& points, const MeshStars& mesh,
                         const std::vector<VertexId>& canonical,
                         const std::array<VertexId, 4>& pool,
                         std::function<void(VertexId, std::vector<VertexId>&)> near)
    : points_(points),
      mesh_(mesh),
      canonical_(canonical),
      pool_(pool),
      near_(std::move(near)),
      slot_(points.size(), -1),
      queued_(points.size(), 0) {}

namespace {

bool collinear(const std::vector<predicates::Point3>& p, VertexId a, VertexId b, VertexId c) {
  return Exact::orient2d(p[a], p[b], p[c], 0) == 0 && Exact::orient2d(p[a], p[b], p[c], 1) == 0 &&
         Exact::orient2d(p[a], p[b], p[c], 2) == 0;
}

// Three of `candidates` that are not coplanar with x, or false.
bool first_triangle(const std::vector<predicates::Point3>& p, VertexId x,
                    const std::vector<VertexId>& candidates, std::array<VertexId, 3>& abc) {
  std::size_t i = 0;
  for (; i < candidates.size() && p[candidates[i]] == p[x]; ++i) {
  }
  if (i == candidates.size()) return false;
  abc[0] = candidates[i];
  std::size_t j = i + 1;
  for (; j < candidates.size() && collinear(p, x, abc[0], candidates[j]); ++j) {
  }
  if (j >= candidates.size()) return false;
  abc[1] = candidates[j];
  for (std::size_t k = j + 1; k < candidates.size(); ++k) {
    if (Exact::orient3d(p[x], p[abc[0]], p[abc[1]], p[candidates[k]]) != 0) {
      abc[2] = candidates[k];
      return true;
    }
  }
  return false;
}

}  // namespace

void StarSplayer::build_star(VertexId x, VertexStar& star, BuildScratch& scratch) const {
  std::vector<Quad>& around = scratch.around;
  mesh_.tetrahedra_of(x, around);
  std::vector<VertexId>& candidates = scratch.candidates;
  candidates.clear();
  for (const Quad& q : around) {
    for (const VertexId y : q) {
      if (y != kInfiniteVertex && canonical_[y] != x) candidates.push_back(canonical_[y]);
    }
  }
  if (candidates.empty() && near_) {
    near_(x, candidates);
    for (VertexId& y : candidates) y = canonical_[y];
  }
  std::sort(candidates.begin(), candidates.end());
  candidates.erase(std::unique(candidates.begin(), candidates.end()), candidates.end());
  std::array<VertexId, 3> abc{};
  if (!first_triangle(points_, x, candidates, abc)) {
    // The mesh's neighbours do not span 3D around x (a broken mesh): the pool does.
    for (const VertexId y : pool_) {
      if (y != x) candidates.push_back(y);
    }
    if (!first_triangle(points_, x, candidates, abc)) {
      throw std::logic_error("star splaying: the pool does not span 3D");
    }
  }
  ++scratch.counts.stars;
  star.start(points_, x, abc[0], abc[1], abc[2]);
  for (const VertexId y : candidates) {
    if (y == x) continue;
    ++scratch.counts.offers;
    scratch.removed.clear();
    if (star.offer(points_, y, scratch.removed, scratch.star)) ++scratch.counts.changes;
  }
}

namespace {

void add_counts(SplayCounts& to, SplayCounts& from) {
  to.stars += from.stars;
  to.offers += from.offers;
  to.changes += from.changes;
  from = {};
}

}  // namespace

bool StarSplayer::claim_slot(VertexId x) {
  if (active(x) || canonical_[x] != x) return false;  // a duplicate is never a vertex of the result
  slot_[x] = static_cast<int>(stars_.size());
  stars_.emplace_back();
  active_.push_back(x);
  return true;
}

void StarSplayer::activate(VertexId x) {
  if (!claim_slot(x)) return;
  build_star(x, star_of(x), build_);
  add_counts(counts_, build_.counts);
  enqueue(x);
}

void StarSplayer::activate_all(const std::vector<VertexId>& xs, int threads) {
  // Slots first, in order (stars_ does not grow while the threads write into it).
  const std::size_t first = stars_.size();
  for (const VertexId x : xs) claim_slot(x);
  const std::size_t built = stars_.size() - first;
  const int parts = std::max(threads, 1);
  std::vector<BuildScratch> scratch(static_cast<std::size_t>(parts));
  // A star takes tens of microseconds: threads pay off from a few dozen stars on.
  constexpr std::size_t kMinimumStars = 64;
  in_parallel_ranges(
      built, parts,
      [&](std::size_t begin, std::size_t end, std::size_t part) {
        for (std::size_t i = begin; i < end; ++i) {
          const VertexId x = active_[first + i];
          build_star(x, stars_[first + i], scratch[part]);
        }
      },
      kMinimumStars);
  for (BuildScratch& mine : scratch) add_counts(counts_, mine.counts);
  for (std::size_t i = first; i < stars_.size(); ++i) enqueue(active_[i]);
}

void StarSplayer::enqueue(VertexId x) {
  if (queued_[x] != 0) return;
  queued_[x] = 1;
  queue_.push_back(x);
}

void StarSplayer::offer(VertexId to, VertexId w) {
  if (w == kInfiniteVertex) return;
  w = canonical_[w];
  if (w == to) return;
  ++counts_.offers;
  removed_.clear();
  if (!star_of(to).offer(points_, w, removed_, scratch_)) return;
  ++counts_.changes;
  enqueue(to);
  // Stars that still hold a tetrahedron `to` dropped now disagree with it.
  for (const Quad& q : removed_) {
    for (const VertexId y : q) {
      if (y != to && y != kInfiniteVertex && active(y)) enqueue(y);
    }
  }
}

void StarSplayer::check(VertexId v) {
  std::vector<Quad>& quads = check_quads_;  // a copy: offers change the star
  quads = star_of(v).tetrahedra();
  // The mesh's tetrahedra at v, sorted: whether the mesh at another vertex u of one of v's
  // tetrahedra holds it is whether the mesh at v does (the tetrahedron contains both), so v's
  // list answers for every u without reading u's.
  std::vector<Quad>& around = check_around_;
  mesh_.tetrahedra_of(v, around);
  std::vector<Quad>& mesh_keys = check_keys_;
  mesh_keys.resize(around.size());
  std::transform(around.begin(), around.end(), mesh_keys.begin(), sorted_quad);
  auto mesh_has = [&](const Quad& key) {
    return std::any_of(mesh_keys.begin(), mesh_keys.end(),
                       [&](const Quad& m) { return same_quad(m, key); });
  };
  std::vector<VertexId>& link = check_link_;
  for (const Quad& q : quads) {
    const Quad key = sorted_quad(q);
    if (!star_of(v).has(key)) continue;  // left v's star meanwhile
    for (const VertexId u : q) {
      if (u == v || u == kInfiniteVertex) continue;
      if (!active(u)) {
        if (mesh_has(key)) continue;  // the mesh at u agrees
        activate(u);
      }
      if (star_of(u).has(key)) continue;
      // u does not have q: offer u the other vertices of q...
      for (const VertexId x : q) {
        if (x != u) offer(u, x);
      }
      if (star_of(u).has(key)) continue;
      // ...and if u still refuses it, the tetrahedron of u's star through which the direction
      // of q leaves u has a vertex inside q's circumsphere (both are in u's star over a set that
      // holds q's vertices): offering u's whole link to v removes q from v's star.
      star_of(u).link_vertices(link);
      for (const VertexId x : link) offer(v, x);
      if (star_of(v).has(key)) {
        throw std::logic_error("star splaying: two stars disagree after enforcement");
      }
      break;  // q left v's star
    }
  }
  // The seam: the mesh's tetrahedra at v that reach an inactive vertex must be in v's star, or
  // that vertex's star (the mesh's) disagrees with v's: activate it.
  for (const Quad& s : around) {
    bool reaches_inactive = false;
    for (const VertexId y : s) reaches_inactive |= y != kInfiniteVertex && !active(y);
    if (!reaches_inactive || star_of(v).has(sorted_quad(s))) continue;
    for (const VertexId y : s) {
      if (y != kInfiniteVertex && !active(y)) activate(y);
    }
  }
}

void StarSplayer::run() {
  while (!queue_.empty()) {
    const VertexId v = queue_.front();
    queue_.pop_front();
    queued_[v] = 0;
    check(v);
  }
}

}  // namespace dtlab::engine
