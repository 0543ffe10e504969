#pragma once
// The insertion kernel: location, 1->4 / 2->6 / k->2k subdivision, and legalization by the
// swaps S23, S32, S22 and S44 (Kohout and Kolingerova 2003, Sect. 4). Templated on the predicate
// kernel K so that a kernel costs nothing to choose, and on the lock policy Sync. See
// docs/design.md. Its parts, each with its contract where it lives:
//   mesh_geometry.hpp    orientation and insphere tests, the infinite vertex
//   point_location.hpp   the DAG descent and the walk
//   tet_replacement.hpp  replacing tetrahedra by new ones (every split and flip ends there)
//   cavity_search.hpp    the conflict region of Bowyer-Watson insertion (--insertion cavity)
//   slot_allocator.hpp   slots for new tetrahedra, reuse of dead ones (walk mode)
//   optimistic_sync.hpp  the lock methods' locks and undo log (Sync)
// This file keeps the insertion itself: start, insert, subdivide, legalize and the flips, or in
// cavity mode the cavity's replacement (flips remain for the points a cavity fails on).
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
#include <limits>
#include <memory>
#include <optional>
#include <stdexcept>
#include <vector>

#include "cavity_search.hpp"
#include "conflict.hpp"
#include "dtlab/engine/tet_mesh.hpp"
#include "dtlab/engine/triangulate.hpp"
#include "dtlab/predicates/perturbation.hpp"
#include "mesh_geometry.hpp"
#include "phase_clock.hpp"
#include "point_location.hpp"
#include "shared_mesh.hpp"
#include "slot_allocator.hpp"
#include "slot_reclaimer.hpp"
#include "tet_id_list.hpp"
#include "tet_replacement.hpp"

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
        geometry_(mesh_),
        slots_(mesh_.tets, recycle_, nullptr),
        replacement_(mesh_, *sync_, slots_, !recycle_),
        locator_(mesh_, options, geometry_, walk_, recycle_, false, Sync::kLocks),
        cavity_search_(mesh_, geometry_, *sync_, verify_cavities(options)),
        cavity_(options.insertion == Insertion::Cavity && recycle_) {
    if (options.max_tetrahedra > 0) mesh_.tets.set_capacity(options.max_tetrahedra);
    mesh_.tets.keep_children(!walk_);
    mesh_.tets.keep_lock_words(Sync::kLocks);
    PhaseClock::calibrate();  // here, not inside the first insertion's phases
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
        geometry_(mesh_),
        slots_(mesh_.tets, recycle_, reclaimer),
        replacement_(mesh_, *sync_, slots_, !recycle_),
        locator_(mesh_, options, geometry_, walk_, recycle_, true, Sync::kLocks),
        cavity_search_(mesh_, geometry_, *sync_, verify_cavities(options)),
        cavity_(options.insertion == Insertion::Cavity && recycle_) {
    PhaseClock::calibrate();
  }

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
  SharedMesh& mesh() { return mesh_; }
  [[nodiscard]] const std::vector<std::pair<VertexId, VertexId>>& duplicates() const {
    return duplicates_;
  }

  // Lock-free DAG descent only (the batch method's locating threads, the pessimistic method's
  // unsynchronized part): a node that contains p, a leaf when nobody changes the mesh meanwhile.
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
  [[nodiscard]] std::uint64_t predicate_calls() const { return geometry_.predicate_calls(); }
  [[nodiscard]] std::uint64_t location_steps() const { return locator_.location_steps(); }
  [[nodiscard]] std::uint64_t walk_fallbacks() const { return locator_.walk_fallbacks(); }
  // Slots in use: the DAG's nodes, or (recycling) the live tetrahedra and the free slots.
  [[nodiscard]] std::uint64_t store_slots() const { return mesh_.tets.size(); }

 private:
  using Replaced = typename TetReplacement<Sync>::Replaced;

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

  // Exhausted: the per-insertion flip bound was hit.
  enum class Flip { Done, NotApplied, GaveUp, Exhausted };

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
    if (!force && !geometry_.in_conflict(mesh_.tets[t2], apex)) return Flip::NotApplied;
    if (++flips > options_.max_flips_per_insertion) return Flip::Exhausted;
    if (!sync_->acquire(t2)) return Flip::GaveUp;
    if constexpr (Sync::kLocks) {
      // A flip locks the records around t and t2 (it writes back references into them): ask
      // for their cache lines now, so that they arrive during the orientation tests below
      // instead of stalling the lock's first load (57 % of acquire's samples, optimistic-detect
      // on one thread). The sequential walk's stores to them wait in the store buffer instead:
      // there the prefetch measured no gain.
      for (int f = 0; f < 4; ++f) {
        if (f != ip) mesh_.tets.prefetch(ref_tet(tet.neighbor[static_cast<std::size_t>(f)]));
        if (f != ref_face(across)) {
          mesh_.tets.prefetch(ref_tet(mesh_.tets[t2].neighbor[static_cast<std::size_t>(f)]));
        }
      }
    }
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
      o[static_cast<std::size_t>(m)] = geometry_.orient_replaced(tet, m, y);
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
    if (!mesh_.tets.is_alive(t, std::memory_order_acquire) || !finite_side(t, f)) return {};
    std::uint64_t count = 0;
    stack_.clear();
    std::vector<TetId> created;
    if (legalize_face(t, f, count, /*force=*/true) == Flip::Done) {
      created.assign(stack_.begin(), stack_.end());
    }
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
      if (mesh_.tets.is_alive(t, std::memory_order_acquire)) {
        for (int f = 0; f < 4; ++f) faces.emplace_back(t, f);
        continue;
      }
      if (everything || !mesh_.tets.has_children()) continue;  // walk mode: no DAG
      for (const auto& c : mesh_.tets.children(t)) {
        const TetId child = c.load(std::memory_order_acquire);
        if (child != kNoTet) pending.push_back(child);
      }
    }
    // Lawson flips raise no face of the lifted triangulation, so they cannot cycle; the bound
    // only guards against an inexact kernel, whose flips can. It counts the live tetrahedra, not
    // the slots: in DAG mode every flip adds slots, and a bound on slots let a sweep after a
    // cycling first pass run to tens of millions of flips (the parallel fuzzer: 60 points, the
    // fast kernel, over 3 GB of pending faces).
    std::uint64_t live = 0;
    for (TetId t = 0; t < mesh_.tets.size(); ++t) {
      live += mesh_.tets.is_alive(t, std::memory_order_acquire) ? 1 : 0;
    }
    return lawson(faces, 64 * live + 1024, nullptr, nullptr);
  }

  // --repair=flips-splay's first stage (splay_repair.hpp, FlipPass): Lawson flips from every face
  // of the live tetrahedra among `tets`, at most `max_flips` of them (the faces still queued then
  // are handed on as they are). Returns the flips; `created` gets every tetrahedron they made (some
  // dead again by the end), `left` the vertices of the two tetrahedra of each face still
  // non-Delaunay at the end (once a face), where no flip applied or the bound stopped the pass
  // before its turn: star splaying's seeds. Each face is tested on its last pair of tetrahedra,
  // since the faces of every new tetrahedron are queued after its creation, so no face is
  // non-Delaunay at the end but those in `left` and those that already were, outside `tets`
  // (docs/design.md, "Flips, then star splaying").
  std::uint64_t flip_from(const std::vector<TetId>& tets, std::vector<TetId>& created,
                          std::vector<Quad>& left,
                          std::uint64_t max_flips = std::numeric_limits<std::uint64_t>::max()) {
    std::vector<std::pair<TetId, int>> faces;
    for (const TetId t : tets) {
      if (!mesh_.tets.is_alive(t, std::memory_order_acquire)) continue;
      for (int f = 0; f < 4; ++f) faces.emplace_back(t, f);
    }
    std::vector<std::pair<TetId, int>> stuck;
    // A bound from the faces given, not the whole mesh (counting its live tetrahedra took 10 to
    // 20 ms at 1M points, more than the flips for a few dozen faces): a pass stopped by it hands
    // the rest to the stars, which finish it whatever is left.
    const std::uint64_t bound = std::min<std::uint64_t>(64 * faces.size() + 1024, max_flips);
    const std::uint64_t flips = lawson(faces, bound, &stuck, &created);
    // Each face once: named from the side of its finite apex, the lower tetrahedron where both
    // apexes are finite.
    std::vector<std::pair<TetId, int>> named;
    for (auto [t, f] : stuck) {
      if (!mesh_.tets.is_alive(t, std::memory_order_acquire)) continue;  // flipped away later
      const FaceRef across = mesh_.tets[t].neighbor[static_cast<std::size_t>(f)];
      const TetId u = ref_tet(across);
      const int g = ref_face(across);
      const bool mine_infinite =
          mesh_.tets[t].vertex[static_cast<std::size_t>(f)] == kInfiniteVertex;
      const bool its_infinite =
          mesh_.tets[u].vertex[static_cast<std::size_t>(g)] == kInfiniteVertex;
      if (mine_infinite != its_infinite ? mine_infinite : u < t) {
        t = u;
        f = g;
      }
      named.emplace_back(t, f);
    }
    std::sort(named.begin(), named.end());
    named.erase(std::unique(named.begin(), named.end()), named.end());
    for (const auto& [t, f] : named) {
      const Tet& tet = mesh_.tets[t];
      const Tet& across = mesh_.tets[ref_tet(tet.neighbor[static_cast<std::size_t>(f)])];
      const VertexId apex = tet.vertex[static_cast<std::size_t>(f)];
      // A face between two infinite apexes (never on a mesh built exactly) is handed on as found.
      if (apex != kInfiniteVertex && !geometry_.in_conflict(across, apex)) continue;
      left.push_back(tet.vertex);
      left.push_back(across.vertex);
    }
    return flips;
  }

 private:
  // Names face f of t from the side of its finite apex (a face has at most one infinite apex on a
  // sound mesh): false where both apexes are infinite.
  bool finite_side(TetId& t, int& f) const {
    if (mesh_.tets[t].vertex[static_cast<std::size_t>(f)] != kInfiniteVertex) return true;
    const FaceRef across = mesh_.tets[t].neighbor[static_cast<std::size_t>(f)];
    t = ref_tet(across);
    f = ref_face(across);
    return mesh_.tets[t].vertex[static_cast<std::size_t>(f)] != kInfiniteVertex;
  }

  // Lawson flips from `faces` (tetrahedron, face) until none is left or `bound` flips were made;
  // the faces of every new tetrahedron follow. A face is tested from the side of its finite apex.
  // `stuck`, when given, receives the faces found non-Delaunay where no flip exists (and those
  // still queued if the bound stops the pass); `created` every new tetrahedron. Returns the number
  // of flips.
  std::uint64_t lawson(std::vector<std::pair<TetId, int>>& faces, std::uint64_t bound,
                       std::vector<std::pair<TetId, int>>* stuck, std::vector<TetId>* created) {
    std::uint64_t flips = 0;
    while (!faces.empty()) {
      if (flips >= bound) {  // what is left is star splaying's, where it runs
        if (stuck != nullptr) stuck->insert(stuck->end(), faces.begin(), faces.end());
        faces.clear();
        break;
      }
      auto [t, f] = faces.back();
      faces.pop_back();
      if (!mesh_.tets.is_alive(t, std::memory_order_acquire)) continue;
      if (!finite_side(t, f)) {
        // Two infinite tetrahedra glued on one face: a mesh the fast kernel broke (seen after
        // its burglary runs). No flip applies; the face stays for the validator to count.
        if (stuck != nullptr) stuck->emplace_back(t, f);
        continue;
      }
      const Tet& tet = mesh_.tets[t];
      const Tet& other = mesh_.tets[ref_tet(tet.neighbor[static_cast<std::size_t>(f)])];
      if (!geometry_.in_conflict(other, tet.vertex[static_cast<std::size_t>(f)])) continue;
      std::uint64_t count = 0;
      stack_.clear();
      if (legalize_face(t, f, count, /*force=*/true) != Flip::Done) {
        if (stuck != nullptr) stuck->emplace_back(t, f);
        stack_.clear();
        continue;
      }
      ++flips;
      for (const TetId id : stack_) {
        for (int g = 0; g < 4; ++g) faces.emplace_back(id, g);
        if (created != nullptr) created->push_back(id);
      }
      stack_.clear();
    }
    return flips;
  }

  // S23: abcp + abcy -> three tetrahedra around the new edge py.
  Flip flip23(TetId t, TetId t2, int ip, VertexId y) {
    std::array<int, 3> positions{};
    std::size_t n = 0;
    for (int m = 0; m < 4; ++m) {
      if (m != ip) positions[n++] = m;
    }
    const Flip result = finish_flip(replacement_.replace_known(t, t2, kNoTet, ip, y, positions));
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
    std::array<int, 2> positions{};
    std::size_t n = 0;
    for (int j = 0; j < 4; ++j) {
      if (j != ip && j != m) positions[n++] = j;
    }
    const Flip result = finish_flip(replacement_.replace_known(t, t2, t3, ip, y, positions));
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
    if (m2 < 0) return Flip::NotApplied;  // t2 lacks t's vertex m: a broken mesh
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
    if (e0 < 0 || e1 < 0) return Flip::NotApplied;  // t3 lacks the edge: a broken mesh
    if (geometry_.orient_replaced(tet3, e0, y) <= 0 ||
        geometry_.orient_replaced(tet3, e1, y) <= 0) {
      return Flip::NotApplied;
    }
    if (!sync_->acquire(t3) || !sync_->acquire(t4)) return Flip::GaveUp;
    const Flip result = finish_flip(replacement_.replace_flip44(t, t2, t3, t4, ip, m, edge, y));
    if (result != Flip::Done) return result;
    if (vm == kInfiniteVertex || w == kInfiniteVertex) {
      ++stats_.flips.s22;
    } else {
      ++stats_.flips.s44;
    }
    return Flip::Done;
  }

  // NotApplied when the flip's faces do not close up (inexact kernel only); the mesh is then
  // unchanged.
  Flip finish_flip(Replaced done) {
    if (done == Replaced::GaveUp) return Flip::GaveUp;
    if (done == Replaced::Impossible) return Flip::NotApplied;
    for (const TetId id : replacement_.created()) stack_.push_back(id);
    return Flip::Done;
  }

  std::unique_ptr<SharedMesh> owned_;  // the sequential engine's own mesh
  SharedMesh& mesh_;
  const TriangulateOptions& options_;
  TriangulationStats& stats_;
  NoSync own_sync_;
  Sync* sync_;
  // Walk mode: walk_ locates by walking; recycle_ reuses the slots of dead tetrahedra (the
  // owning engine in walk mode, and a parallel thread in walk mode with a reclaimer).
  bool walk_;
  bool recycle_;
  MeshGeometry<K> geometry_;
  SlotAllocator slots_;
  TetReplacement<Sync> replacement_;
  PointLocator<K> locator_;
  CavitySearch<K, Sync> cavity_search_;
  bool cavity_;  // Bowyer-Watson insertion (walk mode with slot reuse only: no DAG to keep)
  std::vector<std::pair<VertexId, VertexId>> duplicates_;  // (skipped point, its vertex)
  TetIdList stack_;  // legalization: new tetrahedra whose face opposite p is unchecked
};

}  // namespace dtlab::engine
