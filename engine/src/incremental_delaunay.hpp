#pragma once
// The insertion kernel: DAG location, 1->4 / 2->6 / k->2k subdivision, and legalization by the
// swaps S23, S32, S22 and S44 (Kohout and Kolingerova 2003, Sect. 4). Templated on the predicate
// kernel K so that a kernel costs nothing to choose. See docs/design.md.
//
// The vertex at infinity. Every hull face carries an infinite tetrahedron, so every face has two
// sides and S22 is the S44 whose ring contains the infinite vertex. For orientation tests the
// infinite vertex stands for the point "behind" a fixed interior point O, in the sense of
// oriented projective geometry: orient(..., inf, ...) is minus orient(..., O, ...). O is the exact
// centroid of the first tetrahedron, kept symbolic (a rounded centroid of a flat first
// tetrahedron can land on its face plane): K::orient3d_centroid decides it exactly. An infinite
// tetrahedron (a, b, c, inf) then is the unbounded cone from O beyond the hull face abc, so finite
// and infinite tetrahedra tile all of space, every flip is checked geometrically, and the DAG
// partitions space as the paper's auxiliary tetrahedron does. The insphere test of an infinite
// tetrahedron does not use O: a point conflicts with (a, b, c, inf) iff it lies beyond the plane
// abc, or on it inside circle abc.
#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <memory>
#include <stdexcept>
#include <vector>

#include "conflict.hpp"
#include "dtlab/engine/tet_mesh.hpp"
#include "dtlab/engine/triangulate.hpp"
#include "dtlab/predicates/perturbation.hpp"
#include "shared_mesh.hpp"
#include "slot_reclaimer.hpp"

namespace dtlab::engine {

// Sync is the synchronization policy of the lock methods (NoSync for the sequential engine): it
// is asked before a tetrahedron is read for change or written, and told about every write, so
// that one insertion kernel serves every method.
template <class K, class Sync = NoSync>
class IncrementalDelaunay {
 public:
  // GaveUp: the policy refused a lock (deadlock detected or prevented); everything was undone.
  // GaveUp: a lock conflict (retry later, after backing off). Unlocated: the descent found no
  // tetrahedron containing the point: a rollback raced it, or an inexact kernel contradicted
  // itself, which repeats on every try (retry a bounded number of times, then abandon).
  enum class Outcome { Inserted, Duplicate, Abandoned, GaveUp, Unlocated };

  // The sequential engine: owns its mesh.
  IncrementalDelaunay(const std::vector<Point3>& points, const TriangulateOptions& options,
                      TriangulationStats& stats)
      : owned_(std::make_unique<SharedMesh>(points)),
        mesh_(*owned_),
        options_(options),
        stats_(stats),
        sync_(&own_sync_),
        walk_(options.location == Location::Walk),
        recycle_(walk_),
        shared_(false) {
    if (options.max_tetrahedra > 0) mesh_.tets.set_capacity(options.max_tetrahedra);
  }

  // One inserting thread of a parallel method, on a shared mesh.
  // In walk mode with a reclaimer the thread reuses dead slots (slot_reclaimer.hpp); without one
  // (the post-check's repair) it keeps every slot and writes the DAG children.
  IncrementalDelaunay(SharedMesh& mesh, const TriangulateOptions& options,
                      TriangulationStats& stats, Sync& sync, SlotReclaimer* reclaimer = nullptr)
      : mesh_(mesh),
        options_(options),
        stats_(stats),
        sync_(&sync),
        walk_(options.location == Location::Walk),
        recycle_(walk_ && reclaimer != nullptr),
        shared_(true),
        reclaimer_(reclaimer) {}

  // Builds the first tetrahedron abcd (affinely independent) and its four infinite neighbours.
  void start(VertexId a, VertexId b, VertexId c, VertexId d) {
    const Point3 &pa = mesh_.points[a], &pb = mesh_.points[b], &pc = mesh_.points[c],
                 &pd = mesh_.points[d];
    mesh_.first = {pa, pb, pc, pd};
    int o = K::orient3d(pa, pb, pc, pd);
    if (o == 0) throw TriangulationError("the first tetrahedron is flat under this kernel");
    if (o < 0) std::swap(a, b);
    // O as a plain point when the rounded centroid lies strictly inside the first tetrahedron
    // (checked exactly): one orient3d instead of four. Otherwise O stays the symbolic centroid.
    // (The sum can overflow only for unscaled input near DBL_MAX; then O stays symbolic.)
    const Point3 rounded{(pa.x + pb.x + pc.x + pd.x) / 4, (pa.y + pb.y + pc.y + pd.y) / 4,
                         (pa.z + pb.z + pc.z + pd.z) / 4};
    const Point3 &qa = mesh_.points[a], &qb = mesh_.points[b];
    mesh_.origin_is_point = std::isfinite(rounded.x) && std::isfinite(rounded.y) &&
                            std::isfinite(rounded.z) &&
                            predicates::ExactKernel::orient3d(rounded, qb, pc, pd) > 0 &&
                            predicates::ExactKernel::orient3d(qa, rounded, pc, pd) > 0 &&
                            predicates::ExactKernel::orient3d(qa, qb, rounded, pd) > 0 &&
                            predicates::ExactKernel::orient3d(qa, qb, pc, rounded) > 0;
    mesh_.origin = rounded;
    const std::array<VertexId, 4> first{a, b, c, d};
    scratch_new_.clear();
    scratch_new_.push_back(first);
    for (const auto& f : kFaceVertex) {
      scratch_new_.push_back({first[static_cast<std::size_t>(f[0])],
                              first[static_cast<std::size_t>(f[1])],
                              first[static_cast<std::size_t>(f[2])], kInfiniteVertex});
    }
    scratch_old_.clear();
    scratch_parent_.assign(scratch_new_.size(), -1);
    scratch_source_.assign(scratch_new_.size(), {kNoTet, 0});
    if (replace() != Replaced::Done) {
      throw std::logic_error("dtlab: the first tetrahedron does not close up");
    }
    sync_->commit();
    mesh_.roots = scratch_created_;
  }

