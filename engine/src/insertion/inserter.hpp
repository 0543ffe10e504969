#pragma once
// The inserter: one point into the mesh. It locates the point (location/point_location.hpp),
// then inserts it by a strategy, and the lock method's policy commits or rolls back:
//   flips   the paper's 1->4 / 2->6 / k->2k subdivision, then legalization by the swaps S23, S32,
//           S22 and S44 (Kohout and Kolingerova 2003, Sect. 4; flips.hpp);
//   cavity  Bowyer-Watson: every tetrahedron in conflict replaced at once (cavity_search.hpp), with
//           the flips as the fallback where an inexact kernel's cavity is no star around the
//           point. So both live in one inserter, chosen per insertion by one branch.
// Templated on the predicate kernel K, so that a kernel costs nothing to choose, and on the lock
// policy Sync (sync.hpp), so that one insertion kernel serves every method. The inserter's
// mesh, geometry, slots and replacement come from MeshEditor (mesh_editor.hpp); it also offers
// the Lawson pass (lawson_pass.hpp) over its own mesh.
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
#include <cmath>
#include <cstdint>
#include <optional>
#include <stdexcept>
#include <utility>
#include <vector>

#include "dtlab/engine/triangulate.hpp"
#include "insertion/cavity_search.hpp"
#include "insertion/lawson_pass.hpp"
#include "location/point_location.hpp"
#include "mesh/tet_store.hpp"
#include "support/phase_clock.hpp"

namespace dtlab::engine {

template <class K, class Sync = NoSync>
class IncrementalDelaunay : public LawsonPass<K, Sync> {
  using Base = LawsonPass<K, Sync>;
  using Flip = typename Base::Flip;
  using Base::geometry_;
  using Base::legalize_face;
  using Base::location_;
  using Base::mesh_;
  using Base::options_;
  using Base::recycle_;
  using Base::replacement_;
  using Base::slots_;
  using Base::stack_;
  using Base::stats_;
  using Base::sync_;
  using typename Base::Replaced;

 public:
  // GaveUp: the policy refused a lock (deadlock detected or prevented); everything was undone.
  // GaveUp: a lock conflict (retry later, after backing off). Unlocated: the descent found no
  // tetrahedron containing the point: a rollback raced it, or an inexact kernel contradicted
  // itself, which repeats on every try (retry a bounded number of times, then abandon).
  enum class Outcome { Inserted, Duplicate, Abandoned, GaveUp, Unlocated };

  // The sequential engine (it owns its mesh), or one inserting thread of a parallel method on a
  // shared mesh: MeshEditor's two constructors.
  template <class... Args>
  explicit IncrementalDelaunay(Args&&... args)
      : Base(std::forward<Args>(args)...),
        locator_(mesh_, options_, geometry_, location_.locator, recycle_, !this->owns_mesh(),
                 Sync::kLocks, confinement()),
        cavity_search_(mesh_, geometry_, *sync_, verify_cavities(options_)),
        cavity_(options_.insertion == Insertion::Cavity && recycle_) {}

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
    replacement_.begin({});
    replacement_.push_new(first);
    for (const auto& f : kFaceVertex) {
      replacement_.push_new({first[static_cast<std::size_t>(f[0])],
                             first[static_cast<std::size_t>(f[1])],
                             first[static_cast<std::size_t>(f[2])], kInfiniteVertex});
    }
    if (replacement_.replace() != Replaced::Done) {
      throw std::logic_error("dtlab: the first tetrahedron does not close up");
    }
    sync_->commit();
    mesh_.roots.assign(replacement_.created().begin(), replacement_.created().end());
  }

  Outcome insert(VertexId p) {
    slots_.begin_insertion();
    const Outcome outcome = insert_point(p);
    if (outcome == Outcome::Inserted && !replacement_.created().empty()) {
      locator_.remember(replacement_.created().back());  // alive now: the next walk starts here
    }
    slots_.end_insertion(outcome == Outcome::GaveUp || outcome == Outcome::Unlocated);
    return outcome;
  }

  // Ends an operation that only located (the batch method's locating threads).
  void end_operation() { slots_.end_operation(); }

