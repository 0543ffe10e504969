// The batch method, which the paper described (Sect. 5) and never built: threads - 1 locating
// threads find each point's tetrahedron without a lock and feed a bounded queue with (point,
// where it was found); one inserting thread subdivides and legalizes, so nothing is ever locked
// (docs/design.md, "The batch method").
#include <algorithm>
#include <atomic>
#include <condition_variable>
#include <cstdint>
#include <deque>
#include <mutex>
#include <thread>
#include <vector>

#include "methods/kernel_dispatch.hpp"
#include "methods/method_input.hpp"
#include "methods/parallel_run.hpp"

namespace dtlab::engine {
namespace {

// A located point: where a locating thread found it, and which thread that was.
struct Located {
  std::uint32_t point;
  TetId hint;
  int locator;
};

// The bounded queue between the locating threads and the inserting one. Its lock is taken once
// per kPush points pushed and kTake points taken, and a locating thread that finds the queue full
// sleeps until a take leaves it half empty (all sleepers are woken then, and each has room for its
// points): taken once per point, with a wake-up at every point taken from a full queue, the lock
// and the wake-ups cost the inserting thread more than the queue saved it (docs/performance-log.md,
// the batch method).
class BatchQueue {
 public:
  static constexpr std::size_t kCapacity = 1024;
  static constexpr std::size_t kPush = 16;
  static constexpr std::size_t kTake = 64;

  BatchQueue(int locators, const std::atomic<bool>& stop) : active_(locators), stop_(stop) {}

  // A locating thread's points; false when the run is stopping.
  bool push(const std::vector<Located>& located) {
    std::unique_lock<std::mutex> lock(mutex_);
    if (queue_.size() + located.size() > kCapacity) {
      full_waits_.fetch_add(1, std::memory_order_relaxed);
      not_full_.wait(lock,
                     [&] { return queue_.size() + located.size() <= kCapacity || stop_.load(); });
    }
    if (stop_.load()) return false;
    // The inserting thread waits only on an empty queue.
    const bool was_empty = queue_.empty();
    queue_.insert(queue_.end(), located.begin(), located.end());
    if (was_empty) not_empty_.notify_one();
    return true;
  }
  // A locating thread is done (or failed).
  void locator_done() {
    std::lock_guard<std::mutex> lock(mutex_);
    --active_;
    not_empty_.notify_all();
  }
  // Up to kTake points into `taken` (cleared first); false when none will come any more.
  bool take(std::vector<Located>& taken) {
    taken.clear();
    std::unique_lock<std::mutex> lock(mutex_);
    if (queue_.empty() && active_ > 0) {
      ++empty_waits_;
      not_empty_.wait(lock, [&] { return !queue_.empty() || active_ == 0 || stop_.load(); });
    }
    if (queue_.empty() || stop_.load()) return false;
    const std::size_t before = queue_.size();
    const auto count = static_cast<std::ptrdiff_t>(std::min(before, kTake));
    taken.assign(queue_.begin(), queue_.begin() + count);
    queue_.erase(queue_.begin(), queue_.begin() + count);
    // A locating thread waits only at a queue of more than capacity - kPush points, so one take
    // in every descent from there crosses half (none is missed).
    if (before > kCapacity / 2 && queue_.size() <= kCapacity / 2) not_full_.notify_all();
    return true;
  }
  // The inserting thread stopped taking: no locating thread may sleep on a full queue any more.
  void close() {
    std::lock_guard<std::mutex> lock(mutex_);
    not_full_.notify_all();
  }
  [[nodiscard]] std::uint64_t full_waits() const { return full_waits_.load(); }
  [[nodiscard]] std::uint64_t empty_waits() const { return empty_waits_; }

