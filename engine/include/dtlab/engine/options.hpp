#pragma once
// What a run is asked to do: the kernel, the method, the location and insertion, the repair, and
// the limits that keep a run finite (docs/design.md).
#include <cstdint>

namespace dtlab::engine {

struct RunMonitor;

enum class KernelKind { Fast, Adaptive, Filtered, Exact };
// The lock methods of the paper (Sect. 5) and the batch method it described; each is registered
// with its name and what it supports in methods.hpp.
enum class Method {
  Sequential,
  Pessimistic,
  OptimisticDetect,
  OptimisticPrevent,
  Burglary,
  Batch,
  Partitioned,
  LockGrid
};
// How the permuted points are split among the threads (paper Sect. 6).
// Auto: static in DAG mode (the paper's), blocks in walk mode, where each thread inserts its
// share along its own curve and the threads must work apart (effective_distribution).
enum class Distribution { Static, Dynamic, Strips, Blocks, Auto };
enum class Bounding { Infinite, AuxTet };
// Dag: the paper's history DAG from a random order. Walk: BRIO rounds in Hilbert order and a
// visibility walk from the last insertion, dead slots reused (docs/design.md, "Walk mode").
enum class Location { Dag, Walk };
// How a located point enters the mesh: the paper's 1->4 / 2->6 / k->2k split and flips, or
// (walk mode only) Bowyer-Watson's cavity: every tetrahedron in conflict replaced at once.
enum class Insertion { Flips, Cavity };
// The repair after a run: none; star splaying from the marked tetrahedra and every non-Delaunay
// face or bad tetrahedron, exact, for any method and kernel (Splay: --repair, always ends in the
// Delaunay tetrahedralization, no rebuild); burglary's post-check as the paper has it, Lawson flips
// on the marked tetrahedra, then on every tetrahedron when faces are left (Flips), which can get
// stuck in 3D; or the same, then a sequential rebuild as an explicit last resort (Rebuild;
// reported as `rebuilt`, a baseline, not a repair).
// Splay: star splaying from every damaged face. FlipsThenSplay: burglary's post-check on a mesh
// built exactly and consistent, exact Lawson flips from those faces first, then star splaying from
// the faces the flips leave; elsewhere the same as Splay.
enum class Repair { None, Flips, Rebuild, Splay, FlipsThenSplay };

const char* to_string(KernelKind k);
const char* to_string(Bounding b);
const char* to_string(Location l);
const char* to_string(Insertion i);
const char* to_string(Method m);
const char* to_string(Distribution d);
const char* to_string(Repair r);
// Whether the repair ends in star splaying (Splay, FlipsThenSplay).
inline bool splays(Repair r) {
  return r == Repair::Splay || r == Repair::FlipsThenSplay;
}

struct TriangulateOptions {
  KernelKind kernel = KernelKind::Adaptive;
  Bounding bounding = Bounding::Infinite;
  Location location = Location::Dag;
  Insertion insertion = Insertion::Flips;
  // Cavity insertion: check that every new tetrahedron is positive, and insert by flips where
  // one is not (counted in stats.cavity.fallbacks). Always on with the fast kernel; with an exact
  // one the check never fails (cavity_search.hpp), which the tests confirm with it on.
  bool check_cavities = false;
  std::uint64_t seed = 1;
  // Bounds that keep the fast kernel from hanging: a breach abandons the insertion and counts it.
  std::uint64_t max_flips_per_insertion = 1'000'000;
  std::uint64_t max_location_steps = 100'000'000;
  // Count predicate calls per stage (predicates-audit); costs a little.
  bool audit = false;
  // Progress bar on stderr (the CLI turns it on only for a terminal).
  bool progress = false;
  Method method = Method::Sequential;
  int threads = 1;
  Distribution distribution = Distribution::Auto;
  // Random short delays while locks are held, to shake out races (tests).
  bool stress = false;
  // The partitioned method: a pass uses as many parts (threads) as it has this many points for,
  // at most `threads`; smaller passes run on one thread. Tests lower it to cut small inputs.
  std::uint32_t points_per_part = 2048;
  // The lock-grid method: cells per axis of its grid; 0 chooses from the point count and threads
  // (about 256 points a cell; the stats report the choice).
  std::uint32_t lock_grid_cells = 0;
  // A parallel run with no finished insertion for this long is stopped and reported as a
  // failure; 0 scales the limit with the work: 10 s + 100 us per point, at most 60 s.
  double watchdog_seconds = 0.0;
  // Capacity of the tetrahedron store (DAG nodes included); 0: the limit of 32-bit neighbour
  // references, 2^30. A run that needs more stops with a TriangulationError.
  std::uint64_t max_tetrahedra = 0;
  // The repair after the run (Flips and Rebuild: burglary only).
  Repair repair = Repair::None;
  // Progress published to, and cancellation read from, another thread (run_monitor.hpp); the
  // caller keeps it alive for the run.
  RunMonitor* monitor = nullptr;
};

// The distribution a parallel run uses: options.distribution, with Auto resolved by the location
// mode.
Distribution effective_distribution(const TriangulateOptions& options);

}  // namespace dtlab::engine
