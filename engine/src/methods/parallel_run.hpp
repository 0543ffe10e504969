#pragma once
// What every parallel method's run shares (pessimistic.cpp, optimistic_*.cpp, burglary.cpp,
// batch.cpp): the shared mesh and its first tetrahedron, the points to insert, the lock table and
// the epochs of slot reuse, the threads under the watchdog with the first error rethrown, the
// per-thread results summed into the run's stats, and the output. A method adds only how its
// threads insert.
#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <exception>
#include <memory>
#include <mutex>
#include <string>
#include <utility>
#include <vector>

#include "insertion/inserter.hpp"
#include "location/location_policy.hpp"
#include "mesh/shared_mesh.hpp"
#include "mesh/slot_reclaimer.hpp"
#include "methods/distribution.hpp"
#include "methods/lock_table.hpp"
#include "methods/method_input.hpp"
#include "methods/progress_counters.hpp"
#include "methods/watchdog.hpp"
#include "methods/work_source.hpp"
#include "repair/splay_repair.hpp"
#include "support/parallel_ranges.hpp"

namespace dtlab::engine {

// Counts an insertion's outcome in its thread's counters.
template <class Outcome>
void count_outcome(Outcome outcome, ThreadStats& t) {
  switch (outcome) {
    case Outcome::Inserted:
      ++t.inserted;
      break;
    case Outcome::Duplicate:
      ++t.duplicates;
      break;
    case Outcome::Abandoned:
      ++t.abandoned;
      break;
    case Outcome::GaveUp:
    case Outcome::Unlocated:
      ++t.give_ups;
      break;
  }
}

template <class K>
class ParallelRun {
 public:
  using Duplicates = std::vector<std::pair<VertexId, VertexId>>;

  // `inserting_threads`: the threads that write the mesh (each an entry of stats.threads).
  // `lock_words`: a lock word per slot (the lock methods; the lock grid keeps only the aliveness
  // bit in it); without (the partitioned method, whose threads read no record another thread
  // writes), aliveness is the record's last vertex, as in the sequential walk.
  ParallelRun(const MethodInput& input, TriangulationStats& stats, int inserting_threads,
              bool lock_words = true)
      : input(input),
        options(input.options),
        stats(stats),
        threads(std::max(1, options.threads)),
        location(resolve_location(options.location)),
        distribution(effective_distribution(options)),
        mesh(input.points),
        table(threads),
        // The batch method's locating threads and its inserter: threads + 1 at the most.
        epochs(threads + 1),
        thread_stats_(static_cast<std::size_t>(threads)),
        duplicates_(static_cast<std::size_t>(threads)),
        predicate_calls_(static_cast<std::size_t>(threads), 0),
        location_steps_(static_cast<std::size_t>(threads), 0),
        walk_fallbacks_(static_cast<std::size_t>(threads), 0) {
    if (options.max_tetrahedra > 0) mesh.tets.set_capacity(options.max_tetrahedra);
    mesh.tets.keep_children(location.history);
    mesh.tets.keep_lock_words(lock_words);
    TriangulationStats start_stats;
    NoSync no_sync;
    IncrementalDelaunay<K, NoSync>(mesh, options, start_stats, no_sync)
        .start(input.first[0], input.first[1], input.first[2], input.first[3]);
    // An empty order is the identity: in walk mode the driver stores the points in one BRIO and
    // Hilbert order, so that ids are insertion order.
    const std::size_t listed = input.order.empty() ? input.input_count : input.order.size();
    order.reserve(listed);
    for (std::size_t i = 0; i < listed; ++i) {
      const auto v = input.order.empty() ? static_cast<std::uint32_t>(i) : input.order[i];
      if (input.skip_first && (v == input.first[0] || v == input.first[1] || v == input.first[2] ||
                               v == input.first[3])) {
        continue;
      }
      order.push_back(v);
    }
    if (input.skip_first) stats.inserted += 4;
    stats.threads.assign(static_cast<std::size_t>(inserting_threads), ThreadStats{});
    // A stall is a failure; its limit grows with the work, to a minute at most (an insertion
    // takes micro- to milliseconds, so 10 s without one finishing anywhere is no slow run).
    watchdog_limit_ = options.watchdog_seconds > 0
                          ? options.watchdog_seconds
                          : std::min(60.0, 10.0 + 1e-4 * static_cast<double>(order.size()));
  }
  ParallelRun(const ParallelRun&) = delete;
  ParallelRun& operator=(const ParallelRun&) = delete;

