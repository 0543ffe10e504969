// dtlab._dtlab.triangulate: the engine run on a thread of its own while the caller's thread,
// without the GIL most of the time, wakes ten times a second to report progress and to look for
// a signal (Ctrl-C), which cancels the run through its RunMonitor.
#include <pybind11/pybind11.h>

#include <chrono>
#include <condition_variable>
#include <cstdio>
#include <exception>
#include <mutex>
#include <optional>
#include <string>
#include <thread>

#include "arrays.hpp"
#include "dtlab/engine/methods.hpp"
#include "dtlab/engine/run_monitor.hpp"
#include "dtlab/engine/triangulate.hpp"
#include "option_names.hpp"

namespace dtlab::python {
namespace {

// Shows progress the way the caller asked: a callable gets (done, total), True draws a bar on
// sys.stderr. Called with the GIL held.
class ProgressReport {
 public:
  explicit ProgressReport(py::object progress) : progress_(std::move(progress)) {
    callable_ = PyCallable_Check(progress_.ptr()) != 0;
    bar_ = !callable_ && progress_.ptr() != Py_None && py::bool_(progress_);
  }
  void show(std::uint64_t done, std::uint64_t total) {
    if (total == 0 || (done == last_ && !first_)) return;  // not started, or no change
    first_ = false;
    last_ = done;
    if (callable_) {
      progress_(done, total);
    } else if (bar_) {
      constexpr int kWidth = 40;
      const double part = total == 0 ? 1.0 : static_cast<double>(done) / static_cast<double>(total);
      const int filled = static_cast<int>(part * kWidth);
      char line[128];
      std::snprintf(line, sizeof line, "\r[dtlab] [%-*.*s] %llu / %llu points", kWidth, filled,
                    "########################################",
                    static_cast<unsigned long long>(done), static_cast<unsigned long long>(total));
      auto err = py::module_::import("sys").attr("stderr");
      err.attr("write")(std::string(line));
      err.attr("flush")();
      drawn_ = true;
    }
  }
  void end() {
    if (drawn_) py::module_::import("sys").attr("stderr").attr("write")(std::string("\n"));
    drawn_ = false;
  }

 private:
  py::object progress_;
  bool callable_ = false;
  bool bar_ = false;
  bool first_ = true;
  bool drawn_ = false;
  std::uint64_t last_ = 0;
};

engine::Triangulation run_watched(std::vector<predicates::Point3> points,
                                  engine::TriangulateOptions options, ProgressReport& report) {
  engine::RunMonitor monitor;
  options.monitor = &monitor;
  std::optional<engine::Triangulation> result;
  std::exception_ptr failure;
  std::mutex mutex;
  std::condition_variable finished_signal;
  bool finished = false;
  std::thread runner([&] {
    try {
      result.emplace(engine::triangulate(std::move(points), options));
    } catch (...) {
      failure = std::current_exception();
    }
    std::lock_guard<std::mutex> guard(mutex);
    finished = true;
    finished_signal.notify_all();
  });
  // Joins the runner on every way out, the GIL released while it finishes.
  const auto join = [&] {
    py::gil_scoped_release unlocked;
    runner.join();
  };
  for (;;) {
    bool done;
    {
      py::gil_scoped_release unlocked;
      std::unique_lock<std::mutex> lock(mutex);
      done =
          finished_signal.wait_for(lock, std::chrono::milliseconds(100), [&] { return finished; });
    }
    if (done) break;
    if (PyErr_CheckSignals() != 0) {  // a KeyboardInterrupt (or the handler's own exception)
      py::error_already_set interrupted;
      monitor.cancel.store(true, std::memory_order_relaxed);
      join();
      report.end();
      throw interrupted;
    }
    try {
      report.show(monitor.done.load(std::memory_order_relaxed),
                  monitor.total.load(std::memory_order_relaxed));
    } catch (...) {  // the callback raised: stop the run, then let its exception out
      monitor.cancel.store(true, std::memory_order_relaxed);
      join();
      throw;
    }
  }
  join();
  if (failure) {
    report.end();
    std::rethrow_exception(failure);
  }
  report.show(monitor.total.load(), monitor.total.load());
  report.end();
  return std::move(*result);
}

py::tuple triangulate(const PointArray& xyz, const std::string& predicates,
                      const std::string& method, int threads, const std::string& location,
                      const std::string& insertion, std::uint64_t seed, const std::string& repair,
                      py::object progress) {
  engine::TriangulateOptions options;
  options.kernel = named<engine::KernelKind>(predicates, 4, "predicates");
  const auto m = engine::method_named(method);
  if (!m) throw std::invalid_argument("method must be one of " + engine::method_names());
  options.method = *m;
  options.location = named<engine::Location>(location, 2, "location");
  options.insertion = named<engine::Insertion>(insertion, 2, "insertion");
  options.repair = named<engine::Repair>(repair, 5, "repair");
  options.seed = seed;
  if (threads < 1 || threads > 1024) throw std::invalid_argument("threads must be in [1, 1024]");
  if (!engine::method_info(options.method).parallel && threads != 1) {
    throw std::invalid_argument(std::string("the ") + engine::to_string(options.method) +
                                " method runs on one thread (threads=1)");
  }
  options.threads = threads;
  if (const auto why = engine::unsupported(options)) throw std::invalid_argument(*why);
  ProgressReport report(std::move(progress));
  const engine::Triangulation result = run_watched(to_points(xyz), options, report);
  const std::string stats = engine::stats_json(result.stats, options, method, threads);
  return py::make_tuple(to_int32_rows(result.tetrahedra), stats);
}

}  // namespace

void bind_triangulate(py::module_& m) {
  m.def("triangulate", &triangulate, py::arg("points"), py::arg("predicates"), py::arg("method"),
        py::arg("threads"), py::arg("location"), py::arg("insertion"), py::arg("seed"),
        py::arg("repair"), py::arg("progress"));
}

}  // namespace dtlab::python
