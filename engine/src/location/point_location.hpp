#pragma once
// Point location: the paper's descent of the history DAG, and the walk mode's visibility walk
// (docs/design.md, "Walk mode"). locate() returns a live tetrahedron that contains p, or kNoTet,
// with `o` the four orientations of p against it (what the subdivision needs). One object per
// inserting thread; it reads the shared mesh without locks. Templated on the thread's read
// confinement (mesh/read_confinement.hpp): a confined walk stops at a face it may not cross.
#include <algorithm>
#include <array>
#include <atomic>
#include <cstdint>
#include <stdexcept>

#include "dtlab/engine/triangulate.hpp"
#include "location/location_policy.hpp"
#include "mesh/mesh_geometry.hpp"
#include "mesh/read_confinement.hpp"
#include "mesh/shared_mesh.hpp"
#include "mesh/tet_store.hpp"

namespace dtlab::engine {

template <class K, class Confinement = Unconfined>
class PointLocator {
 public:
  // locator: the DAG's descent or the walk (location_policy.hpp); recycle: dead slots are reused
  // (no DAG); shared: other threads change the mesh meanwhile; retry_on_miss: a descent whose leaf
  // does not contain p is retried (with threads a rollback can race it), instead of reported at
  // once.
  PointLocator(SharedMesh& mesh, const TriangulateOptions& options, MeshGeometry<K>& geometry,
               Locator locator, bool recycle, bool shared, bool retry_on_miss,
               const Confinement& confinement)
      : mesh_(mesh),
        options_(options),
        geometry_(geometry),
        confinement_(confinement),
        walk_(locator == Locator::Walk),
        recycle_(recycle),
        shared_(shared),
        retry_on_miss_(retry_on_miss) {}

  // The next location starts from `hint` (the batch method's hint, the pessimistic method's
  // lock-free part): a DAG node that contains p, or in walk mode any tetrahedron.
  void set_hint(TetId hint) { hint_ = hint; }
  // The walk mode's next start: near the last point inserted or located.
  void remember(TetId t) { walk_start_ = t; }
  [[nodiscard]] TetId walk_start() const { return walk_start_; }

  [[nodiscard]] std::uint64_t location_steps() const { return location_steps_; }
  [[nodiscard]] std::uint64_t walk_fallbacks() const { return walk_fallbacks_; }
  // The last locate() returned kNoTet because a confined walk met a face it may not cross (or
  // had no readable start): the point is for a later pass, not a failed location.
  [[nodiscard]] bool blocked() const { return blocked_; }

  // Descends the history DAG from the roots (or from a batch hint) to the live tetrahedron that
  // contains p. With other threads writing, a node can be retired by a rollback under the reader
  // (dead, no children) or a leaf can turn out not to contain p: the descent then restarts.
  TetId locate(VertexId p, std::array<int, 4>& o) {
    if (walk_) return locate_by_walk(p, o);
    TetId start = hint_;
    hint_ = kNoTet;
    for (int attempt = 0; attempt < 64; ++attempt) {
      bool retry = false;
      const TetId t = descend(p, o, start, retry);
      if (!retry) return t;
      start = kNoTet;
    }
    return kNoTet;
  }

 private:
  // Walk mode. The owning (sequential) engine walks from the tetrahedron its last insertion
  // created, which is alive, over live tetrahedra only: the walk's answer is final (locate_alone).
  // A confined thread (the partitioned method's) reads only tetrahedra no other thread writes, so
  // its answer is final too, or the walk stops where it would leave them (locate_confined).
  // On a shared mesh other threads change the tetrahedra under the walk. With slot reuse (the
  // parallel walk mode) the walk starts from a tetrahedron it has just seen alive, inside an
  // epoch-protected operation: every slot it then reaches was alive at some moment of the
  // operation, so none is reused before the operation ends (slot_reclaimer.hpp) and each keeps
  // real vertices and its last neighbours. The walk may end in a tetrahedron that died
  // meanwhile: then it walks again from a live one. insert() locks the result and checks it is
  // still alive; a live tetrahedron cannot have changed its vertices since the walk read them.
  // Without slot reuse on a store that keeps the DAG, a walk that ends in a dead tetrahedron
  // descends the DAG below it, or from the roots when it failed. (The walk mode's stores keep no
  // DAG; its engines without a reclaimer are the owning one, the confined threads', and the
  // post-check's, which never locates.)
  TetId locate_by_walk(VertexId p, std::array<int, 4>& o) {
    TetId start = hint_ != kNoTet ? hint_ : walk_start_;
    hint_ = kNoTet;
    if constexpr (kConfinedReads<Confinement>) {
      blocked_ = false;
      if (confinement_.confined()) return locate_confined(p, o, start);
      return locate_alone(p, o, start);  // a pass of one part: nobody else writes
    }
    if (recycle_ && shared_) {
      auto alive = [&](TetId t) {
        return t != kNoTet && mesh_.tets.is_alive(t, std::memory_order_acquire);
      };
      // A hint that died meanwhile (the batch method's) gives way to this thread's own last
      // tetrahedron, which is near in space; a slot near in id is not.
      if (!alive(start) && alive(walk_start_)) start = walk_start_;
      for (int attempt = 0; attempt < 64; ++attempt) {
        if (!alive(start)) start = live_near(start);
        const TetId t = walk(p, o, start);
        if (t != kNoTet && mesh_.tets.is_alive(t, std::memory_order_acquire)) return t;
        ++walk_fallbacks_;
        if (t != kNoTet) start = t;
      }
      return kNoTet;
    }
    if (recycle_) return locate_alone(p, o, start);
    if (start == kNoTet) start = mesh_.roots.front();
    for (int attempt = 0; attempt < 64; ++attempt) {
      TetId reached = walk(p, o, start);
      bool retry = false;
      if (reached != kNoTet) {
        const bool alive = mesh_.tets.is_alive(reached, std::memory_order_acquire);
        const TetId t = descend(p, o, reached, retry, alive);
        if (!retry && t != kNoTet) return t;
      }
      ++walk_fallbacks_;
      retry = false;
      const TetId t = descend(p, o, kNoTet, retry, false);
      if (!retry) return t;
      start = mesh_.roots.front();
    }
    return kNoTet;
  }

