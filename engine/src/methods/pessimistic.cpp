// The pessimistic method (paper Sect. 5): each thread descends the DAG (or walks) without a lock,
// then inserts inside one global critical section, an OS mutex, as the method prescribes. Waiting
// for the section is in no phase.
#include <mutex>

#include "methods/kernel_dispatch.hpp"
#include "methods/method_input.hpp"
#include "methods/parallel_run.hpp"

namespace dtlab::engine {
namespace {

template <class K>
std::vector<Tetrahedron> run_with(const MethodInput& input, TriangulationStats& stats) {
  ParallelRun<K> run(input, stats, std::max(1, input.options.threads));
  run.split_among(run.threads);
  std::mutex global;  // the one critical section
  NoSync no_sync;
  run.on_threads([&](int i) {
    ThreadStats counters;  // stored once at the end (optimistic_worker.hpp says why)
    WorkSource work = run.work_for(i);
    ThreadInserter<K, NoSync> thread(run, i, run.thread_stats(i), no_sync);
    auto& dt = thread.dt;
    while (const auto v = work.next()) {
      if (run.stopping()) break;
      // Lock-free descent (timed and counted as location); the leaf-level part, subdivision and
      // legalization in the section.
      dt.set_location_hint(dt.locate_only(*v));
      std::lock_guard<std::mutex> guard(global);
      count_outcome(dt.insert(*v), counters);
      run.progressed(i);
    }
    run.finish_thread(i, dt);
    run.stats.threads[static_cast<std::size_t>(i)] = counters;
  });
  return run.output(run.finish());
}

}  // namespace

std::vector<Tetrahedron> run_pessimistic(const MethodInput& input, TriangulationStats& stats) {
  return with_kernel(input.options, [&]<class K>() { return run_with<K>(input, stats); });
}

}  // namespace dtlab::engine