 private:
  Outcome insert_point(VertexId p) {
    const PhaseClock::Ticks t0 = PhaseClock::now();
    std::array<int, 4> o{};
    TetId t = locator_.locate(p, o);
    bool refused = false;
    if constexpr (Sync::kLocks) {
      // Lock the leaf; if another thread replaced it meanwhile, descend again from it.
      for (int tries = 0; t != kNoTet; ++tries) {
        if (!sync_->acquire(t)) {
          refused = true;
          break;
        }
        if (mesh_.tets.is_alive(t, std::memory_order_acquire)) break;
        sync_->rollback();
        if (tries > 1000) {
          refused = true;
          break;
        }
        t = locator_.locate(p, o);
      }
    }
    const PhaseClock::Ticks t1 = PhaseClock::now();
    // Also when the leaf's lock was refused: a given-up attempt's location is still work done.
    stats_.seconds.location += PhaseClock::seconds(t0, t1);
    if (refused) return give_up();
    if constexpr (kConfinedReads<Sync>) {
      if (t == kNoTet && locator_.blocked()) return give_up();  // for a later pass
    }
    if (t == kNoTet) {
      // With other threads rolling back under the descent, try the point again later.
      if constexpr (Sync::kLocks) {
        give_up();
        return Outcome::Unlocated;
      }
      return Outcome::Abandoned;
    }

    if (cavity_) {
      if (const std::optional<Outcome> replaced = replace_cavity(t, p, o)) {
        stats_.seconds.subdivision += PhaseClock::seconds(t1, PhaseClock::now());
        if (*replaced == Outcome::GaveUp) return give_up();
        sync_->commit();
        return *replaced;
      }
      // No outcome: the cavity failed (an inexact kernel); p goes in by flips.
    }
    const Outcome split = subdivide(t, p, o);
    const PhaseClock::Ticks t2 = PhaseClock::now();
    stats_.seconds.subdivision += PhaseClock::seconds(t1, t2);
    if (split == Outcome::GaveUp) return give_up();
    if (split != Outcome::Inserted) {
      sync_->commit();
      return split;
    }

    const Outcome legal = legalize(p);
    stats_.seconds.legalization += PhaseClock::seconds(t2, PhaseClock::now());
    if (legal == Outcome::GaveUp) return give_up();
    sync_->commit();
    return legal;
  }

 public:
  // Continues a location that another thread started (the batch method's hint): descends from
  // `start`, which must be a node that contains p, then inserts.
  void set_location_hint(TetId hint) { locator_.set_hint(hint); }
  // The walk mode's start when no hint is given: the tetrahedron the last insertion created (or
  // the last location found). The batch method's inserting thread keeps one per locating thread.
  [[nodiscard]] TetId walk_start() const { return locator_.walk_start(); }
  void set_walk_start(TetId t) { locator_.remember(t); }

  std::vector<Tetrahedron> finite_tetrahedra(VertexId vertex_limit) const {
    return mesh_.finite_tetrahedra(vertex_limit, duplicates_);
  }
  // The same, releasing the mesh as it goes (the engine is done afterwards).
  std::vector<Tetrahedron> take_finite_tetrahedra(VertexId vertex_limit) {
    return mesh_.take_finite_tetrahedra(vertex_limit, duplicates_);
  }
  [[nodiscard]] const std::vector<std::pair<VertexId, VertexId>>& duplicates() const {
    return duplicates_;
  }

  // Location only, no insertion (the batch method's locating threads, the pessimistic method's
  // unsynchronized part, the partitioned method's anchors): a DAG node or, in walk mode, a
  // tetrahedron that contains p, a leaf or live one when nobody changes the mesh meanwhile.
  // Counted like insert()'s own location: seconds.location, predicate calls, location steps.
  TetId locate_only(VertexId p) {
    const PhaseClock::Ticks t0 = PhaseClock::now();
    slots_.begin_operation();  // insert() or end_operation() ends it
    std::array<int, 4> o{};
    const TetId t = locator_.locate(p, o);
    if (t != kNoTet) locator_.remember(t);  // the next point is near on the curve
    stats_.seconds.location += PhaseClock::seconds(t0, PhaseClock::now());
    return t;
  }

 private:
  Outcome give_up() {
    sync_->rollback();
    stack_.clear();
    return Outcome::GaveUp;
  }

 public:
  [[nodiscard]] std::uint64_t location_steps() const { return locator_.location_steps(); }
  // The last insertion gave up because its confined walk stopped at a face it may not cross (or
  // had no readable start).
  [[nodiscard]] bool walk_stopped() const { return locator_.blocked(); }
  [[nodiscard]] std::uint64_t walk_fallbacks() const { return locator_.walk_fallbacks(); }