  // Nobody else writes the mesh: one walk, and the last resorts of a walk that fails (an inexact
  // kernel's cycle): some live tetrahedron to start from, every live one tested.
  TetId locate_alone(VertexId p, std::array<int, 4>& o, TetId start) {
    if (start == kNoTet || !mesh_.tets.is_alive(start, std::memory_order_relaxed)) {
      start = any_live_tetrahedron();
    }
    const TetId t = walk(p, o, start);
    if (t != kNoTet) return t;
    ++walk_fallbacks_;
    return scan_for(p, o);
  }

  // A confined thread: from its remembered tetrahedron, which it made or was given readable and
  // which only it writes, over readable tetrahedra only. No scan on failure (it would read the
  // other threads' tetrahedra): kNoTet, and the method retries the point in a later pass.
  TetId locate_confined(VertexId p, std::array<int, 4>& o, TetId start) {
    if (start == kNoTet || !mesh_.tets.is_alive(start, std::memory_order_relaxed)) {
      blocked_ = true;  // no readable start in this pass (an abandoned insertion killed it)
      return kNoTet;
    }
    const TetId t = walk<true>(p, o, start);
    if (t == kNoTet && !blocked_) ++walk_fallbacks_;
    return t;
  }

  // Remembering stochastic visibility walk (Devillers, Pion and Teillaud 2002): from t, cross a
  // face that has p strictly on its far side, trying the faces from a random one on and never
  // the face just crossed (p lies strictly on this side of it). On a Delaunay tetrahedralization
  // with exact predicates no tetrahedron is visited twice, so a walk longer than the store is an
  // inexact kernel's cycle or a shared mesh changing under it: kNoTet. Ends with `o` the four
  // orientations of p against the tetrahedron returned. kConfined: a face the policy does not let
  // it cross is passed over for another face with p beyond it; with none, kNoTet and blocked_.
  // (The face just crossed needs no asking: the walk came through it from the other side.)
  // Out of line: inlined into locate(), the confined walk's orientation tests stayed calls
  // (callgrind, uniform:200000, partitioned at 2 threads: 711M instructions of location, 585M
  // out of line; the sequential walk, already out of line, optimistic-detect's and lock-grid's
  // within 0.8 % of their counts before).
  template <bool kConfined = false>
  [[gnu::noinline]] TetId walk(VertexId p, std::array<int, 4>& o, TetId t) {
    TetId previous = kNoTet;
    const std::uint64_t limit =
        std::min<std::uint64_t>(options_.max_location_steps, mesh_.tets.size() + 64);
    for (std::uint64_t step = 0; step < limit; ++step) {
      const Tet& tet = mesh_.tets[t];
      walk_random_ ^= walk_random_ << 13;
      walk_random_ ^= walk_random_ >> 7;
      walk_random_ ^= walk_random_ << 17;
      const auto first = static_cast<int>(walk_random_ >> 62);
      int skipped = -1;
      TetId next = kNoTet;
      [[maybe_unused]] bool fenced = false;  // p lies beyond a face the walk may not cross
      for (int k = 0; k < 4; ++k) {
        const int f = (first + k) & 3;
        const TetId across = ref_tet(load_neighbor(tet, f));
        if (across == previous && skipped < 0) {
          skipped = f;
          continue;
        }
        o[static_cast<std::size_t>(f)] = geometry_.orient_replaced(tet, f, p);
        if (o[static_cast<std::size_t>(f)] < 0) {
          if constexpr (kConfined) {
            if (!confinement_.may_cross(tet, f)) {
              fenced = true;
              continue;
            }
          }
          next = across;
          break;
        }
      }
      if constexpr (kConfined) {
        if (next == kNoTet && fenced) {
          location_steps_ += step;
          blocked_ = true;
          // The next walk starts here: readable, and nearer the thread's next points (which
          // follow along the curve) than where this one started, so that one walk stopped at the
          // border does not stop every later one from the same start.
          walk_start_ = t;
          return kNoTet;
        }
      }
      if (next == kNoTet) {
        location_steps_ += step;
        // The face skipped is tested too: subdivide needs the exact four signs.
        if (skipped >= 0) {
          o[static_cast<std::size_t>(skipped)] = geometry_.orient_replaced(tet, skipped, p);
          if (o[static_cast<std::size_t>(skipped)] < 0) {
            previous = kNoTet;
            t = ref_tet(load_neighbor(tet, skipped));
            continue;
          }
        }
        return t;
      }
      previous = t;
      t = next;
    }
    location_steps_ += limit;
    return kNoTet;
  }