  // Splits the points among `parts` threads (before they start; nothing to split for the dynamic
  // distribution, whose threads take the next point from a shared index).
  void split_among(int parts) {
    if (distribution != Distribution::Dynamic) {
      parts_ = distribute(input.points, order, distribution, parts);
    }
  }
  // Thread i's share of the points, after split_among.
  WorkSource work_for(int i) {
    if (distribution == Distribution::Dynamic) return WorkSource(nullptr, &shared_index_, &order);
    return WorkSource(&parts_[static_cast<std::size_t>(i)], nullptr, &order);
  }
  // Thread i's stats for its inserter (summed into the run's by finish()).
  TriangulationStats& thread_stats(int i) { return thread_stats_[static_cast<std::size_t>(i)]; }

  // Runs `body` under the watchdog; a thread's exception (record_error) or the watchdog's stop is
  // thrown once `body` has joined its threads. One watchdog thread for the run, started at the
  // first body and paused between bodies.
  template <class Body>
  void watched(Body&& body) {
    if (!watchdog_) {
      watchdog_ =
          std::make_unique<Watchdog>(watchdog_limit_, progress, table.stop, options.monitor);
    } else {
      watchdog_->resume();
    }
    Watchdog& watchdog = *watchdog_;
    struct PauseAtEnd {  // on every way out of body
      Watchdog& watchdog;
      ~PauseAtEnd() { watchdog.pause(); }
    } pause_at_end{watchdog};
    body();
    // A body shorter than the watchdog's period (a partitioned pass) is looked at here.
    if (options.monitor != nullptr) {
      options.monitor->done.store(progress.total(), std::memory_order_relaxed);
      if (options.monitor->cancel.load(std::memory_order_relaxed)) throw RunCancelled();
    }
    if (watchdog.cancelled()) throw RunCancelled();
    if (first_error_) std::rethrow_exception(first_error_);
    if (watchdog.fired()) {
      char limit[32];
      std::snprintf(limit, sizeof limit, "%.1f", watchdog_limit_);
      throw RunFailed(std::string("watchdog: no insertion finished for ") + limit +
                      " s; the run was stopped (a deadlock or lost wake-up)");
    }
  }
  // body(i) for i in [0, threads), each on its own thread at once (the last on this one), all
  // ended on return; an exception leaving body stops the others.
  template <class Body>
  void on_threads(Body&& body) {
    watched([&] {
      // One index a thread: the run's pool (the last on this thread), or threads started for
      // this call (support/parallel_ranges.hpp).
      in_parallel_ranges(
          static_cast<std::size_t>(threads), threads,
          [&](std::size_t, std::size_t, std::size_t i) {
            try {
              body(static_cast<int>(i));
            } catch (...) {
              record_error();
            }
          },
          /*minimum=*/0);
    });
  }
  // The first exception of any thread (the store's limit, out of memory) stops every thread and
  // is rethrown after they are joined: an exception must not leave a thread's function. Called
  // from a catch block.
  void record_error() {
    {
      std::lock_guard<std::mutex> guard(error_mutex_);
      if (!first_error_) first_error_ = std::current_exception();
    }
    table.stop.store(true);
  }
  [[nodiscard]] bool stopping() const { return table.stop.load(std::memory_order_relaxed); }
  // An insertion finished (or a point was abandoned) on thread i: the watchdog's sign of life.
  void progressed(int i) { progress.add(i); }

  // What thread i's inserter found and counted, for finish().
  template <class Inserter>
  void finish_thread(int i, const Inserter& dt) {
    const auto index = static_cast<std::size_t>(i);
    duplicates_[index] = dt.duplicates();
    predicate_calls_[index] += dt.predicate_calls();
    location_steps_[index] += dt.location_steps();
    walk_fallbacks_[index] += dt.walk_fallbacks();
  }
  // Work a helper thread did for inserting thread i (the batch method's locating threads).
  void add_location(int i, const TriangulationStats& helper, std::uint64_t predicate_calls,
                    std::uint64_t location_steps, std::uint64_t walk_fallbacks) {
    const auto index = static_cast<std::size_t>(i);
    thread_stats_[index].seconds.location += helper.seconds.location;
    predicate_calls_[index] += predicate_calls;
    location_steps_[index] += location_steps;
    walk_fallbacks_[index] += walk_fallbacks;
  }