  Outcome insert(VertexId p) {
    if (reclaimer_ != nullptr) reclaimer_->enter();
    attempt_created_.clear();
    const Outcome outcome = insert_point(p);
    if (outcome == Outcome::Inserted && !scratch_created_.empty()) {
      walk_start_ = scratch_created_.back();  // alive now: the next walk starts here
    }
    if (recycle_) {
      if (outcome == Outcome::GaveUp || outcome == Outcome::Unlocated) {
        // The rollback revived the tetrahedra this attempt killed; the ones it created are dead.
        for (const TetId t : attempt_created_) release_slot(t);
      } else {
        for (const TetId t : retired_) release_slot(t);  // killed by this insertion
      }
      retired_.clear();
    }
    if (reclaimer_ != nullptr) {
      reclaimer_->leave();
      reclaimer_->collect(free_slots_);
    }
    return outcome;
  }

  // Ends an operation that only located (the batch method's locating threads).
  void end_operation() {
    if (reclaimer_ != nullptr) reclaimer_->leave();
  }

 private:
  Outcome insert_point(VertexId p) {
    using Clock = std::chrono::steady_clock;
    const auto t0 = Clock::now();
    std::array<int, 4> o{};
    TetId t = locate(p, o);
    bool refused = false;
    if constexpr (Sync::kLocks) {
      // Lock the leaf; if another thread replaced it meanwhile, descend again from it.
      for (int tries = 0; t != kNoTet; ++tries) {
        if (!sync_->acquire(t)) {
          refused = true;
          break;
        }
        if (mesh_.tets[t].alive.load(std::memory_order_acquire)) break;
        sync_->rollback();
        if (tries > 1000) {
          refused = true;
          break;
        }
        t = locate(p, o);
      }
    }
    const auto t1 = Clock::now();
    // Also when the leaf's lock was refused: a given-up attempt's location is still work done.
    stats_.seconds.location += std::chrono::duration<double>(t1 - t0).count();
    if (refused) return give_up();
    if (t == kNoTet) {
      // With other threads rolling back under the descent, try the point again later.
      if constexpr (Sync::kLocks) {
        give_up();
        return Outcome::Unlocated;
      }
      return Outcome::Abandoned;
    }

    const Outcome split = subdivide(t, p, o);
    const auto t2 = Clock::now();
    stats_.seconds.subdivision += std::chrono::duration<double>(t2 - t1).count();
    if (split == Outcome::GaveUp) return give_up();
    if (split != Outcome::Inserted) {
      sync_->commit();
      return split;
    }

    const Outcome legal = legalize(p);
    stats_.seconds.legalization += std::chrono::duration<double>(Clock::now() - t2).count();
    if (legal == Outcome::GaveUp) return give_up();
    sync_->commit();
    return legal;
  }

 public:
  // Continues a location that another thread started (the batch method's hint): descends from
  // `start`, which must be a node that contains p, then inserts.
  void set_location_hint(TetId hint) { hint_ = hint; }

  std::vector<Tetrahedron> finite_tetrahedra(VertexId vertex_limit) const {
    return mesh_.finite_tetrahedra(vertex_limit, duplicates_);
  }
  SharedMesh& mesh() { return mesh_; }
  [[nodiscard]] const std::vector<std::pair<VertexId, VertexId>>& duplicates() const {
    return duplicates_;
  }

  // Lock-free DAG descent only (the batch method's locating threads, the pessimistic method's
  // unsynchronized part): a node that contains p, a leaf when nobody changes the mesh meanwhile.
  // Counted like insert()'s own location: seconds.location, predicate calls, location steps.
  TetId locate_only(VertexId p) {
    using Clock = std::chrono::steady_clock;
    const auto t0 = Clock::now();
    if (reclaimer_ != nullptr) reclaimer_->enter();  // insert() or end_operation() leaves
    std::array<int, 4> o{};
    const TetId t = locate(p, o);
    if (t != kNoTet) walk_start_ = t;  // the next point is near on the curve
    stats_.seconds.location += std::chrono::duration<double>(Clock::now() - t0).count();
    return t;
  }

 private:
  Outcome give_up() {
    sync_->rollback();
    stack_.clear();
    return Outcome::GaveUp;
  }

 public:
  [[nodiscard]] std::uint64_t dag_nodes() const { return mesh_.tets.size(); }
  [[nodiscard]] std::uint64_t predicate_calls() const { return predicate_calls_; }
  [[nodiscard]] std::uint64_t location_steps() const { return location_steps_; }
  [[nodiscard]] std::uint64_t walk_fallbacks() const { return walk_fallbacks_; }
  // Slots in use: the DAG's nodes, or (recycling) the live tetrahedra and the free slots.
  [[nodiscard]] std::uint64_t store_slots() const { return mesh_.tets.size(); }

 private:
  // Only finite vertices are looked up: the infinite vertex never reaches a point lookup.
  const Point3& point(VertexId v) const { return mesh_.points[v]; }

  int orient(const Quad& q) {
    ++predicate_calls_;
    int inf = 3;
    while (inf >= 0 && q[static_cast<std::size_t>(inf)] != kInfiniteVertex) --inf;
    if (inf < 0) return K::orient3d(point(q[0]), point(q[1]), point(q[2]), point(q[3]));
    // orient(q) = -orient(q with inf -> O); move O to the last slot (a swap: one more sign).
    Quad r = q;
    std::swap(r[static_cast<std::size_t>(inf)], r[3]);
    const int s = mesh_.origin_is_point
                      ? K::orient3d(point(r[0]), point(r[1]), point(r[2]), mesh_.origin)
                      : K::orient3d_centroid(point(r[0]), point(r[1]), point(r[2]), mesh_.first);
    return inf == 3 ? -s : s;
  }

  // Orientation of tetrahedron t with its vertex at position i replaced by v.
  int orient_replaced(const Tet& t, int i, VertexId v) {
    Quad q = t.vertex;
    q[static_cast<std::size_t>(i)] = v;
    return orient(q);
  }

  // Whether p lies strictly inside the (perturbed) circumsphere of t (conflict.hpp).
  bool in_conflict(const Tet& t, VertexId p) {
    ++predicate_calls_;
    return engine::in_conflict<K>(mesh_.points, t.vertex, p);
  }

  // p inside or on the boundary of t; `o` receives the four orientations.
  bool contains(TetId t, VertexId p, std::array<int, 4>& o) {
    const Tet& tet = mesh_.tets[t];
    for (int i = 0; i < 4; ++i) {
      o[static_cast<std::size_t>(i)] = orient_replaced(tet, i, p);
      if (o[static_cast<std::size_t>(i)] < 0) return false;
    }
    return true;
  }

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

