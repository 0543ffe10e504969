// dtlab and CGAL's Delaunay_triangulation_3 on the same points, in one run: each engine runs in a
// child process of its own (fork), so that each has its own peak memory, in interleaved rounds;
// the table gives medians. Usage:
//   cgal_compare INPUT [--seed S] [--repeat R] [--threads T[,T...]] [--methods LIST] [--no-dag]
//                [--insertion flips|cavity|both]
// INPUT is a generator spec (uniform:1000000) or a point file. With --threads T > 1 the parallel
// methods in LIST (default optimistic-detect) run in walk mode at T threads, and CGAL's parallel
// mode (TBB) at T threads when this build has it; T may be a list (2,4,8,16), which runs the
// sequential engines once for all the counts. The walk mode's engines run with each insertion
// asked for (default both: the flips, and the cavities as "dtlab walk cavity").
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <exception>
#include <functional>
#include <sstream>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include "dtlab/engine/methods.hpp"
#include "dtlab/engine/triangulate.hpp"
#include "dtlab/experiments/cgal_engine.hpp"
#include "dtlab/generators/generators.hpp"
#include "dtlab/io/point_readers.hpp"

namespace {

using dtlab::predicates::Point3;

struct Sample {
  double seconds = 0;
  double tetrahedra = 0;
  double peak_bytes = 0;
};

struct Engine {
  std::string name;
  // Gets the child's own image of the points (after the fork): it may consume them.
  std::function<Sample(std::vector<Point3>&)> run;
  std::vector<Sample> samples;
};

double peak_rss_bytes() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return static_cast<double>(usage.ru_maxrss) * 1024.0;
}

// Runs `engine` in a child process; its sample comes back through a pipe.
bool run_isolated(const Engine& engine, std::vector<Point3>& points, Sample& out) {
  int fds[2];
  if (pipe(fds) != 0) return false;
  const pid_t pid = fork();
  if (pid == 0) {
    close(fds[0]);
    Sample s{};
    try {
      s = engine.run(points);
    } catch (const std::exception& e) {
      std::fprintf(stderr, "%s: %s\n", engine.name.c_str(), e.what());
      _exit(1);
    }
    s.peak_bytes = peak_rss_bytes();
    const bool written = write(fds[1], &s, sizeof s) == static_cast<ssize_t>(sizeof s);
    _exit(written ? 0 : 1);
  }
  close(fds[1]);
  const bool read_all = read(fds[0], &out, sizeof out) == static_cast<ssize_t>(sizeof out);
  close(fds[0]);
  int status = 0;
  waitpid(pid, &status, 0);
  return read_all && WIFEXITED(status) && WEXITSTATUS(status) == 0;
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v.empty() ? 0.0 : v[v.size() / 2];
}

Sample run_dtlab(std::vector<Point3>& points, dtlab::engine::Location location,
                 dtlab::engine::Method method, int threads, std::uint64_t seed,
                 dtlab::engine::Insertion insertion = dtlab::engine::Insertion::Flips) {
  dtlab::engine::TriangulateOptions options;
  options.seed = seed;
  options.location = location;
  options.insertion = insertion;
  options.method = method;
  options.threads = threads;
  if (method != dtlab::engine::Method::Sequential) {
    options.distribution = dtlab::engine::Distribution::Blocks;
  }
  // Moved in: the engine scales and orders them in place, as a user who gives them up lets it.
  const auto result = dtlab::engine::triangulate(std::move(points), options);
  return {result.stats.seconds.total, static_cast<double>(result.tetrahedra.size()), 0};
}

Sample run_cgal(const std::vector<Point3>& points, int threads) {
  const dtlab::experiments::CgalRun run = dtlab::experiments::run_cgal(points, threads);
  return {run.seconds, static_cast<double>(run.finite_cells), 0};
}

}  // namespace

constexpr const char* kUsage =
    "usage: cgal_compare INPUT [--seed S] [--repeat R] [--threads T[,T...]] [--methods LIST] "
    "[--no-dag] [--insertion flips|cavity|both]\n";

