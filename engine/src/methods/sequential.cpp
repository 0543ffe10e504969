// The sequential method: one thread, no locks (NoSync), the baseline every parallel method is
// measured against.
#include <chrono>
#include <cstdio>

#include "dtlab/engine/run_monitor.hpp"
#include "dtlab/engine/triangulate.hpp"
#include "insertion/inserter.hpp"
#include "location/location_policy.hpp"
#include "methods/kernel_dispatch.hpp"
#include "methods/method_input.hpp"
#include "repair/splay_repair.hpp"

namespace dtlab::engine {
namespace {

using Clock = std::chrono::steady_clock;

// The progress bar on stderr (after 2 s) and the monitor's count and cancellation
// (run_monitor.hpp), looked at every 1024 points.
class Progress {
 public:
  Progress(bool enabled, RunMonitor* monitor, std::size_t total)
      : enabled_(enabled), monitor_(monitor), total_(total), start_(Clock::now()) {}
  void update(std::size_t done) {
    if ((done & 0x3FF) != 0) return;
    if (monitor_ != nullptr) {
      monitor_->done.store(done, std::memory_order_relaxed);
      if (monitor_->cancel.load(std::memory_order_relaxed)) throw RunCancelled();
    }
    if (!enabled_ || (done & 0x3FFF) != 0) return;
    const double elapsed = std::chrono::duration<double>(Clock::now() - start_).count();
    if (elapsed < 2.0) return;
    std::fprintf(stderr, "\r[dtlab] inserted %zu / %zu points (%.0f%%), %.1f s", done, total_,
                 100.0 * static_cast<double>(done) / static_cast<double>(total_), elapsed);
    shown_ = true;
  }
  ~Progress() {
    if (shown_) std::fprintf(stderr, "\n");
  }
  Progress(const Progress&) = delete;
  Progress& operator=(const Progress&) = delete;

 private:
  bool enabled_;
  RunMonitor* monitor_;
  std::size_t total_;
  Clock::time_point start_;
  bool shown_ = false;
};

template <class K>
std::vector<Tetrahedron> run_with(const MethodInput& input, TriangulationStats& stats) {
  const auto& [points, input_count, order, first, skip_first, options] = input;
  IncrementalDelaunay<K> dt(points, options, stats);
  dt.start(first[0], first[1], first[2], first[3]);
  if (skip_first) stats.inserted += 4;
  // An empty order is the identity (the walk mode stores the points in insertion order).
  const std::size_t count = order.empty() ? input_count : order.size();
  Progress progress(options.progress, options.monitor, count);
  for (std::size_t i = 0; i < count; ++i) {
    const auto v = order.empty() ? static_cast<std::uint32_t>(i) : order[i];
    progress.update(i + 1);
    if (skip_first && (v == first[0] || v == first[1] || v == first[2] || v == first[3])) continue;
    switch (dt.insert(v)) {
      case IncrementalDelaunay<K>::Outcome::Inserted:
        ++stats.inserted;
        break;
      case IncrementalDelaunay<K>::Outcome::Duplicate:
        ++stats.duplicates;
        break;
      case IncrementalDelaunay<K>::Outcome::GaveUp:  // no policy gives up in the sequential engine
      case IncrementalDelaunay<K>::Outcome::Unlocated:
      case IncrementalDelaunay<K>::Outcome::Abandoned:
        ++stats.abandoned_insertions;
        break;
    }
  }
  stats.store_slots = dt.store_slots();
  stats.dag_nodes = resolve_location(options.location).history ? dt.store_slots() : 0;
  stats.predicate_calls = dt.predicate_calls();
  stats.location_steps = dt.location_steps();
  stats.walk_fallbacks = dt.walk_fallbacks();
  if (splays(options.repair))
    splay_shared_mesh(dt.mesh(), {}, options.kernel != KernelKind::Fast, 1, stats.splay);
  const auto output_start = Clock::now();
  std::vector<Tetrahedron> result = dt.take_finite_tetrahedra(static_cast<VertexId>(input_count));
  stats.seconds.output += std::chrono::duration<double>(Clock::now() - output_start).count();
  return result;
}

}  // namespace

std::vector<Tetrahedron> run_sequential(const MethodInput& input, TriangulationStats& stats) {
  return with_kernel(input.options, [&]<class K>() { return run_with<K>(input, stats); });
}

}  // namespace dtlab::engine
