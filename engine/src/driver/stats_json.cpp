// The --stats JSON object: every stat of a run and the options that made it, one key each (the
// experiments' CSV columns are these keys, flattened).
#include <array>
#include <utility>

#include "dtlab/engine/triangulate.hpp"
#include "support/json_fields.hpp"

namespace dtlab::engine {
namespace {

// The lock methods' counters, each summed over the threads and listed per thread.
constexpr std::array<std::pair<const char*, std::uint64_t ThreadStats::*>, 9> kLockCounters{{
    {"waits", &ThreadStats::waits},
    {"deadlocks", &ThreadStats::deadlocks},
    {"stale_cycles", &ThreadStats::stale_cycles},
    {"give_ups", &ThreadStats::give_ups},
    {"priority_raises", &ThreadStats::priority_raises},
    {"burglaries", &ThreadStats::burglaries},
    {"burgled", &ThreadStats::burgled},
    {"potential_problems", &ThreadStats::potential_problems},
    {"suspicious_tetrahedra", &ThreadStats::suspicious_tetrahedra},
}};

void put_threads(Json& j, const TriangulationStats& s, const TriangulateOptions& options) {
  Json per_thread = Json::array();
  for (const ThreadStats& t : s.threads) {
    Json one;
    put(one, {{"inserted", t.inserted}, {"duplicates", t.duplicates}, {"abandoned", t.abandoned}});
    for (const auto& [name, counter] : kLockCounters) one[name] = t.*counter;
    per_thread.push_back(one);
  }
  for (const auto& [name, counter] : kLockCounters) {
    std::uint64_t sum = 0;
    for (const ThreadStats& t : s.threads) sum += t.*counter;
    j[name] = sum;
  }
  if (options.method == Method::Batch) {
    put(j, {{"queue_full_waits", s.queue_full_waits}, {"queue_empty_waits", s.queue_empty_waits}});
  }
  j["per_thread"] = per_thread;
}

// How a pass of the partitioned method cut its parts: "x", "y" or "z" (the curve's halves, slabs
// across that axis), "curve" (arcs cut at the keys' quantiles), or "none" (one part).
const char* cut_name(const PartitionPass& p) {
  if (p.parts <= 1) return "none";
  if (p.cut_axis < 0 || p.cut_axis > 2) return "curve";
  return std::array{"x", "y", "z"}[static_cast<std::size_t>(p.cut_axis)];
}

// The partitioned method's passes, one object each, and their count.
void put_partition_passes(Json& j, const std::vector<PartitionPass>& passes,
                          const TriangulateOptions& options) {
  Json list = Json::array();
  std::uint64_t postponed = 0;
  std::uint64_t deferred = 0;
  for (const PartitionPass& p : passes) {
    Json one;
    put(one, {{"points", p.points},
              {"parts", p.parts},
              {"cut", cut_name(p)},
              {"most_points", p.most_points},
              {"after_rounds", p.after_rounds},
              {"postponed", p.postponed},
              {"deferred", p.deferred},
              {"stopped_walks", p.stopped_walks},
              {"seconds", p.seconds},
              {"setup_seconds", p.setup_seconds},
              {"imbalance", p.imbalance}});
    list.push_back(one);
    postponed += p.postponed;
    deferred += p.deferred;
  }
  put(j, {{"partition_rounds", passes.size()},
          {"partition_postponed", postponed},
          {"partition_deferred", deferred},
          {"points_per_part", options.points_per_part}});
  j["partition_passes"] = list;
}

Json post_check_json(const PostCheck& c, const TriangulateOptions& options) {
  Json pc;
  put(pc, {{"non_delaunay_faces", c.non_delaunay_faces},
           {"reflex_boundary_edges", c.reflex_boundary_edges},
           {"mesh_consistent", c.mesh_consistent},
           {"repaired", c.repaired},
           {"repair", to_string(options.repair)}});
  if (c.repaired) {
    put(pc, {{"repair_flips", c.repair_flips},
             {"non_delaunay_after_marked", c.non_delaunay_after_marked},
             {"sweep_flips", c.sweep_flips},
             {"non_delaunay_after_flips", c.non_delaunay_after_flips},
             {"mesh_consistent_after_flips", c.mesh_consistent_after_flips},
             {"rebuilt", c.rebuilt},
             {"seconds_repair", c.seconds_repair}});
  }
  put(pc, {{"non_delaunay_faces_after", c.non_delaunay_faces_after},
           {"reflex_boundary_edges_after", c.reflex_boundary_edges_after},
           {"mesh_consistent_after", c.mesh_consistent_after},
           {"non_delaunay_after", c.non_delaunay_after},
           {"seconds_check", c.seconds_check}});
  return pc;
}

Json splay_json(const SplayStats& r) {
  Json splay;
  put(splay, {{"non_delaunay_faces", r.non_delaunay_faces},
              {"bad_tetrahedra", r.bad_tetrahedra},
              {"reflex_hull_vertices", r.reflex_hull_vertices},
              {"missing_vertices", r.missing_vertices},
              {"seeds", r.seeds},
              {"live_marks", r.live_marks},
              {"marks_seeded", r.marks_seeded},
              {"proven_by_post_check", r.proven_by_post_check},
              {"found_by_post_check", r.found_by_post_check},
              {"stars_walked", r.stars_walked},
              {"stars", r.stars},
              {"offers", r.offers},
              {"changes", r.changes},
              {"regrown", r.regrown},
              {"bridges", r.bridges},
              {"tetrahedra_removed", r.tetrahedra_removed},
              {"tetrahedra_created", r.tetrahedra_created},
              {"seconds", r.seconds},
              {"seconds_scan", r.seconds_scan},
              {"seconds_listing", r.seconds_listing},
              {"seconds_building", r.seconds_building},
              {"seconds_enforcing", r.seconds_enforcing},
              {"flipped", r.flipped},
              {"flips", r.flips},
              {"faces_left", r.faces_left},
              {"walk_starts_moved", r.walk_starts_moved},
              {"seconds_flipping", r.seconds_flipping},
              {"scan_threads", r.scan_threads}});
  return splay;
}

}  // namespace

std::string stats_json(const TriangulationStats& s, const TriangulateOptions& options,
                       const std::string& method, int threads) {
  Json j;
  Json seconds;
  put(seconds, {{"total", s.seconds.total},
                {"location", s.seconds.location},
                {"subdivision", s.seconds.subdivision},
                {"legalization", s.seconds.legalization},
                {"other", s.seconds.other},
                {"ordering", s.seconds.ordering},
                {"output", s.seconds.output}});
  Json flips;
  put(flips,
      {{"S23", s.flips.s23}, {"S32", s.flips.s32}, {"S22", s.flips.s22}, {"S44", s.flips.s44}});
  Json cavity;
  put(cavity, {{"insertions", s.cavity.insertions},
               {"tetrahedra_removed", s.cavity.tetrahedra_removed},
               {"fallbacks", s.cavity.fallbacks}});
  put(j, {{"points", s.points},
          {"inserted", s.inserted},
          {"duplicates", s.duplicates},
          {"tetrahedra", s.tetrahedra},
          {"seconds", seconds},
          {"flips", flips},
          {"cavity", cavity},
          {"dag_nodes", s.dag_nodes},
          {"predicate_calls", s.predicate_calls},
          {"location_steps", s.location_steps},
          {"walk_fallbacks", s.walk_fallbacks},
          {"store_slots", s.store_slots},
          {"abandoned_insertions", s.abandoned_insertions},
          {"hull_tetrahedra_lost",
           s.hull_tetrahedra_lost >= 0 ? Json(s.hull_tetrahedra_lost) : Json(nullptr)},
          {"peak_rss_bytes", s.peak_rss_bytes},
          // The whole process's peak (input, output and the run) per input point.
          {"bytes_per_point", s.points > 0 ? s.peak_rss_bytes / s.points : 0},
          {"scale_exponent", s.scale_exponent}});
  if (!s.threads.empty()) put_threads(j, s, options);
  if (!s.partition_passes.empty()) put_partition_passes(j, s.partition_passes, options);
  if (s.lock_grid_cells > 0) j["lock_grid_cells"] = s.lock_grid_cells;
  if (s.post_check.done) j["post_check"] = post_check_json(s.post_check, options);
  if (s.splay.done) j["splay"] = splay_json(s.splay);
  put(j, {{"repair", to_string(options.repair)},
          {"method", method},
          {"threads", threads},
          {"distribution", to_string(effective_distribution(options))},
          {"predicates", to_string(options.kernel)},
          {"location", to_string(options.location)},
          {"insertion", to_string(options.insertion)},
          {"bounding", to_string(options.bounding)},
          {"seed", options.seed}});
  return j.dump(2);
}

std::string repair_stats_json(const SplayStats& stats, std::uint64_t points,
                              std::uint64_t tetrahedra_in, std::uint64_t tetrahedra_out) {
  Json j;
  put(j, {{"points", points},
          {"tetrahedra_in", tetrahedra_in},
          {"tetrahedra_out", tetrahedra_out},
          {"local", stats.local},
          {"non_delaunay_faces", stats.non_delaunay_faces},
          {"seconds_checking", stats.seconds_checking},
          {"missing_vertices", stats.missing_vertices},
          {"stars", stats.stars},
          {"offers", stats.offers},
          {"changes", stats.changes},
          {"bridges", stats.bridges},
          {"seconds", stats.seconds}});
  return j.dump(2);
}

}  // namespace dtlab::engine