  // After the threads: their phase times, flips and counters summed into the run's stats.
  // Returns the duplicates every thread found, (skipped point, its vertex).
  Duplicates finish() {
    Duplicates all;
    for (std::size_t i = 0; i < thread_stats_.size(); ++i) {
      const TriangulationStats& part = thread_stats_[i];
      stats.seconds.location += part.seconds.location;
      stats.seconds.subdivision += part.seconds.subdivision;
      stats.seconds.legalization += part.seconds.legalization;
      stats.flips.s23 += part.flips.s23;
      stats.flips.s32 += part.flips.s32;
      stats.flips.s22 += part.flips.s22;
      stats.flips.s44 += part.flips.s44;
      stats.cavity.insertions += part.cavity.insertions;
      stats.cavity.tetrahedra_removed += part.cavity.tetrahedra_removed;
      stats.cavity.fallbacks += part.cavity.fallbacks;
      all.insert(all.end(), duplicates_[i].begin(), duplicates_[i].end());
      stats.predicate_calls += predicate_calls_[i];
      stats.location_steps += location_steps_[i];
      stats.walk_fallbacks += walk_fallbacks_[i];
    }
    for (const ThreadStats& t : stats.threads) {
      stats.inserted += t.inserted;
      stats.duplicates += t.duplicates;
      stats.abandoned_insertions += t.abandoned;
    }
    stats.dag_nodes = location.history ? mesh.tets.size() : 0;
    stats.store_slots = mesh.tets.size();
    return all;
  }

  // The finite tetrahedra, after star splaying where options.repair asks, releasing the store.
  std::vector<Tetrahedron> output(const Duplicates& duplicates) {
    if (splays(options.repair)) {
      splay_shared_mesh(mesh, {}, options.kernel != KernelKind::Fast, options.threads, stats.splay);
    }
    const auto output_start = std::chrono::steady_clock::now();
    std::vector<Tetrahedron> result =
        mesh.take_finite_tetrahedra(static_cast<VertexId>(input.input_count), duplicates, threads);
    stats.seconds.output +=
        std::chrono::duration<double>(std::chrono::steady_clock::now() - output_start).count();
    return result;
  }

  const MethodInput& input;
  const TriangulateOptions& options;
  TriangulationStats& stats;
  const int threads;
  const LocationPolicy location;
  const Distribution distribution;
  SharedMesh mesh;
  std::vector<std::uint32_t> order;  // the points to insert, in order (the first four left out)
  LockTable table;
  EpochDomain epochs;  // slot reuse: dead slots reused after the epochs say nobody reads them
  ProgressCounters progress{threads};  // the batch method counts on its inserter, thread 0

 private:
  std::vector<TriangulationStats> thread_stats_;
  std::vector<Duplicates> duplicates_;
  std::vector<std::uint64_t> predicate_calls_;
  std::vector<std::uint64_t> location_steps_;
  std::vector<std::uint64_t> walk_fallbacks_;
  std::vector<std::vector<std::uint32_t>> parts_;
  std::atomic<std::size_t> shared_index_{0};
  double watchdog_limit_ = 0;
  std::mutex error_mutex_;
  std::exception_ptr first_error_;
  std::unique_ptr<Watchdog> watchdog_;  // last: it reads `progress` and `table` until it ends
};

// One thread's inserter on the run's mesh, with the thread's side of the epochs where the
// location mode reuses slots and other threads may read them (not for a policy that confines its
// reads: insertion/sync.hpp). `epoch_slot`: the thread's announcement in run.epochs; `stats`:
// where its inserter counts. A cache line to itself (its walk start and counters are written at
// every insertion), as LocalUndoLog: the partitioned method allocates the threads' one after the
// other.
template <class K, class Sync>
struct alignas(64) ThreadInserter {
  ThreadInserter(ParallelRun<K>& run, int epoch_slot, TriangulationStats& stats, Sync& sync)
      : reclaimer(run.epochs, epoch_slot),
        dt(run.mesh, run.options, stats, sync,
           run.location.slot_reuse && !kConfinedReads<Sync> ? &reclaimer : nullptr) {}
  SlotReclaimer reclaimer;
  IncrementalDelaunay<K, Sync> dt;
};

}  // namespace dtlab::engine
