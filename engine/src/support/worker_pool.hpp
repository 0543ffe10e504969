#pragma once
// The run's threads, started once: a parallel run's steps (the insertion order, each pass of the
// partitioned method, the sorts along its curves, the output) each used to start and join their
// own threads, 115 thread starts in a partitioned run at 2 threads and 1,511 at 16
// (uniform:1000000; about 30 us each on the development VM, all on the calling thread). A pool's
// workers are started when the run begins and parked on a futex (std::atomic::wait) between steps;
// a step wakes them, each runs its own index, and the caller runs the last one itself. Worker i
// runs index i in every step, so a thread keeps its part's data in its core's cache across passes.
//
// The driver makes a pool the current one of its thread for the run (PoolScope); the parallel
// helpers (in_parallel_ranges, stable_sort_by_key, ParallelRun::on_threads) take it when it can
// serve them (can_run), and start threads of their own otherwise: on another thread (a worker
// calling them, a nested step), with more indices than workers, or while a step is running.
#include <atomic>
#include <cstdint>
#include <exception>
#include <thread>
#include <vector>

namespace dtlab::engine {

class WorkerPool {
 public:
  // Starts `workers` threads, parked until run() gives them a step.
  explicit WorkerPool(int workers);
  ~WorkerPool();
  WorkerPool(const WorkerPool&) = delete;
  WorkerPool& operator=(const WorkerPool&) = delete;

  [[nodiscard]] int workers() const { return static_cast<int>(threads_.size()); }
  // Whether run(n, ...) may be called now: the caller's own pool (current()), no step running,
  // and a worker for each index but the caller's.
  [[nodiscard]] bool can_run(int n) const { return !running_ && n >= 1 && n - 1 <= workers(); }

  // Runs job(i) for every i in [0, n) at once, each on its own thread: i < n - 1 on worker i,
  // n - 1 on the calling thread; returns when all have ended. An exception from a job is held
  // until all have ended, then the lowest index's is rethrown; jobs that wait on each other (a
  // barrier, a lock) must catch their own, as the helpers' do, or the others wait for ever.
  // Requires can_run(n).
  template <class Job>
  void run(int n, Job& job) {
    run_erased(n, &job, [](void* j, int i) { (*static_cast<Job*>(j))(i); });
  }

  // The pool the calling thread's parallel steps use, or null (PoolScope).
  static WorkerPool* current();

 private:
  using Trampoline = void (*)(void*, int);
  void run_erased(int n, void* job, Trampoline call);
  void work(int index);
  void stop();  // ends and joins the workers

  std::vector<std::thread> threads_;
  std::vector<std::exception_ptr> errors_;  // per index, this step's
  // Written by the caller before it bumps `generation_`; read by the workers after they see the
  // new generation. Each worker's last read of them comes before its decrement of `remaining_`,
  // which the caller sees reach zero before it writes them again for the next step.
  void* job_ = nullptr;
  Trampoline call_ = nullptr;
  int worker_jobs_ = 0;  // indices [0, worker_jobs_) run on workers this step
  bool stopping_ = false;
  std::atomic<std::uint32_t> generation_{0};  // one more each step; the workers wait on it
  std::atomic<std::uint32_t> remaining_{0};   // workers not yet done with this step
  bool running_ = false;                      // the owner's thread only
};

// Makes `pool` the calling thread's current pool until the scope ends (the previous one then).
class PoolScope {
 public:
  explicit PoolScope(WorkerPool* pool);
  ~PoolScope();
  PoolScope(const PoolScope&) = delete;
  PoolScope& operator=(const PoolScope&) = delete;

 private:
  WorkerPool* previous_;
};

}  // namespace dtlab::engine
