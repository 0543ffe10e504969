// bytes -> (method, threads, distribution, kernel, repair) + point set -> triangulate on 2-4
// threads with the adaptive, filtered or fast kernel, with random delays while locks are held.
//
// First byte, config = byte % 252, a mixed-radix number (every one of the 252 configurations is
// reachable, none twice within 0..251):
//   config = method + 7 * ((threads - 2) + 3 * (distribution + 2 * (kernel + 3 * splay)))
//   method:       0 pessimistic (static distribution) or partitioned (dynamic: see below),
//                 1 optimistic-detect, 2 optimistic-prevent (static) or lock-grid (dynamic: walk
//                 mode, 2 cells per axis), 3 burglary,
//                 4 burglary --repair (star splaying), 5 burglary --repair=rebuild (the paper's
//                 flips, then the reported rebuild), 6 batch
//   threads:      2, 3, 4
//   distribution: 0 static, 1 dynamic (method 0: the partitioned method, which has none; walk
//                 mode, cavities for an odd number of points, flips for an even one, 8 points
//                 a part)
//   kernel:       0 adaptive, 1 filtered, 2 fast
//   splay:        1: --repair (star splaying) for methods 0-3 and 6
// The rest is a point set as for the triangulate harness (fuzz_input.hpp), at most 300 points.
// The number of points picks the location mode: odd, the walk mode; even, the DAG; and 3 mod 4,
// the walk mode with cavity insertion. (Not the input's length: every corpus input is 3 + 6k
// bytes long, odd.)
//
// Every kernel: an input that CGAL finds no tetrahedralization for (tests/cgal_reference.hpp, not
// the engine's own code) must be refused with a TriangulationError, and any other input must not
// be: a refusal there, the watchdog's included (a stall), is a failure.
// Adaptive and filtered (exact): every method gives a sound mesh, every method but burglary
// without a repair a valid one, and that one CGAL's tetrahedra, orientation compared (but after
// the paper's flips, whose plain insphere test may stop at a Delaunay mesh that only the
// perturbation rejects); no insertion is abandoned, and the paper's flips keep the mesh sound.
// Fast: the points are divided by 12 (rounded: nearly degenerate and inexact, where the fast kernel
// fails); the run must finish (no crash, no hang, only the refusals the fast kernel may make);
// validity is not required and abandoned insertions are allowed, but the validator's counters on
// whatever it gave must equal an independent exact recount (tests/validator_recount.hpp: its
// errors are counted right); after star splaying the mesh must be CGAL's.
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>

#include "cgal_reference.hpp"
#include "dtlab/engine/triangulate.hpp"
#include "dtlab/engine/validator.hpp"
#include "fuzz_input.hpp"
#include "validator_recount.hpp"

