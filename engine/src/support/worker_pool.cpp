#include "support/worker_pool.hpp"

#include <algorithm>
#include <cassert>

namespace dtlab::engine {

namespace {
thread_local WorkerPool* current_pool = nullptr;
}  // namespace

WorkerPool::WorkerPool(int workers) : errors_(static_cast<std::size_t>(std::max(workers, 0)) + 1) {
  threads_.reserve(errors_.size() - 1);
  try {
    for (int i = 0; i < workers; ++i) threads_.emplace_back([this, i] { work(i); });
  } catch (...) {  // a thread that could not start (std::system_error): end the started ones
    stop();
    throw;
  }
}

WorkerPool::~WorkerPool() {
  stop();
}

void WorkerPool::stop() {
  if (threads_.empty()) return;
  stopping_ = true;
  generation_.fetch_add(1);  // seq_cst, as in run_erased
  generation_.notify_all();
  for (std::thread& t : threads_) t.join();
  threads_.clear();
}

WorkerPool* WorkerPool::current() {
  return current_pool;
}

void WorkerPool::work(int index) {
  std::uint32_t seen = 0;
  for (;;) {
    generation_.wait(seen, std::memory_order_acquire);  // parked until the next step
    seen = generation_.load(std::memory_order_acquire);
    if (stopping_) return;
    if (index < worker_jobs_) {
      try {
        call_(job_, index);
      } catch (...) {
        errors_[static_cast<std::size_t>(index)] = std::current_exception();
      }
    }
    // The job's writes are the caller's once it sees the count reach zero (seq_cst here, for
    // notify_one's waiter check as in run_erased; acquire there).
    if (remaining_.fetch_sub(1) == 1) remaining_.notify_one();
  }
}

void WorkerPool::run_erased(int n, void* job, Trampoline call) {
  assert(can_run(n));
  running_ = true;
  job_ = job;
  call_ = call;
  worker_jobs_ = n - 1;
  remaining_.store(static_cast<std::uint32_t>(threads_.size()), std::memory_order_relaxed);
  if (!threads_.empty()) {
    // seq_cst, not just release: notify_all skips the wake-up when it reads no waiter, and the
    // library counts its waiters with seq_cst operations, which only a seq_cst change here is
    // ordered against (on x86 the two compile alike).
    generation_.fetch_add(1);
    generation_.notify_all();
  }
  const auto last = static_cast<std::size_t>(n - 1);
  try {
    call(job, n - 1);
  } catch (...) {
    errors_[last] = std::current_exception();
  }
  for (std::uint32_t left = remaining_.load(std::memory_order_acquire); left != 0;
       left = remaining_.load(std::memory_order_acquire)) {
    remaining_.wait(left, std::memory_order_acquire);
  }
  running_ = false;
  std::exception_ptr first;
  for (std::size_t i = 0; i <= last; ++i) {
    if (errors_[i] && !first) first = errors_[i];
    errors_[i] = nullptr;
  }
  if (first) std::rethrow_exception(first);
}

PoolScope::PoolScope(WorkerPool* pool) : previous_(current_pool) {
  current_pool = pool;
}
PoolScope::~PoolScope() {
  current_pool = previous_;
}

}  // namespace dtlab::engine
