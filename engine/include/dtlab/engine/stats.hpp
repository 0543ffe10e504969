#pragma once
// What a run reports: counts, phase times, each thread's lock counters, burglary's post-check and
// star splaying's repair, and the JSON object `--stats` writes (docs/design.md, "Stats").
#include <cstdint>
#include <string>
#include <vector>

#include "dtlab/engine/options.hpp"

namespace dtlab::engine {

struct FlipCounts {
  std::uint64_t s23 = 0;
  std::uint64_t s32 = 0;
  std::uint64_t s22 = 0;
  std::uint64_t s44 = 0;
};

// Cavity insertion (--insertion cavity).
struct CavityCounts {
  std::uint64_t insertions = 0;          // points inserted by their cavity
  std::uint64_t tetrahedra_removed = 0;  // the cavities' tetrahedra, summed
  std::uint64_t fallbacks = 0;  // cavities that were no star around the point (inexact kernel):
                                // inserted by flips
};

// Seconds of a run. location, subdivision and legalization are summed over the inserting
// threads (CPU seconds: on several threads their sum can exceed total); other is total less
// their sum, at least 0. ordering and output are wall-clock and part of total: the steps before
// the first insertion (checking, ordering, renumbering and scaling the points) and after the
// last (collecting the tetrahedra, naming them in input order, restoring the points), which
// a parallel method runs on its threads too. (Burglary's post-check collects the mesh again after
// a repair: that collection is the repair's, in post_check.seconds_repair.)
struct PhaseSeconds {
  double total = 0.0;
  double location = 0.0;
  double subdivision = 0.0;
  double legalization = 0.0;
  double other = 0.0;
  double ordering = 0.0;
  double output = 0.0;
};

// Counters of one inserting thread of a parallel method.
struct ThreadStats {
  std::uint64_t inserted = 0;
  std::uint64_t duplicates = 0;
  std::uint64_t abandoned = 0;
  std::uint64_t waits = 0;            // lock requests that found the lock taken and waited
  std::uint64_t deadlocks = 0;        // waits that would have closed a cycle (detect)
  std::uint64_t stale_cycles = 0;     // closed wait chains that no longer held: not deadlocks
  std::uint64_t give_ups = 0;         // insertions undone and retried
  std::uint64_t priority_raises = 0;  // prevent
  std::uint64_t burglaries = 0;       // burglary: deadlocks broken by picking the partner's locks
  std::uint64_t burgled = 0;          // burglary: times this thread was the victim
  std::uint64_t potential_problems = 0;     // victim found its part changed and stopped
  std::uint64_t suspicious_tetrahedra = 0;  // marks left for the post-check
};

// One pass of the partitioned method: the points it tried, each thread inserting only where its
// part of the curve owns the mesh; the points whose change reached another part wait for the next
// pass (whose cuts differ).
struct PartitionPass {
  std::uint64_t points = 0;         // tried in this pass
  std::uint64_t parts = 0;          // threads inserting (1: the pass runs on one thread)
  int cut_axis = -1;                // several parts: the curve's halves, slabs across axis 0 (x),
                                    // 1 (y) or 2 (z); -1: arcs cut at quantiles; one part: -1
  std::uint64_t most_points = 0;    // the most of the pass's points one part had
  bool after_rounds = false;        // a pass after the last BRIO round (it never defers)
  std::uint64_t postponed = 0;      // given up: left for a later pass
  std::uint64_t deferred = 0;       // not tried: the first part to finish ended the pass, and
                                    // these wait for the next (only in a BRIO round's pass)
  std::uint64_t stopped_walks = 0;  // of those, walks stopped at the part's border (or
                                    // with no readable start)
  double seconds = 0.0;             // the pass's wall time
  double setup_seconds = 0.0;       // of which before its threads insert: the cut, the keys,
                                    // the sort along the curve, the walk starts
  double imbalance = 1.0;           // the busiest part's time over the parts' mean (1: balanced)
};

// Burglary's sequential post-check (paper Sect. 5): the exact validator's count after the
// parallel run, and with --repair the flips on the marked tetrahedra and the counts after them.
struct PostCheck {
  bool done = false;
  std::uint64_t non_delaunay_faces = 0;     // after the parallel run
  std::uint64_t reflex_boundary_edges = 0;  // non-convex hull: infinite tetrahedra not Delaunay
  bool mesh_consistent = false;    // adjacency, orientation, closed boundary, every point a vertex
  bool repaired = false;           // --repair ran
  std::uint64_t repair_flips = 0;  // flips on and below the marked tetrahedra
  std::uint64_t non_delaunay_after_marked = 0;  // faces + reflex boundary edges left
  std::uint64_t sweep_flips = 0;  // second pass over every tetrahedron, when marks missed some
  std::uint64_t non_delaunay_after_flips = 0;  // left when the flips ended (stuck if > 0)
  bool mesh_consistent_after_flips = false;    // the flips kept the mesh sound
  bool rebuilt = false;  // Repair::Rebuild only, when flips got stuck: triangulated again
  // The validator's full verdict on the mesh returned (after the last stage that ran):
  std::uint64_t non_delaunay_faces_after = 0;
  std::uint64_t reflex_boundary_edges_after = 0;
  bool mesh_consistent_after = false;
  std::uint64_t non_delaunay_after = 0;  // final count (faces + reflex boundary edges)
  double seconds_check = 0.0;            // validation (excluded from seconds.total)
  double seconds_repair = 0.0;           // flips and rebuild (included)
};

// Star splaying (--repair; dtlab repair): the local repair into the Delaunay tetrahedralization.
struct SplayStats {
  bool done = false;
  std::uint64_t non_delaunay_faces = 0;  // found by the exact scan before splaying
  std::uint64_t bad_tetrahedra = 0;      // flat or inverted finite tetrahedra found by the scan
  // hull vertices the boundary does not close around convexly (inexact meshes; the scan's)
  std::uint64_t reflex_hull_vertices = 0;
  std::uint64_t missing_vertices = 0;  // points that were no vertex (abandoned insertions)
  std::uint64_t seeds = 0;             // vertices splayed from the start
  std::uint64_t live_marks = 0;        // burglary's marks that are still live tetrahedra
  bool marks_seeded = false;  // their vertices were seeds (not when the scan proved the mesh)
  // Burglary's post-check: its validation, before the repair, proved the mesh the unique
  // perturbed Delaunay tetrahedralization (ValidationReport::is_perturbed_delaunay), so nothing
  // was scanned or splayed (seconds 0; the proof's time is post_check.seconds_check).
  bool proven_by_post_check = false;
  // Burglary's post-check found faces to repair on a mesh its validation judged consistent: those
  // faces (non_delaunay_faces) are the seeds, and the exact scan was skipped (seconds_scan is the
  // store pass alone; the finding's time is post_check.seconds_check).
  bool found_by_post_check = false;
  bool stars_walked = false;  // the mesh's stars found by walks, not from incidence lists
  std::uint64_t stars = 0;    // stars built: the seeds and the vertices they reached
  std::uint64_t offers = 0;   // vertices offered to stars
  std::uint64_t changes = 0;  // offers that changed a star
  std::uint64_t regrown = 0;  // rounds that splayed more vertices where a broken mesh did not fit
  // `dtlab repair`: pieces of agreeing stars joined by their closest pair (star_pieces.hpp)
  std::uint64_t bridges = 0;
  std::uint64_t tetrahedra_removed = 0;
  std::uint64_t tetrahedra_created = 0;
  double seconds = 0.0;          // scan, splaying and writing back (included in seconds.total)
  double seconds_scan = 0.0;     // of which the store pass and the exact scan (if any)
  double seconds_listing = 0.0;  // of which the store pass (the live tetrahedra in scan order)
  // Burglary's and the fast kernel's repair: of `seconds`, building the seeds' stars (on the
  // run's threads) and the consistency enforcement from them (one thread; a broken mesh's
  // further rounds, `regrown`, not included). The rest is the store pass and scan, the grouping of
  // equal points, the incidence lists (a broken mesh's) and the write-back with its walks.
  double seconds_building = 0.0;
  double seconds_enforcing = 0.0;
  // --repair=flips-splay on a mesh built exactly: the exact Lawson flips before splaying (their
  // time part of `seconds`, after the scan), and the non-Delaunay faces they left (the seeds'
  // faces then). `flipped`: the pass ran. `walk_starts_moved`: vertices whose walk start the
  // flips killed, given one of the flips' new tetrahedra.
  bool flipped = false;
  std::uint64_t flips = 0;
  std::uint64_t faces_left = 0;
  std::uint64_t walk_starts_moved = 0;
  // dtlab repair: the list was a tetrahedralization of the hull (distinct points, the boundary one
  // sphere, every star connected, the validator's consistent()), closed into a mesh and splayed
  // from the validation's findings only; false: every vertex splayed. `seconds_checking`: the
  // checks that decided (part of `seconds` either way).
  bool local = false;
  double seconds_checking = 0.0;
  double seconds_flipping = 0.0;
  std::uint64_t scan_threads = 0;  // threads of the store pass and the scan (the run's)
};

struct TriangulationStats {
  std::uint64_t points = 0;
  std::uint64_t inserted = 0;
  std::uint64_t duplicates = 0;
  std::uint64_t tetrahedra = 0;
  PhaseSeconds seconds;
  FlipCounts flips;
  CavityCounts cavity;
  std::uint64_t dag_nodes = 0;
  std::uint64_t predicate_calls = 0;
  std::uint64_t location_steps = 0;  // DAG nodes descended or tetrahedra walked through
  std::uint64_t walk_fallbacks = 0;  // walks that failed and located by the DAG (or a scan)
  std::uint64_t store_slots = 0;     // tetrahedron slots used (DAG nodes, or live + free ones)
  std::uint64_t abandoned_insertions = 0;
  std::int64_t hull_tetrahedra_lost = -1;  // aux-tet only; -1 when not measured
  std::uint64_t peak_rss_bytes = 0;
  std::int32_t scale_exponent = 0;      // inputs were multiplied by 2^scale_exponent (exact)
  std::vector<ThreadStats> threads;     // parallel methods: one entry per inserting thread
  std::uint64_t queue_full_waits = 0;   // batch: locating threads blocked on a full queue
  std::uint64_t queue_empty_waits = 0;  // batch: the inserting thread found the queue empty
  PostCheck post_check;                 // burglary
  std::vector<PartitionPass> partition_passes;  // partitioned
  std::uint64_t lock_grid_cells = 0;            // lock-grid: cells per axis of its grid
  SplayStats splay;                             // --repair (star splaying)
};

// The stats and the options as one JSON object (the --stats output).
std::string stats_json(const TriangulationStats& stats, const TriangulateOptions& options,
                       const std::string& method, int threads);
// The repair's counts as one JSON object (dtlab repair --stats, dtlab.repair's stats).
std::string repair_stats_json(const SplayStats& stats, std::uint64_t points,
                              std::uint64_t tetrahedra_in, std::uint64_t tetrahedra_out);

}  // namespace dtlab::engine