  // Walk mode. The owning (sequential) engine walks from the tetrahedron its last insertion
  // created, which is alive, over live tetrahedra only: the walk's answer is final.
  // On a shared mesh other threads change the tetrahedra under the walk. With slot reuse (the
  // parallel walk mode) the walk starts from a tetrahedron it has just seen alive, inside an
  // epoch-protected operation: every slot it then reaches was alive at some moment of the
  // operation, so none is reused before the operation ends (slot_reclaimer.hpp) and each keeps
  // real vertices and its last neighbours. The walk may end in a tetrahedron that died
  // meanwhile: then it walks again from a live one. insert() locks the result and checks it is
  // still alive; a live tetrahedron cannot have changed its vertices since the walk read them.
  // Without slot reuse (no reclaimer) every dead tetrahedron keeps its DAG children too, and a
  // walk that ends in a dead one descends the DAG below it, or from the roots when it failed.
  TetId locate_by_walk(VertexId p, std::array<int, 4>& o) {
    TetId start = hint_ != kNoTet ? hint_ : walk_start_;
    hint_ = kNoTet;
    if (recycle_ && shared_) {
      for (int attempt = 0; attempt < 64; ++attempt) {
        if (start == kNoTet || !mesh_.tets[start].alive.load(std::memory_order_acquire)) {
          start = live_near(start);
        }
        const TetId t = walk(p, o, start);
        if (t != kNoTet && mesh_.tets[t].alive.load(std::memory_order_acquire)) return t;
        ++walk_fallbacks_;
        if (t != kNoTet) start = t;
      }
      return kNoTet;
    }
    if (recycle_) {
      if (start == kNoTet || !mesh_.tets[start].alive.load(std::memory_order_relaxed)) {
        start = any_live_tetrahedron();
      }
      const TetId t = walk(p, o, start);
      if (t != kNoTet) return t;
      ++walk_fallbacks_;  // an inexact kernel's cycle: test every live tetrahedron
      return scan_for(p, o);
    }
    if (start == kNoTet) start = mesh_.roots.front();
    for (int attempt = 0; attempt < 64; ++attempt) {
      TetId reached = walk(p, o, start);
      bool retry = false;
      if (reached != kNoTet) {
        const bool alive = mesh_.tets[reached].alive.load(std::memory_order_acquire);
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

  // Remembering stochastic visibility walk (Devillers, Pion and Teillaud 2002): from t, cross a
  // face that has p strictly on its far side, trying the faces from a random one on and never
  // the face just crossed (p lies strictly on this side of it). On a Delaunay tetrahedralization
  // with exact predicates no tetrahedron is visited twice, so a walk longer than the store is an
  // inexact kernel's cycle or a shared mesh changing under it: kNoTet. Ends with `o` the four
  // orientations of p against the tetrahedron returned.
  TetId walk(VertexId p, std::array<int, 4>& o, TetId t) {
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
      for (int k = 0; k < 4; ++k) {
        const int f = (first + k) & 3;
        const TetId across = ref_tet(load_neighbor(tet, f));
        if (across == previous && skipped < 0) {
          skipped = f;
          continue;
        }
        o[static_cast<std::size_t>(f)] = orient_replaced(tet, f, p);
        if (o[static_cast<std::size_t>(f)] < 0) {
          next = across;
          break;
        }
      }
      if (next == kNoTet) {
        location_steps_ += step;
        // The face skipped is tested too: subdivide needs the exact four signs.
        if (skipped >= 0) {
          o[static_cast<std::size_t>(skipped)] = orient_replaced(tet, skipped, p);
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
    for (TetId t = top; t-- > 0;) {
      if (mesh_.tets[t].alive.load(std::memory_order_acquire)) return t;
    }
    for (TetId t = top; t < slots; ++t) {
      if (mesh_.tets[t].alive.load(std::memory_order_acquire)) return t;
    }
    return mesh_.roots.front();
  }

  // The owning engine's last resorts: some live tetrahedron, and the live tetrahedron that
  // contains p by testing every one.
  TetId any_live_tetrahedron() const {
    for (TetId t = static_cast<TetId>(mesh_.tets.size()); t-- > 0;) {
      if (mesh_.tets[t].alive.load(std::memory_order_relaxed)) return t;
    }
    return kNoTet;
  }
  TetId scan_for(VertexId p, std::array<int, 4>& o) {
    for (TetId t = 0; t < mesh_.tets.size(); ++t) {
      if (mesh_.tets[t].alive.load(std::memory_order_relaxed) && contains(t, p, o)) return t;
    }
    return kNoTet;
  }

  // Neighbour references are read by walking threads that hold no lock, so they are written with
  // release (after the tetrahedron they name is complete) and read with acquire.
  static FaceRef load_neighbor(const Tet& tet, int f) {
    return std::atomic_ref<FaceRef>(const_cast<FaceRef&>(tet.neighbor[static_cast<std::size_t>(f)]))
        .load(std::memory_order_acquire);
  }
  static void store_neighbor(Tet& tet, int f, FaceRef r) {
    std::atomic_ref<FaceRef>(tet.neighbor[static_cast<std::size_t>(f)])
        .store(r, std::memory_order_release);
  }

  TetId descend(VertexId p, std::array<int, 4>& o, TetId start, bool& retry,
                bool start_tested = false) {
    TetId t = start;
    bool tested = start_tested;  // whether `o` holds t's orientations
    if (t == kNoTet) {
      for (const TetId r : mesh_.roots) {
        if (contains(r, p, o)) {
          t = r;
          tested = true;
          break;
        }
      }
    }
    std::uint64_t steps = 0;
    while (t != kNoTet && !mesh_.tets[t].alive.load(std::memory_order_acquire)) {
      if (++steps > options_.max_location_steps) return kNoTet;
      // One snapshot of the children: a rollback of another thread may reset them meanwhile.
      const Tet& node = mesh_.tets[t];
      std::array<TetId, 4> children{};
      int count = 0;
      for (std::size_t k = 0; k < 4; ++k) {
        children[k] = node.child[k].load(std::memory_order_acquire);
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
        if (contains(children[static_cast<std::size_t>(k)], p, o)) {
          next = children[static_cast<std::size_t>(k)];
          tested = true;
          break;
        }
      }
      t = next;
    }
    location_steps_ += steps;
    if (t != kNoTet && !tested && !contains(t, p, o)) {
      // An inexact kernel's contradiction, or (with threads) a rollback that raced the descent.
      retry = Sync::kLocks;
      return kNoTet;
    }
    return t;
  }

  // Adds to scratch_new_ tetrahedron t's copy with the vertex at `position` replaced by v. Its
  // face `position` is t's face `position`: replace() links it without searching.
  void push_replaced(TetId t, int position, VertexId v, int parent) {
    Quad q = mesh_.tets[t].vertex;
    q[static_cast<std::size_t>(position)] = v;
    scratch_new_.push_back(q);
    scratch_parent_.push_back(parent);
    scratch_source_.push_back({t, position});
  }

  // What replace() did: Impossible when the new tetrahedra do not close up (nothing written).
  enum class Replaced { Done, Impossible, GaveUp };

  // 1->4 inside, 2->6 on a face, k->2k on an edge; a point on a vertex is a duplicate.
  Outcome subdivide(TetId t, VertexId p, const std::array<int, 4>& o) {
    scratch_old_.clear();
    scratch_new_.clear();
    scratch_parent_.clear();
    scratch_source_.clear();
    const int zeros = static_cast<int>(std::count(o.begin(), o.end(), 0));
    if (zeros == 0) {
      scratch_old_.push_back(t);
      return finish_split(replace_known(t, kNoTet, kNoTet, -1, p, {0, 1, 2, 3}, 4));
    }
    if (zeros == 1) {
      const int i0 = static_cast<int>(std::find(o.begin(), o.end(), 0) - o.begin());
      const FaceRef across = mesh_.tets[t].neighbor[static_cast<std::size_t>(i0)];
      const TetId t2 = ref_tet(across);
      if (!sync_->acquire(t2)) return Outcome::GaveUp;
      scratch_old_ = {t, t2};
      for (int i = 0; i < 4; ++i) {
        if (i != i0) push_replaced(t, i, p, 0);
        if (i != ref_face(across)) push_replaced(t2, i, p, 1);
      }
    } else if (zeros == 2) {
      std::array<int, 2> edge{};
      int k = 0;
      for (int i = 0; i < 4; ++i) {
        if (o[static_cast<std::size_t>(i)] != 0) edge[static_cast<std::size_t>(k++)] = i;
      }
      const VertexId a = mesh_.tets[t].vertex[static_cast<std::size_t>(edge[0])];
      const VertexId b = mesh_.tets[t].vertex[static_cast<std::size_t>(edge[1])];
      const Ring ring = collect_edge_ring(t, a, b);
      if (ring == Ring::GaveUp) return Outcome::GaveUp;
      if (ring == Ring::Broken) return Outcome::Abandoned;
      for (std::size_t r = 0; r < scratch_old_.size(); ++r) {
        const Tet& ring_tet = mesh_.tets[scratch_old_[r]];
        push_replaced(scratch_old_[r], ring_tet.index_of(a), p, static_cast<int>(r));
        push_replaced(scratch_old_[r], ring_tet.index_of(b), p, static_cast<int>(r));
      }
    } else if (zeros == 3) {
      const int m = static_cast<int>(
          std::find_if(o.begin(), o.end(), [](int s) { return s != 0; }) - o.begin());
      const VertexId v = mesh_.tets[t].vertex[static_cast<std::size_t>(m)];
      if (v != kInfiniteVertex && mesh_.points[v] == mesh_.points[p]) {
        duplicates_.push_back({p, v});
        return Outcome::Duplicate;
      }
      return Outcome::Abandoned;  // inconsistent signs from an inexact kernel
    } else {
      return Outcome::Abandoned;
    }
    return finish_split(replace());
  }

  Outcome finish_split(Replaced done) {
    if (done == Replaced::GaveUp) return Outcome::GaveUp;
    if (done == Replaced::Impossible) return Outcome::Abandoned;
    stack_.assign(scratch_created_.begin(), scratch_created_.end());
    return Outcome::Inserted;
  }

  enum class Ring { Complete, Broken, GaveUp };

  // All tetrahedra around edge ab, starting from t (locked), into scratch_old_, each locked
  // before its neighbours are read.
  Ring collect_edge_ring(TetId t, VertexId a, VertexId b) {
    scratch_old_.clear();
    TetId current = t;
    TetId previous = kNoTet;
    for (std::size_t guard = 0; guard < 100000; ++guard) {
      if (!sync_->acquire(current)) return Ring::GaveUp;
      scratch_old_.push_back(current);
      const Tet& tet = mesh_.tets[current];
      TetId next = kNoTet;
      for (int i = 0; i < 4; ++i) {
        const VertexId v = tet.vertex[static_cast<std::size_t>(i)];
        if (v == a || v == b) continue;
        const TetId candidate = ref_tet(tet.neighbor[static_cast<std::size_t>(i)]);
        if (candidate != previous) {
          next = candidate;
          break;
        }
      }
      previous = current;
      current = next;
      if (current == t) return Ring::Complete;
      if (current == kNoTet) return Ring::Broken;
    }
    return Ring::Broken;
  }

  // Exhausted: the per-insertion flip bound was hit.
  enum class Flip { Done, NotApplied, GaveUp, Exhausted };

  // Legalizes the faces opposite p of the tetrahedra on stack_: Inserted, Abandoned when the flip
  // bound was hit, GaveUp when the policy refused a lock and the insertion must be undone.
  Outcome legalize(VertexId p) {
    std::uint64_t flips = 0;
    while (!stack_.empty()) {
      const TetId t = stack_.back();
      stack_.pop_back();
      if (!mesh_.tets[t].alive.load(std::memory_order_acquire)) continue;
      const int ip = mesh_.tets[t].index_of(p);
      const Flip result = legalize_face(t, ip, flips);
      if (result == Flip::Exhausted) {
        stack_.clear();
        return Outcome::Abandoned;
      }
      if (result != Flip::GaveUp) continue;
      // A refused lock: detect and prevent undo the insertion; a burglary victim goes on with
      // face t again when its part of the mesh survived the burglar, and else stops here.
      const Resume resume = sync_->resume();
      if (resume == Resume::GiveUp) return Outcome::GaveUp;
      stack_.push_back(t);
      if (resume == Resume::Stop) {
        for (const TetId s : stack_) sync_->mark_suspicious(s);
        stack_.clear();
      }
    }
    return Outcome::Inserted;
  }

  // Face ip of live tetrahedron t (the face opposite its vertex `apex`): flips it when the vertex
  // across lies strictly inside t's circumsphere and the flip exists; the new tetrahedra go on
  // stack_. `flips` counts against the per-insertion bound.
  // With `force`, the face is flipped whether or not it is locally Delaunay (flip_face).
  Flip legalize_face(TetId t, int ip, std::uint64_t& flips, bool force = false) {
    const Tet& tet = mesh_.tets[t];
    const VertexId apex = tet.vertex[static_cast<std::size_t>(ip)];
    const FaceRef across = tet.neighbor[static_cast<std::size_t>(ip)];
    const TetId t2 = ref_tet(across);
    const VertexId y = mesh_.tets[t2].vertex[static_cast<std::size_t>(ref_face(across))];
    if (!force && !in_conflict(mesh_.tets[t2], apex)) return Flip::NotApplied;
    if (++flips > options_.max_flips_per_insertion) return Flip::Exhausted;
    if (!sync_->acquire(t2)) return Flip::GaveUp;
    // Where does segment apex-y pass face F = t minus apex? o[m] is the orientation of t with
    // F's vertex m replaced by y: all positive, through F's interior; one negative, outside the
    // edge opposite m; one zero, through that edge (apex, y and the edge coplanar).
    int negative = -1;
    int zero = -1;
    int negatives = 0;
    int zeros = 0;
    std::array<int, 4> o{};
    for (int m = 0; m < 4; ++m) {
      if (m == ip) continue;
      o[static_cast<std::size_t>(m)] = orient_replaced(tet, m, y);
      if (o[static_cast<std::size_t>(m)] < 0) {
        negative = m;
        ++negatives;
      } else if (o[static_cast<std::size_t>(m)] == 0) {
        zero = m;
        ++zeros;
      }
    }
    if (negatives == 0 && zeros == 0) return flip23(t, t2, ip, y);
    if (negatives == 1 && zeros == 0) return flip32(t, t2, ip, negative, y);
    if (zeros == 1 && negatives == 0) return flip44(t, t2, ip, zero, y);
    // Not flippable now; a later flip removes it (Joe 1991).
    return Flip::NotApplied;
  }

 public:
  // Flips face f of live tetrahedron t by S23, S32 or S44/S22, whatever the Delaunay test says,
  // when the same geometry as in legalization allows a flip: the tests inject non-Delaunay faces
  // into a Delaunay mesh with it and check that relegalize() removes them. Sequential use only.
  // Returns the new tetrahedra (empty when no flip exists there).
  std::vector<TetId> flip_face(TetId t, int f) {
    const Tet& tet = mesh_.tets[t];
    if (!tet.alive.load(std::memory_order_acquire)) return {};
    if (tet.vertex[static_cast<std::size_t>(f)] == kInfiniteVertex) {
      const FaceRef across = tet.neighbor[static_cast<std::size_t>(f)];
      t = ref_tet(across);
      f = ref_face(across);
    }
    std::uint64_t count = 0;
    stack_.clear();
    std::vector<TetId> created;
    if (legalize_face(t, f, count, /*force=*/true) == Flip::Done) created = stack_;
    stack_.clear();
    return created;
  }

  // Burglary's sequential post-check: legalizes every face of the live tetrahedra at or below
  // the marked DAG nodes (all live tetrahedra when `everything`) by Lawson flips, following the
  // faces of each new tetrahedron. Lawson flips in 3D can get stuck at a non-flippable face; the
  // caller checks the result with the validator. Returns the number of flips.
  std::uint64_t relegalize(const std::vector<TetId>& marks, bool everything) {
    std::vector<std::pair<TetId, int>> faces;
    std::vector<char> seen(mesh_.tets.size(), 0);
    std::vector<TetId> pending;
    if (everything) {
      for (TetId t = 0; t < mesh_.tets.size(); ++t) pending.push_back(t);
    } else {
      pending = marks;
    }
    while (!pending.empty()) {  // down the DAG to the live tetrahedra
      const TetId t = pending.back();
      pending.pop_back();
      if (t >= seen.size() || seen[t] != 0) continue;
      seen[t] = 1;
      const Tet& tet = mesh_.tets[t];
      if (tet.alive.load(std::memory_order_acquire)) {
        for (int f = 0; f < 4; ++f) faces.emplace_back(t, f);
        continue;
      }
      for (const auto& c : tet.child) {
        const TetId child = c.load(std::memory_order_acquire);
        if (child != kNoTet && !everything) pending.push_back(child);
      }
    }
    std::uint64_t flips = 0;
    // Lawson flips raise no face of the lifted triangulation, so they cannot cycle; the bound
    // only guards against an inexact kernel.
    const std::uint64_t bound = 64 * mesh_.tets.size() + 1024;
    while (!faces.empty() && flips < bound) {
      auto [t, f] = faces.back();
      faces.pop_back();
      const Tet& tet = mesh_.tets[t];
      if (!tet.alive.load(std::memory_order_acquire)) continue;
      if (tet.vertex[static_cast<std::size_t>(f)] == kInfiniteVertex) {
        // Test the face from the finite side (a face has at most one infinite apex).
        const FaceRef across = tet.neighbor[static_cast<std::size_t>(f)];
        t = ref_tet(across);
        f = ref_face(across);
      }
      std::uint64_t count = 0;
      stack_.clear();
      if (legalize_face(t, f, count) != Flip::Done) continue;
      ++flips;
      for (const TetId created : stack_) {
        for (int g = 0; g < 4; ++g) faces.emplace_back(created, g);
      }
      stack_.clear();
    }
    return flips;
  }

 private:
  // S23: abcp + abcy -> three tetrahedra around the new edge py.
  Flip flip23(TetId t, TetId t2, int ip, VertexId y) {
    begin_flip({t, t2});
    std::array<int, 4> positions{};
    int n = 0;
    for (int m = 0; m < 4; ++m) {
      if (m != ip) positions[static_cast<std::size_t>(n++)] = m;
    }
    const Flip result = finish_flip(replace_known(t, t2, kNoTet, ip, y, positions, n));
    if (result == Flip::Done) ++stats_.flips.s23;
    return result;
  }

  // S32: the reflex edge opposite F's vertex `m` has exactly three tetrahedra (t, t2 and the one
  // across t's face m, which must contain y); they become two around the face (p, y, F[m]).
  Flip flip32(TetId t, TetId t2, int ip, int m, VertexId y) {
    const FaceRef across = mesh_.tets[t].neighbor[static_cast<std::size_t>(m)];
    const TetId t3 = ref_tet(across);
    if (mesh_.tets[t3].vertex[static_cast<std::size_t>(ref_face(across))] != y) {
      return Flip::NotApplied;
    }
    if (!sync_->acquire(t3)) return Flip::GaveUp;
    begin_flip({t, t2, t3});
    std::array<int, 4> positions{};
    int n = 0;
    for (int j = 0; j < 4; ++j) {
      if (j != ip && j != m) positions[static_cast<std::size_t>(n++)] = j;
    }
    const Flip result = finish_flip(replace_known(t, t2, t3, ip, y, positions, n));
    if (result == Flip::Done) ++stats_.flips.s32;
    return result;
  }

  // S44 (S22 on the hull): p, y and the edge opposite F's vertex `m` are coplanar and the edge has
  // exactly four tetrahedra; the edge is replaced by py.
  Flip flip44(TetId t, TetId t2, int ip, int m, VertexId y) {
    const Tet& tet = mesh_.tets[t];
    const VertexId vm = tet.vertex[static_cast<std::size_t>(m)];
    const FaceRef across3 = tet.neighbor[static_cast<std::size_t>(m)];
    const TetId t3 = ref_tet(across3);
    const VertexId w = mesh_.tets[t3].vertex[static_cast<std::size_t>(ref_face(across3))];
    const int m2 = mesh_.tets[t2].index_of(vm);
    const FaceRef across4 = mesh_.tets[t2].neighbor[static_cast<std::size_t>(m2)];
    const TetId t4 = ref_tet(across4);
    if (mesh_.tets[t4].vertex[static_cast<std::size_t>(ref_face(across4))] != w) {
      return Flip::NotApplied;
    }
    std::array<int, 2> edge{};
    int k = 0;
    for (int j = 0; j < 4; ++j) {
      if (j != ip && j != m) edge[static_cast<std::size_t>(k++)] = j;
    }
    // The two new tetrahedra on w's side must be positively oriented too.
    const Tet& tet3 = mesh_.tets[t3];
    const int e0 = tet3.index_of(tet.vertex[static_cast<std::size_t>(edge[0])]);
    const int e1 = tet3.index_of(tet.vertex[static_cast<std::size_t>(edge[1])]);
    if (orient_replaced(tet3, e0, y) <= 0 || orient_replaced(tet3, e1, y) <= 0) {
      return Flip::NotApplied;
    }
    if (!sync_->acquire(t3) || !sync_->acquire(t4)) return Flip::GaveUp;
    begin_flip({t, t2, t3, t4});
    push_replaced(t, edge[0], y, -1);
    push_replaced(t, edge[1], y, -1);
    push_replaced(t3, e0, y, -1);
    push_replaced(t3, e1, y, -1);
    const Flip result = finish_flip(replace());
    if (result != Flip::Done) return result;
    if (vm == kInfiniteVertex || w == kInfiniteVertex) {
      ++stats_.flips.s22;
    } else {
      ++stats_.flips.s44;
    }
    return Flip::Done;
  }

  void begin_flip(std::initializer_list<TetId> old) {
    scratch_old_.assign(old.begin(), old.end());
    scratch_new_.clear();
    scratch_parent_.clear();
    scratch_source_.clear();
  }
  // NotApplied when the flip's faces do not close up (inexact kernel only); the mesh is then
  // unchanged.
  Flip finish_flip(Replaced done) {
    if (done == Replaced::GaveUp) return Flip::GaveUp;
    if (done == Replaced::Impossible) return Flip::NotApplied;
    stack_.insert(stack_.end(), scratch_created_.begin(), scratch_created_.end());
    return Flip::Done;
  }

  // A free slot: a recycled one, else the next of this engine's run of fresh slots.
  TetId allocate_slot() {
    TetId id = kNoTet;
    if (!free_slots_.empty()) {
      id = free_slots_.back();
      free_slots_.pop_back();
    } else {
      if (run_next_ == run_end_) {
        std::size_t count = 0;
        run_next_ = mesh_.tets.allocate_run(kSlotRun, count);
        run_end_ = run_next_ + static_cast<TetId>(count);
      }
      id = run_next_++;
    }
    if (reclaimer_ != nullptr) attempt_created_.push_back(id);
    return id;
  }
  // A dead slot: free at once for the owning engine, after the epochs for a shared mesh.
  void release_slot(TetId t) {
    if (reclaimer_ != nullptr) {
      reclaimer_->retire(t);
    } else {
      free_slots_.push_back(t);
    }
  }
  // 64 slots of 56 bytes: a run spans whole cache lines, and what a run leaves unused at the end
  // (dead, never alive) is at most 63 slots per thread.
  static constexpr std::size_t kSlotRun = 64;

  // A face's vertex set as two integers (sorted ids): cheap to compare.
  struct FaceKey {
    std::uint64_t high;
    std::uint32_t low;
    bool operator==(const FaceKey&) const = default;
  };
  struct OpenFace {
    FaceKey key;
    FaceRef ref;  // an existing tetrahedron's face, or (is_new) 4 * new index + face
    bool is_new;
  };
  struct FaceMatch {
    FaceRef ref;
    bool is_new;
    bool set;
  };

  static FaceKey face_key(const Quad& v, int f) {
    const auto& fv = kFaceVertex[static_cast<std::size_t>(f)];
    VertexId a = v[static_cast<std::size_t>(fv[0])];
    VertexId b = v[static_cast<std::size_t>(fv[1])];
    VertexId c = v[static_cast<std::size_t>(fv[2])];
    if (a > b) std::swap(a, b);
    if (b > c) std::swap(b, c);
    if (a > b) std::swap(a, b);
    return {(static_cast<std::uint64_t>(a) << 32) | b, c};
  }

  // Replaces the tetrahedra scratch_old_ by scratch_new_ (same region), linking the new ones to
  // each other and to the outside by their shared faces. scratch_parent_[j] is the index in
  // scratch_old_ of new tetrahedron j's only DAG parent, or -1 when it is a child of every old one.
  // Every face is matched before anything is written: when the new tetrahedra do not close up
  // (only possible with an inexact kernel's contradictory signs) nothing changes and the result
  // is false. The new ids land in scratch_created_.
  Replaced replace() {
    auto is_old = [&](TetId t) {
      return std::find(scratch_old_.begin(), scratch_old_.end(), t) != scratch_old_.end();
    };
    // Direct links: new tetrahedron j's face `position` is its source's face `position`.
    matched_.assign(4 * scratch_new_.size(), FaceMatch{0, false, false});
    claimed_.clear();
    for (std::size_t j = 0; j < scratch_new_.size(); ++j) {
      const auto [source, position] = scratch_source_[j];
      if (source == kNoTet) continue;
      const FaceRef outside = mesh_.tets[source].neighbor[static_cast<std::size_t>(position)];
      if (is_old(ref_tet(outside))) continue;
      matched_[4 * j + static_cast<std::size_t>(position)] = {outside, false, true};
      claimed_.push_back(face_ref(source, position));
    }
    // The other faces of the region's boundary, seen from outside.
    open_faces_.clear();
    for (const TetId o : scratch_old_) {
      const Tet& tet = mesh_.tets[o];
      for (int f = 0; f < 4; ++f) {
        const FaceRef outside = tet.neighbor[static_cast<std::size_t>(f)];
        if (is_old(ref_tet(outside))) continue;
        if (std::find(claimed_.begin(), claimed_.end(), face_ref(o, f)) != claimed_.end()) continue;
        open_faces_.push_back({face_key(tet.vertex, f), outside, false});
      }
    }
    // Match the remaining new faces before writing anything.
    for (std::size_t j = 0; j < scratch_new_.size(); ++j) {
      for (int f = 0; f < 4; ++f) {
        const auto self = static_cast<FaceRef>(4 * j + static_cast<std::size_t>(f));
        if (matched_[self].set) continue;
        const auto key = face_key(scratch_new_[j], f);
        const auto match = std::find_if(open_faces_.begin(), open_faces_.end(),
                                        [&](const OpenFace& of) { return of.key == key; });
        if (match == open_faces_.end()) {
          open_faces_.push_back({key, self, true});
          continue;
        }
        matched_[self] = {match->ref, match->is_new, true};
        if (match->is_new) matched_[match->ref] = {self, true, true};
        *match = open_faces_.back();
        open_faces_.pop_back();
      }
    }
    if (!open_faces_.empty()) return Replaced::Impossible;
    return commit_replacement();
  }

  // The three most frequent replacements, 1->4, S23 and S32, written directly: new tetrahedron
  // j is t with the vertex at positions[j] replaced by `put`, and its faces follow from the
  // adjacency alone, without matching keys. Two new tetrahedra made from t by replacing
  // positions a and b share the face opposite b in the first and opposite a in the second; a new
  // tetrahedron's face at its own replaced position is t's face there; its face opposite p (S23,
  // S32) belongs to t2, across t's face ip, and its face opposite t[m] (S32) to t3, across t's
  // face m; each is found by the vertex it lacks, t[a]. scratch_old_ holds the old tetrahedra.
  // When the neighbourhood is not the textbook one (a broken mesh from an inexact kernel: the
  // vertex put in already in t, old tetrahedra not glued to each other both ways, or an outside
  // face that belongs to an old tetrahedron) the generic matching of replace() decides.
  Replaced replace_known(TetId t, TetId t2, TetId t3, int ip, VertexId put,
                         const std::array<int, 4>& positions, int n) {
    const Tet& tet = mesh_.tets[t];
    const auto count = static_cast<std::size_t>(n);
    auto generic = [&] {
      scratch_new_.clear();
      scratch_parent_.clear();
      scratch_source_.clear();
      for (std::size_t j = 0; j < count; ++j)
        push_replaced(t, positions[j], put, t2 == kNoTet ? 0 : -1);
      return replace();
    };
    if (tet.index_of(put) >= 0) return generic();
    int m = -1;
    if (t2 != kNoTet) {
      const Tet& second = mesh_.tets[t2];
      const int put_at = second.index_of(put);
      if (put_at < 0 || second.neighbor[static_cast<std::size_t>(put_at)] != face_ref(t, ip)) {
        return generic();
      }
      if (t3 != kNoTet) {
        m = 6 - ip - positions[0] - positions[1];
        const int m_at = second.index_of(tet.vertex[static_cast<std::size_t>(m)]);
        const int p_at = mesh_.tets[t3].index_of(tet.vertex[static_cast<std::size_t>(ip)]);
        if (m_at < 0 || p_at < 0 ||
            second.neighbor[static_cast<std::size_t>(m_at)] != face_ref(t3, p_at)) {
          return generic();
        }
      }
    }
    // link[j][f]: the outside face across new tetrahedron j's face f, or (is_new) 4 * k + g,
    // face g of new tetrahedron k.
    std::array<std::array<FaceMatch, 4>, 4> link{};
    bool textbook = true;
    auto outside = [&](std::size_t j, int f, FaceRef ref) {
      const TetId other = ref_tet(ref);
      if (other == t || other == t2 || other == t3) textbook = false;
      link[j][static_cast<std::size_t>(f)] = {ref, false, true};
    };
    auto across_from = [&](TetId old, VertexId lacking) {
      const Tet& o = mesh_.tets[old];
      const int i = o.index_of(lacking);
      if (i < 0) {
        textbook = false;
        return FaceRef{0};
      }
      return o.neighbor[static_cast<std::size_t>(i)];
    };
    for (std::size_t j = 0; j < count; ++j) {
      const int a = positions[j];
      outside(j, a, tet.neighbor[static_cast<std::size_t>(a)]);
      for (std::size_t k = 0; k < count; ++k) {
        if (k != j) {
          link[j][static_cast<std::size_t>(positions[k])] = {static_cast<FaceRef>(4 * k + a), true,
                                                             true};
        }
      }
      const VertexId lost = tet.vertex[static_cast<std::size_t>(a)];
      if (t2 != kNoTet) outside(j, ip, across_from(t2, lost));
      if (t3 != kNoTet) outside(j, m, across_from(t3, lost));
    }
    if (!textbook) return generic();

    // As in commit_replacement: lock every tetrahedron written, log it before its first write.
    if constexpr (Sync::kLocks) {
      for (std::size_t j = 0; j < count; ++j) {
        for (const FaceMatch& l : link[j]) {
          if (!l.is_new && !sync_->acquire(ref_tet(l.ref))) return Replaced::GaveUp;
        }
      }
      for (std::size_t j = 0; j < count; ++j) {
        for (const FaceMatch& l : link[j]) {
          if (!l.is_new) sync_->before_write(ref_tet(l.ref));
        }
      }
      for (const TetId o : scratch_old_) sync_->before_write(o);
    }
    std::array<TetId, 4> ids{};
    for (std::size_t j = 0; j < count; ++j) {
      ids[j] = allocate_slot();
      Tet& fresh = mesh_.tets[ids[j]];
      fresh.vertex = tet.vertex;
      fresh.vertex[static_cast<std::size_t>(positions[j])] = put;
      if (!recycle_) {
        for (auto& c : fresh.child) c.store(kNoTet, std::memory_order_relaxed);
      }
      sync_->created(ids[j]);
    }
    // The new tetrahedra's own references first, then the outside's references to them
    // (release): a walking thread that reaches a new tetrahedron finds all four set.
    for (std::size_t j = 0; j < count; ++j) {
      Tet& fresh = mesh_.tets[ids[j]];
      for (int f = 0; f < 4; ++f) {
        const FaceMatch l = link[j][static_cast<std::size_t>(f)];
        store_neighbor(fresh, f, l.is_new ? face_ref(ids[ref_tet(l.ref)], ref_face(l.ref)) : l.ref);
      }
    }
    for (std::size_t j = 0; j < count; ++j) {
      for (int f = 0; f < 4; ++f) {
        const FaceMatch l = link[j][static_cast<std::size_t>(f)];
        if (!l.is_new) {
          store_neighbor(mesh_.tets[ref_tet(l.ref)], ref_face(l.ref), face_ref(ids[j], f));
        }
      }
    }
    // Every old tetrahedron is covered by all the new ones (1->4 has one old tetrahedron).
    for (const TetId o : scratch_old_) {
      Tet& old = mesh_.tets[o];
      if (recycle_) {
        old.alive.store(false, std::memory_order_release);
        retired_.push_back(o);
        sync_->killed(o);
        continue;
      }
      for (std::size_t j = 0; j < count; ++j) old.child[j].store(ids[j], std::memory_order_release);
      old.alive.store(false, std::memory_order_release);
      sync_->killed(o);
    }
    scratch_created_.assign(ids.begin(), ids.begin() + n);
    for (std::size_t j = 0; j < count; ++j) {
      mesh_.tets[ids[j]].alive.store(true, std::memory_order_release);
    }
    return Replaced::Done;
  }

  Replaced commit_replacement() {
    // Every tetrahedron written below is locked first: the outside neighbours get new back
    // references (the old ones are locked already), and the undo log sees each before its first
    // write.
    if constexpr (Sync::kLocks) {
      for (const FaceMatch& m : matched_) {
        if (!m.is_new && !sync_->acquire(ref_tet(m.ref))) return Replaced::GaveUp;
      }
      for (const FaceMatch& m : matched_) {
        if (!m.is_new) sync_->before_write(ref_tet(m.ref));
      }
      for (const TetId o : scratch_old_) sync_->before_write(o);
    }

    scratch_created_.clear();
    for (const Quad& q : scratch_new_) {
      const TetId id = allocate_slot();
      Tet& tet = mesh_.tets[id];
      tet.vertex = q;
      for (auto& c : tet.child) c.store(kNoTet, std::memory_order_relaxed);
      sync_->created(id);  // locked by this thread before anyone can reach it
      scratch_created_.push_back(id);
    }
    // The new tetrahedra's own references first, then the outside's references to them.
    for (std::size_t j = 0; j < scratch_created_.size(); ++j) {
      Tet& tet = mesh_.tets[scratch_created_[j]];
      for (int f = 0; f < 4; ++f) {
        const FaceMatch m = matched_[4 * j + static_cast<std::size_t>(f)];
        store_neighbor(
            tet, f, m.is_new ? face_ref(scratch_created_[ref_tet(m.ref)], ref_face(m.ref)) : m.ref);
      }
    }
    for (std::size_t j = 0; j < scratch_created_.size(); ++j) {
      for (int f = 0; f < 4; ++f) {
        const FaceMatch m = matched_[4 * j + static_cast<std::size_t>(f)];
        if (!m.is_new) {
          store_neighbor(mesh_.tets[ref_tet(m.ref)], ref_face(m.ref),
                         face_ref(scratch_created_[j], f));
        }
      }
    }
    // History: children first (release), then the old tetrahedra die, then the new ones live.
    // A recycling engine keeps no history: the old slots are reused after this insertion.
    for (std::size_t r = 0; r < scratch_old_.size(); ++r) {
      Tet& old = mesh_.tets[scratch_old_[r]];
      if (recycle_) {
        old.alive.store(false, std::memory_order_release);
        retired_.push_back(scratch_old_[r]);
        sync_->killed(scratch_old_[r]);
        continue;
      }
      int slot = 0;
      for (std::size_t j = 0; j < scratch_created_.size(); ++j) {
        if (scratch_parent_[j] == -1 || scratch_parent_[j] == static_cast<int>(r)) {
          old.child[static_cast<std::size_t>(slot++)].store(scratch_created_[j],
                                                            std::memory_order_release);
        }
      }
      old.alive.store(false, std::memory_order_release);
      sync_->killed(scratch_old_[r]);
    }
    for (const TetId id : scratch_created_)
      mesh_.tets[id].alive.store(true, std::memory_order_release);
    return Replaced::Done;
  }

  std::unique_ptr<SharedMesh> owned_;  // the sequential engine's own mesh
  SharedMesh& mesh_;
  const TriangulateOptions& options_;
  TriangulationStats& stats_;
  NoSync own_sync_;
  Sync* sync_;
  TetId hint_ = kNoTet;
  // Walk mode: walk_ locates by walking; recycle_ (the owning engine in walk mode) reuses the
  // slots of dead tetrahedra, which go to retired_ when they die and to free_slots_ when the
  // insertion that killed them ends (its legalization stack may still name them until then).
  bool walk_;
  bool recycle_;
  bool shared_;                         // other threads may change the mesh meanwhile
  SlotReclaimer* reclaimer_ = nullptr;  // a shared mesh's slot reuse (parallel walk mode)
  std::vector<TetId> attempt_created_;  // slots this insertion attempt took (reclaimer only)
  TetId walk_start_ = kNoTet;
  std::uint64_t walk_random_ = (options_.seed * 0x9E3779B97F4A7C15ULL) | 1;  // xorshift state
  std::uint64_t walk_fallbacks_ = 0;
  std::vector<TetId> free_slots_;
  TetId run_next_ = 0;  // this engine's run of fresh slots: [run_next_, run_end_)
  TetId run_end_ = 0;
  std::vector<TetId> retired_;
  std::uint64_t predicate_calls_ = 0;
  std::uint64_t location_steps_ = 0;
  std::vector<std::pair<VertexId, VertexId>> duplicates_;  // (skipped point, its vertex)

  // Scratch buffers reused across insertions (no allocation per insertion once warm).
  std::vector<TetId> scratch_old_;
  std::vector<Quad> scratch_new_;
  std::vector<int> scratch_parent_;
  std::vector<TetId> scratch_created_;
  std::vector<OpenFace> open_faces_;
  std::vector<FaceMatch> matched_;
  std::vector<FaceRef> claimed_;
  std::vector<std::pair<TetId, int>> scratch_source_;  // (old tetrahedron, replaced position)
  std::vector<TetId> stack_;
};

}  // namespace dtlab::engine
