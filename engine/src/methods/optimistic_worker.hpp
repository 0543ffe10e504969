#pragma once
// The inserting threads of the methods that give an insertion up on a lock conflict
// (optimistic-detect, optimistic-prevent, burglary, lock-grid): each inserts its share with its
// own lock policy; a point given up is retried after the rest, once the thread has backed off, and
// abandoned after too many tries.
#include <algorithm>
#include <chrono>
#include <cstdint>
#include <thread>

#include "dtlab/common/random.hpp"
#include "methods/kernel_dispatch.hpp"
#include "methods/parallel_run.hpp"

namespace dtlab::engine {

// A thread's sleeps after consecutive give-ups: after the (k+1)-th in a row, drawn at random
// from 2^k / 2 to 2^k us (at least 1). Random, so that threads that gave up against each other do
// not come back in step and meet again; growing to 2^14 us (16 ms), as long as a slow insertion
// takes: with every predicate handed to GMP (coordinates 1e-300 beside 1e300) one takes about
// 1 ms on a CPU of its own and several times that with threads sharing it, and with a fixed
// sleep capped at 1 ms (as until 2026-11-30) 16 such threads on 2 CPUs gave up against each other
// up to 25 times a point and once went 10 s without an insertion (performance-log.md, twentieth
// session).
constexpr int kMostBackoffShift = 14;
// A failed location (an inexact kernel's, mostly, which every retry repeats) backs off to 1 ms
// at most, as before: its kMaxLocationAttempts tries take under 0.1 s.
constexpr int kMostLocationBackoffShift = 10;
class Backoff {
 public:
  explicit Backoff(std::uint64_t seed) : random_(seed) {}
  // Microseconds to sleep after give-up number shift + 1 in a row: in [2^shift / 2, 2^shift],
  // at least 1.
  std::uint32_t draw(int shift) {
    const std::uint32_t half = (1U << shift) / 2;
    return std::max<std::uint32_t>(1, half + static_cast<std::uint32_t>(random_.below(half + 1)));
  }

 private:
  common::Random random_;  // the project's seeded generator (dtlab/common/random.hpp)
};

// Runs run.threads threads, thread i with the policy `make_sync(i, counters)` returns (counters:
// the thread's ThreadStats); `done(i, sync)` sees thread i's policy after its last insertion
// (burglary takes its marks).
template <class K, class MakeSync, class Done>
void insert_with_policies(ParallelRun<K>& run, MakeSync&& make_sync, Done&& done) {
  run.split_among(run.threads);
  run.on_threads([&](int i) {
    // Counted in the thread's own object, stored once at the end: the threads' entries of
    // stats.threads share cache lines, and a count per insertion there bounced them between cores.
    ThreadStats counters;
    WorkSource work = run.work_for(i);
    auto sync = make_sync(i, counters);
    using Sync = decltype(sync);
    ThreadInserter<K, Sync> thread(run, i, run.thread_stats(i), sync);
    auto& dt = thread.dt;
    using Outcome = typename IncrementalDelaunay<K, Sync>::Outcome;
    int consecutive_give_ups = 0;
    Backoff backoff(static_cast<std::uint64_t>(i));
    while (const auto v = work.next()) {
      if (run.stopping()) break;
      const Outcome outcome = dt.insert(*v);
      count_outcome(outcome, counters);
      if (outcome == Outcome::GaveUp || outcome == Outcome::Unlocated) {
        const int limit = outcome == Outcome::Unlocated ? WorkSource::kMaxLocationAttempts
                                                        : WorkSource::kMaxLockAttempts;
        const bool abandoned = !work.retry_later(*v, limit);
        if (abandoned) ++counters.abandoned;
        // Progress for the watchdog: an abandonment, and a failed location too, since a point
        // has at most kMaxLocationAttempts of them (bounded work: the last rounds over an inexact
        // kernel's hopeless points, slow under a sanitizer, are no stall). Not a lock conflict:
        // threads can give up against each other forever.
        if (abandoned || outcome == Outcome::Unlocated) run.progressed(i);
        // Back off before the next attempt: the thread that waited for our locks must get them
        // before we take them again, or the two can give up against each other forever; and a
        // rollback that raced our descent must finish before we descend again.
        const int most =
            outcome == Outcome::Unlocated ? kMostLocationBackoffShift : kMostBackoffShift;
        const int shift = std::min(consecutive_give_ups++, most);
        std::this_thread::sleep_for(std::chrono::microseconds(backoff.draw(shift)));
      } else {
        consecutive_give_ups = 0;
        run.progressed(i);
      }
    }
    run.finish_thread(i, dt);
    done(i, sync);
    run.stats.threads[static_cast<std::size_t>(i)] = counters;
  });
}

// The optimistic methods' threads: thread i's policy is Sync with lock id i + 1.
template <class Sync, class K, class Done>
void insert_optimistically(ParallelRun<K>& run, Done&& done) {
  insert_with_policies(
      run,
      [&](int i, ThreadStats& counters) {
        return Sync(run.mesh, run.table, static_cast<std::uint32_t>(i + 1), counters,
                    run.options.stress);
      },
      done);
}

// An optimistic method's whole run with policy Sync, for the methods with nothing after their
// threads but the output (optimistic-detect, optimistic-prevent).
template <class Sync>
std::vector<Tetrahedron> run_optimistic(const MethodInput& input, TriangulationStats& stats) {
  return with_kernel(input.options, [&]<class K>() {
    ParallelRun<K> run(input, stats, std::max(1, input.options.threads));
    insert_optimistically<Sync>(run, [](int, const Sync&) {});
    return run.output(run.finish());
  });
}

}  // namespace dtlab::engine
