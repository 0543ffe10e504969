// Burglary's post-check (paper Sect. 5) and the repairs after it (burglary_post_check.hpp).
#include "methods/burglary_post_check.hpp"

#include <chrono>
#include <optional>

#include "dtlab/engine/validator.hpp"
#include "insertion/lawson_pass.hpp"
#include "location/location_policy.hpp"
#include "methods/kernel_dispatch.hpp"
#include "repair/splay_repair.hpp"

namespace dtlab::engine {

using Clock = std::chrono::steady_clock;

// Burglary's sequential post-check: the exact validator's count after the parallel run; with
// --repair, Lawson flips on the marked tetrahedra, then (only if the validator still finds
// non-Delaunay faces) on every tetrahedron. Flips can get stuck in 3D: what they leave is reported
// (non_delaunay_after_flips), and only Repair::Rebuild then triangulates again sequentially, as an
// explicit, reported last resort (rebuilt). Each stage's count goes into stats.post_check, and the
// validator's full verdict on the mesh returned into its *_after fields.
template <class K>
std::vector<Tetrahedron> post_check(SharedMesh& mesh, const std::vector<TetId>& marks,
                                    const std::vector<std::pair<VertexId, VertexId>>& duplicates,
                                    const MethodInput& run, TriangulationStats& stats) {
  const TriangulateOptions& options = run.options;
  const std::size_t input_count = run.input_count;
  PostCheck& check = stats.post_check;
  check.done = true;
  const std::vector<Point3> input(mesh.points.begin(),
                                  mesh.points.begin() + static_cast<std::ptrdiff_t>(input_count));
  // With the auxiliary tetrahedron the hull it lost shows as reflex boundary edges in every
  // method (docs/experiments.md), so only the vertex at infinity counts them as burglary's.
  const bool hull_counts = options.bounding == Bounding::Infinite;
  // Validates `tets`, records the verdict as the latest stage's, returns the violations left.
  ValidationReport report;  // the latest stage's
  auto count = [&](const std::vector<Tetrahedron>& tets) {
    const auto t0 = Clock::now();
    report = validate(input, tets, ValidateWith::Adaptive, kAllThreads, true);
    check.seconds_check += std::chrono::duration<double>(Clock::now() - t0).count();
    check.non_delaunay_faces_after = report.non_delaunay_faces;
    check.reflex_boundary_edges_after = report.reflex_boundary_edges;
    check.mesh_consistent_after = report.mesh_consistent();
    check.non_delaunay_after =
        report.non_delaunay_faces + (hull_counts ? report.reflex_boundary_edges : 0);
    return check.non_delaunay_after;
  };
  const auto output_start = Clock::now();
  std::vector<Tetrahedron> tets =
      mesh.finite_tetrahedra(static_cast<VertexId>(input_count), duplicates, options.threads);
  stats.seconds.output += std::chrono::duration<double>(Clock::now() - output_start).count();
  count(tets);
  check.non_delaunay_faces = check.non_delaunay_faces_after;
  check.reflex_boundary_edges = check.reflex_boundary_edges_after;
  check.mesh_consistent = check.mesh_consistent_after;
  if (options.repair == Repair::None) return tets;

  check.repaired = true;
  const auto t0 = Clock::now();
  const double check_before = check.seconds_check;
  if (splays(options.repair)) {
    // The validation above already proved the mesh the unique perturbed Delaunay
    // tetrahedralization (ValidationReport::is_perturbed_delaunay): what star splaying would
    // return unchanged, so its own scan is skipped (the marks, if any, changed nothing that
    // shows) and the verdict after is that one. Only with the vertex at infinity: with the
    // auxiliary tetrahedron star splaying works on the input and the four auxiliary vertices,
    // whose Delaunay tetrahedralization can lose hull tetrahedra that the input's has, so a proof
    // about the finite tetrahedra says nothing about what it would return.
    if (hull_counts && report.is_perturbed_delaunay()) {
      stats.splay.done = true;
      stats.splay.proven_by_post_check = true;
      return tets;
    }
    // Star splaying from the marks and every non-Delaunay face: always ends Delaunay. Where the
    // validation above judged the mesh consistent (built exactly), the faces it rejected are the
    // ones the repair's exact scan would find: handed over, they spare a second pass over the
    // whole mesh.
    const bool exact_mesh = options.kernel != KernelKind::Fast;
    std::optional<ValidatedFindings> found;
    if (hull_counts && exact_mesh && report.mesh_consistent()) {
      found = validated_findings(report, input_count, duplicates);
    }
    // --repair=flips-splay: exact Lawson flips first, by this kernel (exact: only a mesh built
    // exactly is flipped).
    TriangulationStats flip_stats;
    NoSync flip_sync;
    const FlipPass flips = [&](const std::vector<TetId>& at, std::vector<TetId>& created,
                               std::vector<Quad>& left) {
      LawsonPass<K, NoSync> lawson(mesh, options, flip_stats, flip_sync);
      return lawson.flip_from(at, created, left);
    };
    const bool flips_first = options.repair == Repair::FlipsThenSplay && exact_mesh;
    splay_shared_mesh(mesh, marks, exact_mesh, options.threads, stats.splay,
                      found ? &*found : nullptr, flips_first ? &flips : nullptr);
    check.seconds_repair = stats.splay.seconds;
    // Nothing flipped or written back: the mesh and so its verdict are the ones validated above.
    if (stats.splay.flips == 0 && stats.splay.tetrahedra_removed == 0 &&
        stats.splay.tetrahedra_created == 0) {
      return tets;
    }
    tets = mesh.finite_tetrahedra(static_cast<VertexId>(input_count), duplicates, options.threads);
    count(tets);
    return tets;
  }
  TriangulationStats repair_stats;
  NoSync no_sync;
  LawsonPass<K, NoSync> dt(mesh, options, repair_stats, no_sync);
  // Without the DAG (the walk mode, which reuses slots) a mark stands for itself, when it is
  // still alive (a reused slot marks an unrelated live tetrahedron: extra faces checked, nothing
  // missed, since the sweep below and star splaying's exact scan find every non-Delaunay face).
  const bool history = resolve_location(options.location).history;
  std::vector<TetId> live_marks;
  if (!history) {
    for (const TetId t : marks) {
      if (mesh.tets.is_alive(t, std::memory_order_relaxed)) live_marks.push_back(t);
    }
  }
  check.repair_flips = dt.relegalize(history ? marks : live_marks, false);
  tets = mesh.finite_tetrahedra(static_cast<VertexId>(input_count), duplicates, options.threads);
  check.non_delaunay_after_marked = count(tets);
  check.non_delaunay_after_flips = check.non_delaunay_after_marked;
  if (check.non_delaunay_after_flips > 0) {
    check.sweep_flips = dt.relegalize({}, true);
    tets = mesh.finite_tetrahedra(static_cast<VertexId>(input_count), duplicates, options.threads);
    check.non_delaunay_after_flips = count(tets);
  }
  check.mesh_consistent_after_flips = check.mesh_consistent_after;
  if (check.non_delaunay_after_flips > 0 && options.repair == Repair::Rebuild) {
    check.rebuilt = true;
    TriangulationStats rebuild_stats;
    TriangulateOptions sequential = options;
    sequential.progress = false;
    tets = run_sequential(
        MethodInput{run.points, input_count, run.order, run.first, run.skip_first, sequential},
        rebuild_stats);
    count(tets);
  }
  check.seconds_repair = std::chrono::duration<double>(Clock::now() - t0).count() -
                         (check.seconds_check - check_before);
  return tets;
}

#define DTLAB_INSTANTIATE(K)                                                                     \
  template std::vector<Tetrahedron> post_check<K>(                                               \
      SharedMesh&, const std::vector<TetId>&, const std::vector<std::pair<VertexId, VertexId>>&, \
      const MethodInput&, TriangulationStats&);
DTLAB_FOR_EACH_KERNEL(DTLAB_INSTANTIATE)
#undef DTLAB_INSTANTIATE

}  // namespace dtlab::engine
