// Drivers of the parallel methods: point distribution, threads, the watchdog, stats.
#include "parallel_methods.hpp"

#include <algorithm>
#include <atomic>
#include <cassert>
#include <chrono>
#include <condition_variable>
#include <cstdio>
#include <deque>
#include <exception>
#include <mutex>
#include <optional>
#include <thread>
#include <unordered_map>

#include "dtlab/engine/validator.hpp"
#include "dtlab/predicates/audit.hpp"
#include "dtlab/predicates/kernels.hpp"
#include "incremental_delaunay.hpp"
#include "optimistic_sync.hpp"
#include "splay_repair.hpp"

namespace dtlab::engine {
namespace {

using Clock = std::chrono::steady_clock;

// Splits `ids` (kept in their order) into `parts` groups of equal size by the coordinate `axis`
// (median splits), recursively alternating axes for blocks.
void split_by_median(const std::vector<Point3>& points, std::vector<std::uint32_t> ids, int parts,
                     int axis, int axes, std::vector<std::vector<std::uint32_t>>& out) {
  if (parts <= 1) {
    out.push_back(std::move(ids));
    return;
  }
  const int left_parts = parts / 2;
  std::vector<std::uint32_t> sorted = ids;
  const std::size_t cut =
      ids.size() * static_cast<std::size_t>(left_parts) / static_cast<std::size_t>(parts);
  std::nth_element(sorted.begin(), sorted.begin() + static_cast<std::ptrdiff_t>(cut), sorted.end(),
                   [&](std::uint32_t a, std::uint32_t b) {
                     const double ca = predicates::coordinate(points[a], axis);
                     const double cb = predicates::coordinate(points[b], axis);
                     return ca < cb || (ca == cb && a < b);
                   });
  // Membership by rank, so that each side keeps the random order of `ids`.
  std::vector<char> left(points.size(), 0);
  for (std::size_t i = 0; i < cut; ++i) left[sorted[i]] = 1;
  std::vector<std::uint32_t> a;
  std::vector<std::uint32_t> b;
  for (const std::uint32_t v : ids) (left[v] ? a : b).push_back(v);
  const int next_axis = (axis + 1) % axes;
  split_by_median(points, std::move(a), left_parts, next_axis, axes, out);
  split_by_median(points, std::move(b), parts - left_parts, next_axis, axes, out);
}

// Stops a run in which no insertion finished for too long: a lost wake-up or an undetected
// deadlock becomes a reported failure, not a hang.
class Watchdog {
 public:
  Watchdog(double seconds, std::atomic<std::uint64_t>& progress, std::atomic<bool>& stop)
      : seconds_(seconds), progress_(progress), stop_(stop), thread_([this] { watch(); }) {}
  Watchdog(const Watchdog&) = delete;
  Watchdog& operator=(const Watchdog&) = delete;
  ~Watchdog() {
    {
      std::lock_guard<std::mutex> guard(mutex_);
      done_ = true;
    }
    wake_.notify_all();
    thread_.join();
  }
  [[nodiscard]] bool fired() const { return fired_.load(); }