 private:
  // 1->4 inside, 2->6 on a face, k->2k on an edge; a point on a vertex is a duplicate.
  Outcome subdivide(TetId t, VertexId p, const std::array<int, 4>& o) {
    const int zeros = static_cast<int>(std::count(o.begin(), o.end(), 0));
    if (zeros == 0) {
      return finish_split(
          replacement_.replace_known(t, kNoTet, kNoTet, -1, p, std::array<int, 4>{0, 1, 2, 3}));
    }
    replacement_.begin({});
    if (zeros == 1) {
      const int i0 = static_cast<int>(std::find(o.begin(), o.end(), 0) - o.begin());
      const FaceRef across = mesh_.tets[t].neighbor[static_cast<std::size_t>(i0)];
      const TetId t2 = ref_tet(across);
      if (!sync_->acquire(t2)) return Outcome::GaveUp;
      replacement_.old_tets() = {t, t2};
      for (int i = 0; i < 4; ++i) {
        if (i != i0) replacement_.push_replaced(t, i, p, 0);
        if (i != ref_face(across)) replacement_.push_replaced(t2, i, p, 1);
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
      for (std::size_t r = 0; r < replacement_.old_tets().size(); ++r) {
        const Tet& ring_tet = mesh_.tets[replacement_.old_tets()[r]];
        replacement_.push_replaced(replacement_.old_tets()[r], ring_tet.index_of(a), p,
                                   static_cast<int>(r));
        replacement_.push_replaced(replacement_.old_tets()[r], ring_tet.index_of(b), p,
                                   static_cast<int>(r));
      }
      return finish_split(replacement_.replace_edge_ring(a, b));
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
    return finish_split(replacement_.replace());
  }

  // Bowyer-Watson insertion of p, located in t (locked): Inserted, Duplicate, GaveUp (a lock
  // refused, nothing written), or no outcome when the cavity is not a star around p (an inexact
  // kernel): no live record changed, the caller inserts p by flips, its locks still held. Each such
  // attempt counts in stats.cavity.fallbacks (a point given up later and retried counts again).
  std::optional<Outcome> replace_cavity(TetId t, VertexId p, const std::array<int, 4>& o) {
    if (std::count(o.begin(), o.end(), 0) == 3) return subdivide(t, p, o);  // on a vertex
    using Grown = typename CavitySearch<K, Sync>::Grown;
    const Grown grown = cavity_search_.grow(t, p);
    if (grown == Grown::GaveUp) return Outcome::GaveUp;
    if (grown == Grown::Done) {
      const std::size_t removed = cavity_search_.cavity().size();
      // Never GaveUp: the search holds every lock the replacement needs.
      if (replacement_.replace_cavity(p, cavity_search_.boundary(), cavity_search_.cavity()) ==
          Replaced::Done) {
        ++stats_.cavity.insertions;
        stats_.cavity.tetrahedra_removed += removed;
        return Outcome::Inserted;
      }
    }
    ++stats_.cavity.fallbacks;
    return std::nullopt;
  }

  // What the walk asks before it crosses a face: the policy, where it confines the reads.
  const ReadConfinement<Sync>& confinement() const {
    if constexpr (kConfinedReads<Sync>) {
      return *sync_;
    } else {
      static constexpr Unconfined kAnywhere{};
      return kAnywhere;
    }
  }

  // The fast kernel can contradict itself: its cavities are checked (cavity_search.hpp).
  static bool verify_cavities(const TriangulateOptions& options) {
    return options.check_cavities || options.kernel == KernelKind::Fast;
  }

  Outcome finish_split(Replaced done) {
    if (done == Replaced::GaveUp) return Outcome::GaveUp;
    if (done == Replaced::Impossible) return Outcome::Abandoned;
    stack_.clear();
    for (const TetId id : replacement_.created()) stack_.push_back(id);
    return Outcome::Inserted;
  }

  enum class Ring { Complete, Broken, GaveUp };

  // All tetrahedra around edge ab, starting from t (locked), into replacement_.old_tets(), each
  // locked before its neighbours are read.
  Ring collect_edge_ring(TetId t, VertexId a, VertexId b) {
    replacement_.old_tets().clear();
    TetId current = t;
    TetId previous = kNoTet;
    for (std::size_t guard = 0; guard < 100000; ++guard) {
      if (!sync_->acquire(current)) return Ring::GaveUp;
      replacement_.old_tets().push_back(current);
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

  // Legalizes the faces opposite p of the tetrahedra on stack_: Inserted, Abandoned when the flip
  // bound was hit, GaveUp when the policy refused a lock and the insertion must be undone.
  Outcome legalize(VertexId p) {
    std::uint64_t flips = 0;
    while (!stack_.empty()) {
      const TetId t = stack_.pop_back();
      if (!mesh_.tets.is_alive(t, std::memory_order_acquire)) continue;
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

  PointLocator<K, ReadConfinement<Sync>> locator_;
  CavitySearch<K, Sync> cavity_search_;
  bool cavity_;  // Bowyer-Watson insertion (slot reuse only: no DAG to keep)
  std::vector<std::pair<VertexId, VertexId>> duplicates_;  // (skipped point, its vertex)
};

}  // namespace dtlab::engine