  // A tetrahedron seen alive: the first at or below `near` (or from the top), else above it. With
  // slots reused almost every slot is alive, so the search is short.
  TetId live_near(TetId near) const {
    const auto slots = static_cast<TetId>(mesh_.tets.size());
    const TetId top = near == kNoTet || near >= slots ? slots : near + 1;
    // Ids taken by other threads may lie in blocks not installed yet: those are skipped.
    auto alive = [&](TetId t) {
      return mesh_.tets.has_block(t) && mesh_.tets.is_alive(t, std::memory_order_acquire);
    };
    for (TetId t = top; t-- > 0;) {
      if (alive(t)) return t;
    }
    for (TetId t = top; t < slots; ++t) {
      if (alive(t)) return t;
    }
    return mesh_.roots.front();
  }

  // The owning engine's last resorts: some live tetrahedron, and the live tetrahedron that
  // contains p by testing every one. A mesh with no live tetrahedron is broken (once an inexact
  // kernel's cavity of every tetrahedron, now refused: tet_replacement.hpp): an error, not a
  // walk from no tetrahedron. Out of line and cold, so that the callers' code stays as it was.
  [[gnu::noinline, gnu::cold]] TetId any_live_tetrahedron() const {
    for (TetId t = static_cast<TetId>(mesh_.tets.size()); t-- > 0;) {
      if (mesh_.tets.is_alive(t, std::memory_order_relaxed)) return t;
    }
    throw std::logic_error("dtlab: the mesh has no live tetrahedron to walk from (an engine bug)");
  }
  TetId scan_for(VertexId p, std::array<int, 4>& o) {
    for (TetId t = 0; t < mesh_.tets.size(); ++t) {
      if (mesh_.tets.is_alive(t, std::memory_order_relaxed) && geometry_.contains(t, p, o))
        return t;
    }
    return kNoTet;
  }

  TetId descend(VertexId p, std::array<int, 4>& o, TetId start, bool& retry,
                bool start_tested = false) {
    TetId t = start;
    bool tested = start_tested;  // whether `o` holds t's orientations
    if (t == kNoTet) {
      for (const TetId r : mesh_.roots) {
        if (geometry_.contains(r, p, o)) {
          t = r;
          tested = true;
          break;
        }
      }
    }
    std::uint64_t steps = 0;
    while (t != kNoTet && !mesh_.tets.is_alive(t, std::memory_order_acquire)) {
      if (++steps > options_.max_location_steps) return kNoTet;
      if (!mesh_.tets.has_children()) {  // walk mode keeps no DAG to descend
        retry = true;
        return kNoTet;
      }
      // One snapshot of the children: a rollback of another thread may reset them meanwhile.
      const auto& node_children = mesh_.tets.children(t);
      std::array<TetId, 4> children{};
      int count = 0;
      for (std::size_t k = 0; k < 4; ++k) {
        children[k] = node_children[k].load(std::memory_order_acquire);
        if (children[k] == kNoTet) break;
        ++count;
      }
      if (count == 0) {  // retired by another thread's rollback
        retry = true;
        return kNoTet;
      }
      // The children cover their parent: when all but the last fail, p is in the last one
      // (verified at the leaf).
      TetId next = children[static_cast<std::size_t>(count - 1)];
      tested = false;
      for (int k = 0; k + 1 < count; ++k) {
        if (geometry_.contains(children[static_cast<std::size_t>(k)], p, o)) {
          next = children[static_cast<std::size_t>(k)];
          tested = true;
          break;
        }
      }
      t = next;
    }
    location_steps_ += steps;
    if (t != kNoTet && !tested && !geometry_.contains(t, p, o)) {
      // An inexact kernel's contradiction, or (with threads) a rollback that raced the descent.
      retry = retry_on_miss_;
      return kNoTet;
    }
    return t;
  }
  SharedMesh& mesh_;
  const TriangulateOptions& options_;
  MeshGeometry<K>& geometry_;
  const Confinement& confinement_;
  bool walk_;
  bool recycle_;
  bool shared_;
  bool retry_on_miss_;
  TetId hint_ = kNoTet;
  TetId walk_start_ = kNoTet;
  bool blocked_ = false;
  std::uint64_t walk_random_ = (options_.seed * 0x9E3779B97F4A7C15ULL) | 1;  // xorshift state
  std::uint64_t walk_fallbacks_ = 0;
  std::uint64_t location_steps_ = 0;
};

}  // namespace dtlab::engine