 private:
  void watch() {
    std::uint64_t last = progress_.load();
    auto last_change = Clock::now();
    std::unique_lock<std::mutex> lock(mutex_);
    while (!done_) {
      wake_.wait_for(lock, std::chrono::milliseconds(100));
      const std::uint64_t now = progress_.load();
      if (now != last) {
        last = now;
        last_change = Clock::now();
      } else if (std::chrono::duration<double>(Clock::now() - last_change).count() > seconds_) {
        fired_ = true;
        stop_ = true;
        return;
      }
    }
  }
  double seconds_;
  std::atomic<std::uint64_t>& progress_;
  std::atomic<bool>& stop_;
  std::atomic<bool> fired_{false};
  std::mutex mutex_;
  std::condition_variable wake_;
  bool done_ = false;
  std::thread thread_;
};

void add_phase_times(TriangulationStats& total, const TriangulationStats& part) {
  total.seconds.location += part.seconds.location;
  total.seconds.subdivision += part.seconds.subdivision;
  total.seconds.legalization += part.seconds.legalization;
  total.flips.s23 += part.flips.s23;
  total.flips.s32 += part.flips.s32;
  total.flips.s22 += part.flips.s22;
  total.flips.s44 += part.flips.s44;
  total.cavity.insertions += part.cavity.insertions;
  total.cavity.tetrahedra_removed += part.cavity.tetrahedra_removed;
  total.cavity.fallbacks += part.cavity.fallbacks;
}

// Points not yet inserted by a thread: its own list (static, strips, blocks) or the shared
// index (dynamic), plus the points it gave up, retried after the rest.
class WorkSource {
 public:
  WorkSource(const std::vector<std::uint32_t>* own, std::atomic<std::size_t>* shared_index,
             const std::vector<std::uint32_t>* shared)
      : own_(own), shared_index_(shared_index), shared_(shared) {}
  std::optional<std::uint32_t> next() {
    if (own_ != nullptr && position_ < own_->size()) return (*own_)[position_++];
    if (shared_index_ != nullptr) {
      const std::size_t i = shared_index_->fetch_add(1, std::memory_order_relaxed);
      if (i < shared_->size()) return (*shared_)[i];
    }
    if (retry_position_ < retry_.size()) return retry_[retry_position_++];
    return std::nullopt;
  }
  // Queues v again; false when it was given up more than `limit` times (then the caller
  // abandons it).
  bool retry_later(std::uint32_t v, int limit) {
    if (++attempts_[v] > limit) return false;
    retry_.push_back(v);
    return true;
  }
  // Lock conflicts end when the other thread finishes. A location fails under an exact kernel
  // only while another thread's rollback races the descent; with the back-off below, 64 attempts
  // span more than 50 ms, longer than any insertion takes even under --stress, so a location
  // that fails that often is an inexact kernel's contradiction, which every retry repeats.
  static constexpr int kMaxLockAttempts = 100000;
  static constexpr int kMaxLocationAttempts = 64;

