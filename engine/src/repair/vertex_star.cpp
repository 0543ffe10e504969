#include "repair/vertex_star.hpp"

#include <algorithm>
#include <stdexcept>

#include "dtlab/predicates/kernels.hpp"

namespace dtlab::engine {

using Exact = predicates::AdaptiveKernel;  // exact for every finite double

void VertexStar::start(const std::vector<predicates::Point3>& points, VertexId v, VertexId a,
                       VertexId b, VertexId c) {
  const int o = Exact::orient3d(points[v], points[a], points[b], points[c]);
  if (o == 0) throw std::logic_error("star splaying: a flat first tetrahedron");
  if (o < 0) std::swap(a, b);
  center_ = v;
  const Quad first{v, a, b, c};
  quads_ = {first};
  // The infinite tetrahedra on the faces through v (faces 1-3; kFaceVertex leaves the opposite
  // vertex on the negative side, so the vertex at infinity on the positive one).
  for (std::size_t f = 1; f < 4; ++f) {
    const auto& fv = kFaceVertex[f];
    quads_.push_back({first[static_cast<std::size_t>(fv[0])],
                      first[static_cast<std::size_t>(fv[1])],
                      first[static_cast<std::size_t>(fv[2])], kInfiniteVertex});
  }
  // Four tetrahedra: link faces by brute force (each pair of quads shares one face through v).
  across_.assign(4, {-1, -1, -1, -1});
  for (std::size_t i = 0; i < 4; ++i) {
    for (std::size_t j = 0; j < 4; ++j) {
      if (i == j) continue;
      // The vertex of quad i that quad j lacks is opposite their shared face.
      for (std::size_t k = 0; k < 4; ++k) {
        const VertexId x = quads_[i][k];
        if (std::find(quads_[j].begin(), quads_[j].end(), x) == quads_[j].end()) {
          across_[i][k] = static_cast<int>(j);
        }
      }
    }
  }
  known_ = {a, b, c};
  std::sort(known_.begin(), known_.end());
  make_keys();
}

bool VertexStar::knows(VertexId w) const {
  return std::binary_search(known_.begin(), known_.end(), w);
}

namespace {

bool finite(const Quad& q) {
  return std::find(q.begin(), q.end(), kInfiniteVertex) == q.end();
}

// Which side of q's face opposite q[j] w lies on: orient3d of q with w in q[j]'s place (> 0: the
// inner side, where q[j] is).
int side_of_face(const std::vector<predicates::Point3>& points, Quad q, std::size_t j, VertexId w) {
  q[j] = w;
  return Exact::orient3d(points[q[0]], points[q[1]], points[q[2]], points[q[3]]);
}

}  // namespace

int VertexStar::cone_of(const std::vector<predicates::Point3>& points, VertexId w) const {
  std::size_t i = 0;
  while (i < quads_.size() && !finite(quads_[i])) ++i;
  if (i == quads_.size()) return kUndecided;  // never: the star spans 3D from its start
  // A visibility walk over the cones: leave through a face (through the centre) that has w's
  // direction strictly on its outer side. The finite cones cover the tangent cone at the centre
  // of the hull of what it knows, which is convex: leaving it means no finite cone holds w. A
  // walk in a triangulation that is not Delaunay may cycle, hence the bound.
  for (std::size_t step = 0; step <= quads_.size(); ++step) {
    const Quad& q = quads_[i];
    int exit = -1;
    bool tie = false;
    for (std::size_t k = 0; k < 4 && exit < 0; ++k) {
      const std::size_t j = (k + step) & 3;  // a varying first face, against cycles
      if (q[j] == center_) continue;
      const int side = side_of_face(points, q, j, w);
      if (side < 0) exit = static_cast<int>(j);
      tie |= side == 0;
    }
    if (exit < 0) return tie ? kUndecided : static_cast<int>(i);
    i = static_cast<std::size_t>(across_[i][static_cast<std::size_t>(exit)]);
    if (!finite(quads_[i])) return kOutside;
  }
  return kUndecided;
}

bool VertexStar::offer(const std::vector<predicates::Point3>& points, VertexId w,
                       std::vector<Quad>& removed, StarScratch& scratch) {
  std::vector<char>& conflict = scratch.conflict;
  std::vector<char>& visited = scratch.visited;
  std::vector<int>& stack = scratch.stack;
  std::vector<int>& remap = scratch.remap;
  if (w == center_ || w == kInfiniteVertex || knows(w)) return false;
  known_.insert(std::lower_bound(known_.begin(), known_.end(), w), w);
  const std::size_t n = quads_.size();
  // The tetrahedra w conflicts with form a disk of the link whose interior holds w's direction
  // from the centre (w becomes a vertex of the link, its fan replacing the disk). So one test
  // decides: the tetrahedron whose closed cone at the centre holds that direction (cheap orient3d
  // tests, found by a walk) conflicts with w, or nothing does. Outside every finite cone the
  // direction leaves the hull of what the centre knows, beyond a hull face at the centre: an
  // infinite tetrahedron's.
  int start = -1;
  bool held = false;
  const int cone = cone_of(points, w);
  if (cone >= 0) {
    held = true;
    if (in_conflict<Exact>(points, quads_[static_cast<std::size_t>(cone)], w)) start = cone;
  } else if (cone == kUndecided) {
    // A tie or a long walk: the first finite cone that holds the direction, in order.
    for (std::size_t i = 0; i < n && !held; ++i) {
      const Quad& q = quads_[i];
      if (!finite(q)) continue;
      held = true;
      for (std::size_t j = 0; j < 4 && held; ++j) {
        // w on the inner side of the face opposite q[j], or on it
        held = q[j] == center_ || side_of_face(points, q, j, w) >= 0;
      }
      if (held && in_conflict<Exact>(points, q, w)) start = static_cast<int>(i);
    }
  }
  for (std::size_t i = 0; i < n && !held && start < 0; ++i) {
    const Quad& q = quads_[i];
    if (finite(q)) continue;
    if (in_conflict<Exact>(points, q, w)) start = static_cast<int>(i);
  }
  if (start < 0) return false;
  // The rest of the disk: a search over the link from there.
  conflict.assign(n, 0);
  visited.assign(n, 0);
  stack.assign(1, start);
  conflict[static_cast<std::size_t>(start)] = 1;
  visited[static_cast<std::size_t>(start)] = 1;
  while (!stack.empty()) {
    const auto i = static_cast<std::size_t>(stack.back());
    stack.pop_back();
    for (std::size_t j = 0; j < 4; ++j) {
      if (quads_[i][j] == center_) continue;
      const auto next = static_cast<std::size_t>(across_[i][j]);
      if (visited[next] != 0) continue;
      visited[next] = 1;
      if (in_conflict<Exact>(points, quads_[next], w)) {
        conflict[next] = 1;
        stack.push_back(static_cast<int>(next));
      }
    }
  }

  // Kept quads first, in order; then one new quad per horizon face: the conflict quad with the
  // vertex across the horizon replaced by w (same orientation, as in Bowyer-Watson).
  remap.assign(n, -1);
  // Each quad's key goes with it: a kept quad's is kept, a new quad's made once.
  std::vector<Quad>& quads = scratch.next_quads;
  std::vector<Quad>& keys = scratch.next_keys;
  std::vector<std::array<int, 4>>& across = scratch.next_across;
  quads.clear();
  keys.clear();
  across.clear();
  for (std::size_t i = 0; i < n; ++i) {
    if (conflict[i] != 0) continue;
    remap[i] = static_cast<int>(quads.size());
    quads.push_back(quads_[i]);
    keys.push_back(keys_[i]);
  }
  for (std::size_t i = 0; i < n; ++i) {
    if (conflict[i] != 0) continue;
    std::array<int, 4> a = across_[i];
    for (int& x : a) {
      if (x >= 0)
        x = conflict[static_cast<std::size_t>(x)] != 0 ? -2 : remap[static_cast<std::size_t>(x)];
    }
    across.push_back(a);
  }
  std::vector<StarScratch::OpenFace>& open = scratch.open;
  open.clear();
  for (std::size_t i = 0; i < n; ++i) {
    if (conflict[i] == 0) continue;
    removed.push_back(quads_[i]);
    for (std::size_t j = 0; j < 4; ++j) {
      if (quads_[i][j] == center_) continue;
      const int outside = across_[i][j];
      if (conflict[static_cast<std::size_t>(outside)] != 0) continue;
      Quad q = quads_[i];
      q[j] = w;
      const int id = static_cast<int>(quads.size());
      quads.push_back(q);
      keys.push_back(sorted_quad(q));
      across.push_back({-1, -1, -1, -1});
      // The horizon face: link both ways (the kept quad's face is opposite its vertex not in q).
      across.back()[j] = remap[static_cast<std::size_t>(outside)];
      const Quad& kept = quads_[static_cast<std::size_t>(outside)];
      for (std::size_t g = 0; g < 4; ++g) {
        if (std::find(q.begin(), q.end(), kept[g]) == q.end()) {
          across[static_cast<std::size_t>(remap[static_cast<std::size_t>(outside)])][g] = id;
        }
      }
      // The faces through the centre and w: keyed by their third vertex, matched in pairs below.
      for (std::size_t k = 0; k < 4; ++k) {
        if (k == j || q[k] == center_) continue;
        for (std::size_t m = 0; m < 4; ++m) {
          if (m != j && m != k && q[m] != center_) open.push_back({q[m], id, static_cast<int>(k)});
        }
      }
    }
  }
  std::sort(
      open.begin(), open.end(),
      [](const StarScratch::OpenFace& x, const StarScratch::OpenFace& y) { return x.key < y.key; });
  for (std::size_t i = 0; i < open.size(); i += 2) {
    // The horizon is one cycle of v's link, so each of its vertices is on exactly two new faces.
    if (i + 1 >= open.size() || open[i].key != open[i + 1].key) {
      throw std::logic_error("star splaying: the removed tetrahedra are not a disk of the link");
    }
    across[static_cast<std::size_t>(open[i].quad)][static_cast<std::size_t>(open[i].face)] =
        open[i + 1].quad;
    across[static_cast<std::size_t>(open[i + 1].quad)][static_cast<std::size_t>(open[i + 1].face)] =
        open[i].quad;
  }
  for (std::size_t i = 0; i < quads.size(); ++i) {
    for (std::size_t j = 0; j < 4; ++j) {
      if ((quads[i][j] == center_) != (across[i][j] == -1) || across[i][j] == -2) {
        throw std::logic_error("star splaying: a link face without a neighbour");
      }
    }
  }
  std::swap(quads_, quads);  // the old lists become the next offer's scratch
  std::swap(keys_, keys);
  std::swap(across_, across);
  return true;
}

void VertexStar::make_keys() {
  keys_.clear();
  for (const Quad& q : quads_) keys_.push_back(sorted_quad(q));
}

bool VertexStar::has(const Quad& sorted) const {
  return std::any_of(keys_.begin(), keys_.end(),
                     [&](const Quad& key) { return same_quad(key, sorted); });
}

void VertexStar::link_vertices(std::vector<VertexId>& out) const {
  out.clear();
  for (const Quad& q : quads_) {
    for (const VertexId x : q) {
      if (x != center_) out.push_back(x);
    }
  }
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
}

}  // namespace dtlab::engine