namespace {

[[noreturn]] void fail(const char* what) {
  std::fprintf(stderr, "parallel_fuzz: %s\n", what);
  std::abort();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size < 1) return 0;
  using dtlab::engine::KernelKind;
  using dtlab::engine::Method;
  unsigned config = data[0] % 252U;
  const unsigned method = config % 7;
  config /= 7;
  const unsigned threads = config % 3;
  config /= 3;
  const unsigned distribution = config % 2;
  config /= 2;
  const unsigned kernel = config % 3;
  const bool splay = config / 3 != 0;
  constexpr Method kMethods[] = {
      Method::Pessimistic, Method::OptimisticDetect, Method::OptimisticPrevent,
      Method::Burglary,    Method::Burglary,         Method::Burglary,
      Method::Batch};
  constexpr KernelKind kKernels[] = {KernelKind::Adaptive, KernelKind::Filtered, KernelKind::Fast};
  dtlab::engine::TriangulateOptions options;
  options.method = kMethods[method];
  // Burglary (4) repairs by star splaying, after exact flips where `splay` is set.
  options.repair = method == 4 && splay                    ? dtlab::engine::Repair::FlipsThenSplay
                   : method == 4 || (splay && method != 5) ? dtlab::engine::Repair::Splay
                   : method == 5                           ? dtlab::engine::Repair::Rebuild
                                                           : dtlab::engine::Repair::None;
  options.threads = 2 + static_cast<int>(threads);
  options.distribution = distribution != 0 ? dtlab::engine::Distribution::Dynamic
                                           : dtlab::engine::Distribution::Static;
  options.kernel = kKernels[kernel];
  options.stress = true;
  options.seed = size;
  // The default watchdog (10 s + 100 us per point) turns a hang into a TriangulationError.
  auto points = dtlab::fuzz::points_from_bytes(data + 1, size - 1, 300);
  // Odd sizes walk; of those, every other one inserts by cavities.
  options.location =
      points.size() % 2 == 1 ? dtlab::engine::Location::Walk : dtlab::engine::Location::Dag;
  if (points.size() % 4 == 3) options.insertion = dtlab::engine::Insertion::Cavity;
  if (method == 0 && distribution != 0) {
    // The dynamic distribution's pessimistic slot runs the partitioned method (which has no
    // distribution): walk mode only, cavities for odd sizes, parts of 8 points so that these
    // small inputs are cut into arcs and insertions cross the cuts.
    options.method = Method::Partitioned;
    options.location = dtlab::engine::Location::Walk;
    options.insertion =
        points.size() % 2 == 1 ? dtlab::engine::Insertion::Cavity : dtlab::engine::Insertion::Flips;
    options.points_per_part = 8;
  }
  if (method == 2 && distribution != 0) {
    // The dynamic distribution's optimistic-prevent slot runs the lock grid (walk mode only), on
    // 2 cells per axis so that the threads meet in cells.
    options.method = Method::LockGrid;
    options.location = dtlab::engine::Location::Walk;
    options.lock_grid_cells = 2;
  }
  if (options.kernel == KernelKind::Fast) {
    // Small integers keep the fast kernel's arithmetic exact; a twelfth of them (rounded, as a
    // grid with spacing 1/12 on [0, 1] is) is nearly degenerate and inexact, where it fails.
    for (auto& p : points) p = {p.x / 12, p.y / 12, p.z / 12};
  }
  // The points are small integers times a power of two, so always finite; a non-finite one would
  // have to be refused and is not shown to CGAL.
  const int dimension = dtlab::test::all_finite(points) ? dtlab::test::cgal_dimension(points) : -1;
  try {
    const auto result = dtlab::engine::triangulate(points, options);
    if (dimension != 3) fail("triangulated an input without a tetrahedralization");
    const auto report = dtlab::engine::validate(points, result.tetrahedra);
    const auto cgal_mesh = [&points] {
      return dtlab::engine::canonical_tetrahedra(dtlab::test::cgal_delaunay(points));
    };
    if (options.kernel == KernelKind::Fast && !dtlab::engine::splays(options.repair)) {
      // The fast kernel may be wrong; the validator must count what is wrong exactly.
      if (!dtlab::test::counters_agree(report,
                                       dtlab::test::exact_recount(points, result.tetrahedra))) {
        fail("the validator's counts on the fast kernel's mesh differ from the exact recount");
      }
      return 0;
    }
    if (dtlab::engine::splays(options.repair)) {
      if (!report.valid()) fail("invalid mesh after star splaying");
      if (dtlab::engine::canonical_tetrahedra(result.tetrahedra) != cgal_mesh()) {
        fail("star splaying did not give CGAL's tetrahedra");
      }
      return 0;
    }
    if (!report.mesh_consistent()) fail("unsound mesh");
    // Burglary unrepaired may leave non-Delaunay faces, except with cavity insertion.
    const bool must_be_valid = options.method != Method::Burglary ||
                               options.repair != dtlab::engine::Repair::None ||
                               options.insertion == dtlab::engine::Insertion::Cavity;
    if (must_be_valid && !report.valid()) fail("invalid mesh");
    const bool paper_flips = options.method == Method::Burglary &&
                             options.repair != dtlab::engine::Repair::None &&
                             !dtlab::engine::splays(options.repair);
    if (must_be_valid && !paper_flips &&
        dtlab::engine::canonical_tetrahedra(result.tetrahedra) != cgal_mesh()) {
      fail("the mesh is not CGAL's tetrahedra");
    }
    if (result.stats.abandoned_insertions != 0) fail("abandoned insertions");
    const dtlab::engine::PostCheck& check = result.stats.post_check;
    if (check.repaired && !check.mesh_consistent_after_flips) fail("the flips broke the mesh");
  } catch (const dtlab::engine::TriangulationError& e) {
    // Refused an input with a tetrahedralization, or the watchdog stopped a stalled run. The fast
    // kernel may refuse one more way: start() asks its orient3d about the first tetrahedron (found
    // exactly), and on the inexact twelfths it can see that tetrahedron as flat.
    const bool flat_first = std::strstr(e.what(), "flat under this kernel") != nullptr;
    if (dimension == 3 && !(options.kernel == KernelKind::Fast && flat_first)) fail(e.what());
  }
  return 0;
}