 private:
  const std::vector<std::uint32_t>* own_;
  std::size_t position_ = 0;
  std::atomic<std::size_t>* shared_index_;
  const std::vector<std::uint32_t>* shared_;
  std::vector<std::uint32_t> retry_;
  std::size_t retry_position_ = 0;
  std::unordered_map<std::uint32_t, int> attempts_;
};

template <class Dt>
void count_outcome(typename Dt::Outcome outcome, ThreadStats& t) {
  switch (outcome) {
    case Dt::Outcome::Inserted:
      ++t.inserted;
      break;
    case Dt::Outcome::Duplicate:
      ++t.duplicates;
      break;
    case Dt::Outcome::Abandoned:
      ++t.abandoned;
      break;
    case Dt::Outcome::GaveUp:
    case Dt::Outcome::Unlocated:
      ++t.give_ups;
      break;
  }
}

// Burglary's sequential post-check: the exact validator's count after the parallel run; with
// --repair, Lawson flips on the marked tetrahedra, then (only if the validator still finds
// non-Delaunay faces) on every tetrahedron. Flips can get stuck in 3D: what they leave is reported
// (non_delaunay_after_flips), and only Repair::Rebuild then triangulates again sequentially, as an
// explicit, reported last resort (rebuilt). Each stage's count goes into stats.post_check, and the
// validator's full verdict on the mesh returned into its *_after fields.
template <class K>
std::vector<Tetrahedron> post_check(SharedMesh& mesh, std::size_t input_count,
                                    const std::vector<TetId>& marks,
                                    const std::vector<std::uint32_t>& full_order,
                                    const std::array<std::uint32_t, 4>& first, bool skip_first,
                                    const std::vector<std::pair<VertexId, VertexId>>& duplicates,
                                    const TriangulateOptions& options, TriangulationStats& stats) {
  PostCheck& check = stats.post_check;
  check.done = true;
  const std::vector<Point3> input(mesh.points.begin(),
                                  mesh.points.begin() + static_cast<std::ptrdiff_t>(input_count));
  // With the auxiliary tetrahedron the hull it lost shows as reflex boundary edges in every
  // method (docs/experiments.md), so only the vertex at infinity counts them as burglary's.
  const bool hull_counts = options.bounding == Bounding::Infinite;
  // Validates `tets`, records the verdict as the latest stage's, returns the violations left.
  ValidationReport report;  // the latest stage's
  auto count = [&](const std::vector<Tetrahedron>& tets) {
    const auto t0 = Clock::now();
    report = validate(input, tets, ValidateWith::Adaptive, kAllThreads, true);
    check.seconds_check += std::chrono::duration<double>(Clock::now() - t0).count();
    check.non_delaunay_faces_after = report.non_delaunay_faces;
    check.reflex_boundary_edges_after = report.reflex_boundary_edges;
    check.mesh_consistent_after = report.mesh_consistent();
    check.non_delaunay_after =
        report.non_delaunay_faces + (hull_counts ? report.reflex_boundary_edges : 0);
    return check.non_delaunay_after;
  };
  const auto output_start = Clock::now();
  std::vector<Tetrahedron> tets =
      mesh.finite_tetrahedra(static_cast<VertexId>(input_count), duplicates, options.threads);
  stats.seconds.output += std::chrono::duration<double>(Clock::now() - output_start).count();
  count(tets);
  check.non_delaunay_faces = check.non_delaunay_faces_after;
  check.reflex_boundary_edges = check.reflex_boundary_edges_after;
  check.mesh_consistent = check.mesh_consistent_after;
  if (options.repair == Repair::None) return tets;

  check.repaired = true;
  const auto t0 = Clock::now();
  const double check_before = check.seconds_check;
  if (splays(options.repair)) {
    // The validation above already proved the mesh the unique perturbed Delaunay
    // tetrahedralization (ValidationReport::is_perturbed_delaunay): what star splaying would
    // return unchanged, so its own scan is skipped (the marks, if any, changed nothing that
    // shows) and the verdict after is that one. Only with the vertex at infinity: with the
    // auxiliary tetrahedron star splaying works on the input and the four auxiliary vertices,
    // whose Delaunay tetrahedralization can lose hull tetrahedra that the input's has, so a proof
    // about the finite tetrahedra says nothing about what it would return.
    if (hull_counts && report.is_perturbed_delaunay()) {
      stats.splay.done = true;
      stats.splay.proven_by_post_check = true;
      return tets;
    }
    // Star splaying from the marks and every non-Delaunay face: always ends Delaunay. Where the
    // validation above judged the mesh consistent (built exactly), the faces it rejected are the
    // ones the repair's exact scan would find: handed over, they spare a second pass over the
    // whole mesh.
    const bool exact_mesh = options.kernel != KernelKind::Fast;
    std::optional<ValidatedFindings> found;
    if (hull_counts && exact_mesh && report.mesh_consistent()) {
      found = validated_findings(report, input_count, duplicates);
    }
    // --repair=flips-splay: exact Lawson flips first, by this kernel (exact: only a mesh built
    // exactly is flipped).
    TriangulationStats flip_stats;
    NoSync flip_sync;
    const FlipPass flips = [&](const std::vector<TetId>& at, std::vector<TetId>& created,
                               std::vector<Quad>& left) {
      IncrementalDelaunay<K, NoSync> flipper(mesh, options, flip_stats, flip_sync);
      return flipper.flip_from(at, created, left);
    };
    const bool flips_first = options.repair == Repair::FlipsThenSplay && exact_mesh;
    splay_shared_mesh(mesh, marks, exact_mesh, options.threads, stats.splay,
                      found ? &*found : nullptr, flips_first ? &flips : nullptr);
    check.seconds_repair = stats.splay.seconds;
    // Nothing flipped or written back: the mesh and so its verdict are the ones validated above.
    if (stats.splay.flips == 0 && stats.splay.tetrahedra_removed == 0 &&
        stats.splay.tetrahedra_created == 0) {
      return tets;
    }
    tets = mesh.finite_tetrahedra(static_cast<VertexId>(input_count), duplicates, options.threads);
    count(tets);
    return tets;
  }
  TriangulationStats repair_stats;
  NoSync no_sync;
  IncrementalDelaunay<K, NoSync> dt(mesh, options, repair_stats, no_sync);
  // Walk mode keeps no DAG and reuses slots: a mark stands for itself, when it is still alive
  // (a reused slot marks an unrelated live tetrahedron: extra faces checked, nothing missed,
  // since the sweep below and star splaying's exact scan find every non-Delaunay face).
  std::vector<TetId> live_marks;
  if (options.location == Location::Walk) {
    for (const TetId t : marks) {
      if (mesh.tets.is_alive(t, std::memory_order_relaxed)) live_marks.push_back(t);
    }
  }
  check.repair_flips =
      dt.relegalize(options.location == Location::Walk ? live_marks : marks, false);
  tets = mesh.finite_tetrahedra(static_cast<VertexId>(input_count), duplicates, options.threads);
  check.non_delaunay_after_marked = count(tets);
  check.non_delaunay_after_flips = check.non_delaunay_after_marked;
  if (check.non_delaunay_after_flips > 0) {
    check.sweep_flips = dt.relegalize({}, true);
    tets = mesh.finite_tetrahedra(static_cast<VertexId>(input_count), duplicates, options.threads);
    check.non_delaunay_after_flips = count(tets);
  }
  check.mesh_consistent_after_flips = check.mesh_consistent_after;
  if (check.non_delaunay_after_flips > 0 && options.repair == Repair::Rebuild) {
    check.rebuilt = true;
    TriangulationStats rebuild_stats;
    TriangulateOptions sequential = options;
    sequential.progress = false;
    tets = run_sequential<K>(mesh.points, input_count, full_order, first, skip_first, sequential,
                             rebuild_stats);
    count(tets);
  }
  check.seconds_repair = std::chrono::duration<double>(Clock::now() - t0).count() -
                         (check.seconds_check - check_before);
  return tets;
}

}  // namespace

std::vector<std::vector<std::uint32_t>> distribute(const std::vector<Point3>& points,
                                                   const std::vector<std::uint32_t>& order,
                                                   Distribution distribution, int threads) {
  assert(distribution != Distribution::Auto);
  std::vector<std::vector<std::uint32_t>> parts;
  if (distribution == Distribution::Strips || distribution == Distribution::Blocks) {
    split_by_median(points, order, threads, 0, distribution == Distribution::Strips ? 1 : 3, parts);
    return parts;
  }
  // Static: contiguous pieces of the random permutation.
  const std::size_t n = order.size();
  for (int i = 0; i < threads; ++i) {
    const std::size_t begin = n * static_cast<std::size_t>(i) / static_cast<std::size_t>(threads);
    const std::size_t end = n * static_cast<std::size_t>(i + 1) / static_cast<std::size_t>(threads);
    parts.emplace_back(order.begin() + static_cast<std::ptrdiff_t>(begin),
                       order.begin() + static_cast<std::ptrdiff_t>(end));
  }
  return parts;
}

template <class K>
std::vector<Tetrahedron> run_parallel(const std::vector<Point3>& points, std::size_t input_count,
                                      const std::vector<std::uint32_t>& full_order,
                                      const std::array<std::uint32_t, 4>& first, bool skip_first,
                                      const TriangulateOptions& options,
                                      TriangulationStats& stats) {
  const int threads = std::max(1, options.threads);
  SharedMesh mesh(points);
  if (options.max_tetrahedra > 0) mesh.tets.set_capacity(options.max_tetrahedra);
  mesh.tets.keep_children(options.location != Location::Walk);  // the walk mode keeps no DAG
  mesh.tets.keep_lock_words(true);
  TriangulationStats start_stats;
  NoSync no_sync;
  IncrementalDelaunay<K, NoSync>(mesh, options, start_stats, no_sync)
      .start(first[0], first[1], first[2], first[3]);
  // An empty full order is the identity: in walk mode triangulate() stores the points in one
  // BRIO and Hilbert order, so that ids are insertion order.
  std::vector<std::uint32_t> order;
  const std::size_t listed = full_order.empty() ? input_count : full_order.size();
  order.reserve(listed);
  for (std::size_t i = 0; i < listed; ++i) {
    const auto v = full_order.empty() ? static_cast<std::uint32_t>(i) : full_order[i];
    if (skip_first && (v == first[0] || v == first[1] || v == first[2] || v == first[3])) continue;
    order.push_back(v);
  }
  if (skip_first) stats.inserted += 4;

  stats.threads.assign(static_cast<std::size_t>(threads), ThreadStats{});
  std::vector<TriangulationStats> thread_stats(static_cast<std::size_t>(threads));
  std::vector<std::vector<std::pair<VertexId, VertexId>>> duplicates(
      static_cast<std::size_t>(threads));
  std::vector<std::uint64_t> predicate_calls(static_cast<std::size_t>(threads), 0);
  std::vector<std::uint64_t> location_steps(static_cast<std::size_t>(threads), 0);
  std::vector<std::uint64_t> walk_fallbacks(static_cast<std::size_t>(threads), 0);
  std::atomic<std::uint64_t> progress{0};
  std::vector<std::vector<TetId>> suspicious(static_cast<std::size_t>(threads));
  LockTable table(threads);
  // Walk mode: dead slots are reused, after the epochs say no operation can reach them.
  EpochDomain epochs(threads + 1);  // the batch method: its locating threads and its inserter
  std::atomic<std::size_t> shared_index{0};
  const Distribution distribution = effective_distribution(options);
  const bool dynamic = distribution == Distribution::Dynamic;
  const bool walk = options.location == Location::Walk;
  // Walk mode: the points are stored in one BRIO and Hilbert order (triangulate.cpp), and the
  // distributions keep the order of `order` inside each share, so each thread's share is in BRIO
  // rounds, each along the Hilbert curve, already: a subsequence of a round is a random sample of
  // the share, and of a curve order a curve order. Its points lie close in memory too, which the
  // per-thread orders of the input's ids did not give (the walk's and the tests' reads of points
  // missed the cache: 1.3x the sequential run's time on one thread, 1M points).
  const bool batch_method = options.method == Method::Batch;  // splits among its locators
  auto parts = dynamic || batch_method ? std::vector<std::vector<std::uint32_t>>{}
                                       : distribute(points, order, distribution, threads);
  std::mutex global;  // pessimistic: the one critical section
  // A stall is a failure; its limit grows with the work, to a minute at most (an insertion takes
  // micro- to milliseconds, so 10 s without one finishing anywhere is no slow run).
  const double watchdog_limit =
      options.watchdog_seconds > 0
          ? options.watchdog_seconds
          : std::min(60.0, 10.0 + 1e-4 * static_cast<double>(order.size()));

  // The first exception of any thread (the store's limit, out of memory) stops every thread and
  // is rethrown after they are joined: an exception must not leave a thread's function.
  std::mutex error_mutex;
  std::exception_ptr first_error;
  auto record_error = [&] {
    {
      std::lock_guard<std::mutex> guard(error_mutex);
      if (!first_error) first_error = std::current_exception();
    }
    table.stop.store(true);
  };

  auto finish_thread = [&](int i, const auto& dt) {
    duplicates[static_cast<std::size_t>(i)] = dt.duplicates();
    predicate_calls[static_cast<std::size_t>(i)] = dt.predicate_calls();
    location_steps[static_cast<std::size_t>(i)] = dt.location_steps();
    walk_fallbacks[static_cast<std::size_t>(i)] = dt.walk_fallbacks();
  };

  auto worker_body = [&](int i) {
    const auto index = static_cast<std::size_t>(i);
    ThreadStats& counters = stats.threads[index];
    WorkSource work(dynamic ? nullptr : &parts[index], dynamic ? &shared_index : nullptr, &order);
    SlotReclaimer reclaimer(epochs, i);
    SlotReclaimer* reuse = walk ? &reclaimer : nullptr;
    if (options.method == Method::Pessimistic) {
      IncrementalDelaunay<K, NoSync> dt(mesh, options, thread_stats[index], no_sync, reuse);
      while (const auto v = work.next()) {
        if (table.stop.load(std::memory_order_relaxed)) break;
        // Lock-free descent (timed and counted as location); the leaf-level part, subdivision
        // and legalization in one section. Waiting for the section is in no phase.
        dt.set_location_hint(dt.locate_only(*v));
        std::lock_guard<std::mutex> guard(global);
        count_outcome<decltype(dt)>(dt.insert(*v), counters);
        progress.fetch_add(1, std::memory_order_relaxed);
      }
      finish_thread(i, dt);
      return;
    }
    const auto mode = options.method == Method::OptimisticPrevent ? OptimisticSync::Mode::Prevent
                      : options.method == Method::Burglary        ? OptimisticSync::Mode::Burglary
                                                                  : OptimisticSync::Mode::Detect;
    OptimisticSync sync(mesh, table, static_cast<std::uint32_t>(i + 1), mode, counters,
                        options.stress);
    IncrementalDelaunay<K, OptimisticSync> dt(mesh, options, thread_stats[index], sync, reuse);
    int consecutive_give_ups = 0;
    while (const auto v = work.next()) {
      if (table.stop.load(std::memory_order_relaxed)) break;
      const auto outcome = dt.insert(*v);
      count_outcome<decltype(dt)>(outcome, counters);
      if (outcome == decltype(dt)::Outcome::GaveUp || outcome == decltype(dt)::Outcome::Unlocated) {
        const int limit = outcome == decltype(dt)::Outcome::Unlocated
                              ? WorkSource::kMaxLocationAttempts
                              : WorkSource::kMaxLockAttempts;
        const bool abandoned = !work.retry_later(*v, limit);
        if (abandoned) ++counters.abandoned;
        // Progress for the watchdog: an abandonment, and a failed location too, since a point
        // has at most kMaxLocationAttempts of them (bounded work: the last rounds over an inexact
        // kernel's hopeless points, slow under a sanitizer, are no stall). Not a lock conflict:
        // threads can give up against each other forever.
        if (abandoned || outcome == decltype(dt)::Outcome::Unlocated) {
          progress.fetch_add(1, std::memory_order_relaxed);
        }
        // Back off before the next attempt: the thread that waited for our locks must get them
        // before we take them again, or the two can give up against each other forever; and a
        // rollback that raced our descent must finish before we descend again.
        const int shift = std::min(consecutive_give_ups++, 10);
        std::this_thread::sleep_for(std::chrono::microseconds(1 << shift));
      } else {
        consecutive_give_ups = 0;
        progress.fetch_add(1, std::memory_order_relaxed);
      }
    }
    finish_thread(i, dt);
    suspicious[index] = sync.suspicious();
  };
  auto worker = [&](int i) {
    try {
      worker_body(i);
    } catch (...) {
      record_error();
    }
  };

  auto batch = [&] {
    // Locating threads feed a bounded queue with (point, DAG node that contains it); one thread
    // subdivides and legalizes.
    const int locators = std::max(1, threads - 1);
    const std::size_t capacity = 1024;
    // The queue's lock is taken once per kPush points pushed and kTake points taken, and a
    // locating thread that finds the queue full sleeps until a take leaves it half empty (all
    // sleepers are woken then, and each has room for its points): taken once per point, with a
    // wake-up at every point taken from a full queue, the lock and the wake-ups cost the
    // inserting thread more than the queue saved it (docs/performance.md, the batch method).
    constexpr std::size_t kPush = 16;
    constexpr std::size_t kTake = 64;
    struct Located {
      std::uint32_t point;
      TetId hint;
      int locator;
    };
    std::deque<Located> queue;
    std::mutex queue_mutex;
    std::condition_variable not_full;
    std::condition_variable not_empty;
    int active_locators = locators;
    std::atomic<std::uint64_t> full_waits{0};
    std::uint64_t empty_waits = 0;
    // The inserting thread's lists, allocated before the locating threads start, so that their
    // allocations cannot fail while those run (an exception outside the loops' handlers then
    // would leave the threads joinable).
    std::vector<Located> taken;
    taken.reserve(kTake);
    std::vector<TetId> start_of(static_cast<std::size_t>(locators), kNoTet);
    auto locator_parts = dynamic ? std::vector<std::vector<std::uint32_t>>{}
                                 : distribute(points, order, distribution, locators);
    std::vector<std::thread> pool;
    std::vector<TriangulationStats> locator_stats(static_cast<std::size_t>(locators));
    for (int i = 0; i < locators; ++i) {
      pool.emplace_back([&, i] {
        const auto index = static_cast<std::size_t>(i);
        try {
          SlotReclaimer reclaimer(epochs, i + 1);
          IncrementalDelaunay<K, NoSync> dt(mesh, options, locator_stats[index], no_sync,
                                            walk ? &reclaimer : nullptr);
          WorkSource work(dynamic ? nullptr : &locator_parts[index],
                          dynamic ? &shared_index : nullptr, &order);
          std::vector<Located> located;
          located.reserve(kPush);
          for (bool more = true; more;) {
            located.clear();
            while (located.size() < kPush) {
              const auto v = work.next();
              if (!v) {
                more = false;
                break;
              }
              const TetId hint = dt.locate_only(*v);
              dt.end_operation();  // the inserting thread checks the hint is still alive
              located.push_back({*v, hint, i});
            }
            if (located.empty()) break;
            std::unique_lock<std::mutex> lock(queue_mutex);
            if (queue.size() + located.size() > capacity) {
              full_waits.fetch_add(1, std::memory_order_relaxed);
              not_full.wait(lock, [&] {
                return queue.size() + located.size() <= capacity || table.stop.load();
              });
            }
            if (table.stop.load()) break;
            // The inserting thread waits only on an empty queue.
            const bool was_empty = queue.empty();
            queue.insert(queue.end(), located.begin(), located.end());
            if (was_empty) not_empty.notify_one();
          }
          // Merged into the run's stats after the join (the descent's seconds are already there).
          locator_stats[index].predicate_calls = dt.predicate_calls();
          locator_stats[index].location_steps = dt.location_steps();
          locator_stats[index].walk_fallbacks = dt.walk_fallbacks();
        } catch (...) {
          record_error();
        }
        std::lock_guard<std::mutex> lock(queue_mutex);
        --active_locators;
        not_empty.notify_all();
      });
    }
    SlotReclaimer reclaimer(epochs, 0);
    IncrementalDelaunay<K, NoSync> dt(mesh, options, thread_stats[0], no_sync,
                                      walk ? &reclaimer : nullptr);
    ThreadStats& counters = stats.threads[0];
    // Walk mode: the queue interleaves the locating threads' points, each thread's along its own
    // share's curve, so the tetrahedron the last insertion created is in another thread's share
    // as often as not. The inserting thread keeps one walk start per locating thread: what the
    // insertion of that thread's previous point created. A hint is up to a queue's length of
    // insertions old, so its slot may have died or been reused anywhere: of the two candidates
    // that are alive, the walk starts from the one whose first finite vertex is nearer the point
    // (only this thread writes the mesh, so what it reads is current).
    auto squared_distance = [&](TetId t, std::uint32_t p) {
      const Tet& tet = mesh.tets[t];
      const VertexId v = tet.vertex[0] != kInfiniteVertex ? tet.vertex[0] : tet.vertex[1];
      const Point3& a = mesh.points[v];
      const Point3& b = mesh.points[p];
      return (a.x - b.x) * (a.x - b.x) + (a.y - b.y) * (a.y - b.y) + (a.z - b.z) * (a.z - b.z);
    };
    auto alive = [&](TetId t) {
      return t != kNoTet && mesh.tets.is_alive(t, std::memory_order_relaxed);
    };
    std::size_t next_taken = 0;
    while (!table.stop.load(std::memory_order_relaxed)) {
      if (next_taken == taken.size()) {
        taken.clear();
        next_taken = 0;
        std::unique_lock<std::mutex> lock(queue_mutex);
        if (queue.empty() && active_locators > 0) {
          ++empty_waits;
          not_empty.wait(
              lock, [&] { return !queue.empty() || active_locators == 0 || table.stop.load(); });
        }
        if (queue.empty() || table.stop.load()) break;
        const std::size_t before = queue.size();
        const auto count = static_cast<std::ptrdiff_t>(std::min(before, kTake));
        taken.assign(queue.begin(), queue.begin() + count);
        queue.erase(queue.begin(), queue.begin() + count);
        // A locating thread waits only at a queue of more than capacity - kPush points, so one
        // take in every descent from there crosses half (none is missed).
        if (before > capacity / 2 && queue.size() <= capacity / 2) not_full.notify_all();
      }
      const Located item = taken[next_taken++];
      TetId start = item.hint;
      TetId& own = start_of[static_cast<std::size_t>(item.locator)];
      if (walk && alive(own) &&
          (!alive(start) ||
           squared_distance(own, item.point) < squared_distance(start, item.point))) {
        start = own;
      }
      dt.set_location_hint(start);
      try {
        count_outcome<decltype(dt)>(dt.insert(item.point), counters);
      } catch (...) {
        record_error();
        break;
      }
      if (walk) own = dt.walk_start();
      progress.fetch_add(1, std::memory_order_relaxed);
    }
    {
      std::lock_guard<std::mutex> lock(queue_mutex);
      not_full.notify_all();
    }
    for (auto& t : pool) t.join();
    finish_thread(0, dt);
    stats.queue_full_waits = full_waits.load();
    stats.queue_empty_waits = empty_waits;
    // The locating threads' descents are the batch method's location: their seconds (summed, like
    // every phase), predicate calls and steps join the inserting thread's.
    for (const auto& ls : locator_stats) {
      thread_stats[0].seconds.location += ls.seconds.location;
      predicate_calls[0] += ls.predicate_calls;
      location_steps[0] += ls.location_steps;
      walk_fallbacks[0] += ls.walk_fallbacks;
    }
  };

  {
    Watchdog watchdog(watchdog_limit, progress, table.stop);
    if (options.method == Method::Batch) {
      stats.threads.assign(1, ThreadStats{});
      batch();
    } else {
      std::vector<std::thread> pool;
      for (int i = 0; i < threads; ++i) pool.emplace_back(worker, i);
      for (auto& t : pool) t.join();
    }
    if (first_error) std::rethrow_exception(first_error);
    if (watchdog.fired()) {
      char limit[32];
      std::snprintf(limit, sizeof limit, "%.1f", watchdog_limit);
      throw TriangulationError(std::string("watchdog: no insertion finished for ") + limit +
                               " s; the run was stopped (a deadlock or lost wake-up)");
    }
  }

  std::vector<std::pair<VertexId, VertexId>> all_duplicates;
  for (std::size_t i = 0; i < thread_stats.size(); ++i) {
    add_phase_times(stats, thread_stats[i]);
    all_duplicates.insert(all_duplicates.end(), duplicates[i].begin(), duplicates[i].end());
    stats.predicate_calls += predicate_calls[i];
    stats.location_steps += location_steps[i];
    stats.walk_fallbacks += walk_fallbacks[i];
  }
  for (const ThreadStats& t : stats.threads) {
    stats.inserted += t.inserted;
    stats.duplicates += t.duplicates;
    stats.abandoned_insertions += t.abandoned;
  }
  stats.dag_nodes = walk ? 0 : mesh.tets.size();
  stats.store_slots = mesh.tets.size();
  if (options.method == Method::Burglary) {
    std::vector<TetId> marks;
    for (const auto& m : suspicious) marks.insert(marks.end(), m.begin(), m.end());
    return post_check<K>(mesh, input_count, marks, full_order, first, skip_first, all_duplicates,
                         options, stats);
  }
  if (splays(options.repair))
    splay_shared_mesh(mesh, {}, options.kernel != KernelKind::Fast, options.threads, stats.splay);
  const auto output_start = Clock::now();
  std::vector<Tetrahedron> result =
      mesh.take_finite_tetrahedra(static_cast<VertexId>(input_count), all_duplicates, threads);
  stats.seconds.output += std::chrono::duration<double>(Clock::now() - output_start).count();
  return result;
}

#define DTLAB_INSTANTIATE(K)                                                      \
  template std::vector<Tetrahedron> run_parallel<K>(                              \
      const std::vector<Point3>&, std::size_t, const std::vector<std::uint32_t>&, \
      const std::array<std::uint32_t, 4>&, bool, const TriangulateOptions&, TriangulationStats&);
DTLAB_FOR_EACH_KERNEL(DTLAB_INSTANTIATE)
#undef DTLAB_INSTANTIATE

}  // namespace dtlab::engine