int compare(int argc, char** argv) {
  if (argc < 2) {
    std::fputs(kUsage, stderr);
    return 2;
  }
  if (std::string(argv[1]) == "--help" || std::string(argv[1]) == "-h") {
    std::fputs(kUsage, stdout);
    return 0;
  }
  const std::string input = argv[1];
  std::uint64_t seed = 1;
  int repeat = 3;
  std::vector<int> thread_counts;
  bool dag = true;
  std::string methods = "optimistic-detect";
  std::string insertion = "both";
  for (int i = 2; i < argc; ++i) {
    const std::string arg = argv[i];
    const bool has_value = i + 1 < argc;
    if (arg == "--seed" && has_value) {
      seed = std::stoull(argv[++i]);
    } else if (arg == "--repeat" && has_value) {
      repeat = std::stoi(argv[++i]);
    } else if (arg == "--threads" && has_value) {
      std::stringstream list(argv[++i]);
      std::string count;
      while (std::getline(list, count, ',')) thread_counts.push_back(std::stoi(count));
    } else if (arg == "--methods" && has_value) {
      methods = argv[++i];
    } else if (arg == "--no-dag") {
      dag = false;
    } else if (arg == "--insertion" && has_value) {
      insertion = argv[++i];
    } else {
      std::fprintf(stderr, "cgal_compare: unknown argument %s\n", arg.c_str());
      return 2;
    }
  }
  std::vector<Point3> points;
  std::string family;
  std::int64_t n = 0;
  if (dtlab::generators::parse_spec(input, family, n)) {
    points = dtlab::generators::generate(family, n, seed).points;
  } else {
    points = dtlab::io::read_points(input);
  }

  using dtlab::engine::Insertion;
  using dtlab::engine::Location;
  using dtlab::engine::Method;
  if (insertion != "flips" && insertion != "cavity" && insertion != "both") {
    std::fprintf(stderr, "cgal_compare: --insertion takes flips, cavity or both\n");
    return 2;
  }
  // The walk mode's insertions asked for, each with its name's prefix.
  std::vector<std::pair<Insertion, std::string>> walks;
  if (insertion != "cavity") walks.emplace_back(Insertion::Flips, "dtlab walk, ");
  if (insertion != "flips") walks.emplace_back(Insertion::Cavity, "dtlab walk cavity, ");
  std::vector<Engine> engines;
  auto add = [&](std::string name, std::function<Sample(std::vector<Point3>&)> run) {
    engines.push_back(Engine{std::move(name), std::move(run), {}});
  };
  for (const auto& [how, prefix] : walks) {
    add(prefix + "sequential", [&, how = how](auto& p) {
      return run_dtlab(p, Location::Walk, Method::Sequential, 1, seed, how);
    });
  }
  if (dag) {
    add("dtlab DAG, sequential",
        [&](auto& p) { return run_dtlab(p, Location::Dag, Method::Sequential, 1, seed); });
  }
  add("CGAL, sequential", [](auto& p) { return run_cgal(p, 1); });
  for (const int threads : thread_counts) {
    if (threads < 2) continue;
    std::stringstream list(methods);
    std::string name;
    while (std::getline(list, name, ',')) {
      // Any parallel method of the registry that runs in walk mode.
      const auto named = dtlab::engine::method_named(name);
      const bool known = named.has_value() && dtlab::engine::method_info(*named).parallel &&
                         dtlab::engine::method_info(*named).walk;
      const Method method = named.value_or(Method::OptimisticDetect);
      if (!known) {
        std::fprintf(stderr, "cgal_compare: unknown method %s\n", name.c_str());
        return 2;
      }
      for (const auto& [how, prefix] : walks) {
        add(prefix + name + " " + std::to_string(threads) + "t",
            [&, method, threads, how = how](auto& p) {
              return run_dtlab(p, Location::Walk, method, threads, seed, how);
            });
      }
    }
    if (dtlab::experiments::cgal_parallel_available()) {
      add("CGAL, parallel (TBB) " + std::to_string(threads) + "t",
          [threads](auto& p) { return run_cgal(p, threads); });
    }
  }

  const double baseline = peak_rss_bytes();  // this process: the input alone
  for (int r = 0; r < repeat; ++r) {
    for (Engine& e : engines) {
      Sample s;
      if (!run_isolated(e, points, s)) {
        std::fprintf(stderr, "cgal_compare: %s failed\n", e.name.c_str());
        return 1;
      }
      e.samples.push_back(s);
    }
  }

  std::printf("input %s, %zu points, seed %llu, %d interleaved rounds, %u hardware threads\n",
              input.c_str(), points.size(), static_cast<unsigned long long>(seed), repeat,
              std::thread::hardware_concurrency());
  std::printf(
      "times and memory are medians; each run in its own process (peak RSS includes the "
      "input, %.0f MiB before any run)\n",
      baseline / 1048576.0);
  std::printf("%-42s %9s %9s %12s %10s %9s %12s\n", "engine", "median s", "min s", "Mpoints/s",
              "x CGAL", "peak MiB", "bytes/point");
  double cgal = 0;
  for (const Engine& e : engines) {
    if (e.name == "CGAL, sequential") {
      std::vector<double> s;
      for (const Sample& x : e.samples) s.push_back(x.seconds);
      cgal = median(s);
    }
  }
  for (const Engine& e : engines) {
    std::vector<double> s;
    std::vector<double> mem;
    for (const Sample& x : e.samples) {
      s.push_back(x.seconds);
      mem.push_back(x.peak_bytes);
    }
    const double t = median(s);
    const double m = median(mem);
    std::printf("%-42s %9.3f %9.3f %12.3f %10.2f %9.0f %12.0f\n", e.name.c_str(), t,
                *std::min_element(s.begin(), s.end()), static_cast<double>(points.size()) / t / 1e6,
                t / cgal, m / 1048576.0, m / static_cast<double>(points.size()));
  }
  std::printf("tetrahedra:");
  for (const Engine& e : engines) std::printf(" %.0f", e.samples.back().tetrahedra);
  std::printf("\n");
  return 0;
}

// Bad input (an unreadable file, a malformed number) ends with its message, not an abort.
int main(int argc, char** argv) {
  try {
    return compare(argc, argv);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "cgal_compare: %s\n", e.what());
    return 2;
  }
}