 private:
  std::deque<Located> queue_;
  std::mutex mutex_;
  std::condition_variable not_full_;
  std::condition_variable not_empty_;
  int active_;
  const std::atomic<bool>& stop_;
  std::atomic<std::uint64_t> full_waits_{0};
  std::uint64_t empty_waits_ = 0;
};

// What a locating thread measured: its descents are the batch method's location, so their
// seconds (summed, like every phase), predicate calls and steps join the inserting thread's once
// the threads are joined.
struct LocatorCounts {
  TriangulationStats stats;
  std::uint64_t predicate_calls = 0;
  std::uint64_t location_steps = 0;
  std::uint64_t walk_fallbacks = 0;
};

// Locating thread i: locates its share of the points, kPush at a time, into the queue.
template <class K>
void locate_into(ParallelRun<K>& run, BatchQueue& queue, int i, LocatorCounts& counts) {
  try {
    NoSync no_sync;
    ThreadInserter<K, NoSync> thread(run, i + 1, counts.stats, no_sync);
    auto& dt = thread.dt;
    WorkSource work = run.work_for(i);
    std::vector<Located> located;
    located.reserve(BatchQueue::kPush);
    for (bool more = true; more;) {
      located.clear();
      while (located.size() < BatchQueue::kPush) {
        const auto v = work.next();
        if (!v) {
          more = false;
          break;
        }
        const TetId hint = dt.locate_only(*v);
        dt.end_operation();  // the inserting thread checks the hint is still alive
        located.push_back({*v, hint, i});
      }
      if (located.empty() || !queue.push(located)) break;
    }
    counts.predicate_calls = dt.predicate_calls();
    counts.location_steps = dt.location_steps();
    counts.walk_fallbacks = dt.walk_fallbacks();
  } catch (...) {
    run.record_error();
  }
  queue.locator_done();
}

// The inserting thread's walk starts (walk mode). The queue interleaves the locating threads'
// points, each thread's along its own share's curve, so the tetrahedron the last insertion
// created is in another thread's share as often as not. The inserting thread keeps one walk start
// per locating thread: what the insertion of that thread's previous point created. A hint is up to
// a queue's length of insertions old, so its slot may have died or been reused anywhere: of the
// two candidates that are alive, the walk starts from the one whose first finite vertex is nearer
// the point (only this thread writes the mesh, so what it reads is current).
class WalkStarts {
 public:
  WalkStarts(const SharedMesh& mesh, int locators)
      : mesh_(mesh), start_of_(static_cast<std::size_t>(locators), kNoTet) {}
  TetId start_for(const Located& item) const {
    const TetId own = start_of_[static_cast<std::size_t>(item.locator)];
    if (alive(own) && (!alive(item.hint) || squared_distance(own, item.point) <
                                                squared_distance(item.hint, item.point))) {
      return own;
    }
    return item.hint;
  }
  void inserted(const Located& item, TetId created) {
    start_of_[static_cast<std::size_t>(item.locator)] = created;
  }

 private:
  [[nodiscard]] bool alive(TetId t) const {
    return t != kNoTet && mesh_.tets.is_alive(t, std::memory_order_relaxed);
  }
  [[nodiscard]] double squared_distance(TetId t, std::uint32_t p) const {
    const Tet& tet = mesh_.tets[t];
    const VertexId v = tet.vertex[0] != kInfiniteVertex ? tet.vertex[0] : tet.vertex[1];
    const Point3& a = mesh_.points[v];
    const Point3& b = mesh_.points[p];
    return (a.x - b.x) * (a.x - b.x) + (a.y - b.y) * (a.y - b.y) + (a.z - b.z) * (a.z - b.z);
  }
  const SharedMesh& mesh_;
  std::vector<TetId> start_of_;
};

template <class K>
std::vector<Tetrahedron> run_with(const MethodInput& input, TriangulationStats& stats) {
  ParallelRun<K> run(input, stats, 1);
  const int locators = std::max(1, run.threads - 1);
  run.split_among(locators);
  BatchQueue queue(locators, run.table.stop);
  // The inserting thread's lists and inserter are made before the locating threads start, so that
  // their allocations cannot fail while those run (an exception outside the loops' handlers then
  // would leave the threads joinable).
  std::vector<Located> taken;
  taken.reserve(BatchQueue::kTake);
  std::vector<LocatorCounts> located_by(static_cast<std::size_t>(locators));
  NoSync no_sync;
  ThreadInserter<K, NoSync> thread(run, 0, run.thread_stats(0), no_sync);
  auto& dt = thread.dt;
  WalkStarts starts(run.mesh, locators);
  const bool walk = run.location.locator == Locator::Walk;
  ThreadStats& counters = run.stats.threads[0];
  run.watched([&] {
    std::vector<std::thread> pool;
    for (int i = 0; i < locators; ++i) {
      pool.emplace_back(
          [&, i] { locate_into(run, queue, i, located_by[static_cast<std::size_t>(i)]); });
    }
    std::size_t next_taken = 0;
    while (!run.stopping()) {
      if (next_taken == taken.size()) {
        next_taken = 0;
        if (!queue.take(taken)) break;
      }
      const Located item = taken[next_taken++];
      dt.set_location_hint(walk ? starts.start_for(item) : item.hint);
      try {
        count_outcome(dt.insert(item.point), counters);
      } catch (...) {
        run.record_error();
        break;
      }
      if (walk) starts.inserted(item, dt.walk_start());
      run.progressed(0);
    }
    queue.close();
    for (auto& t : pool) t.join();
  });
  run.finish_thread(0, dt);
  for (const LocatorCounts& c : located_by) {
    run.add_location(0, c.stats, c.predicate_calls, c.location_steps, c.walk_fallbacks);
  }
  stats.queue_full_waits = queue.full_waits();
  stats.queue_empty_waits = queue.empty_waits();
  return run.output(run.finish());
}

}  // namespace

std::vector<Tetrahedron> run_batch(const MethodInput& input, TriangulationStats& stats) {
  return with_kernel(input.options, [&]<class K>() { return run_with<K>(input, stats); });
}

}  // namespace dtlab::engine
