#include "commands.hpp"

#include <cstdio>
#include <fstream>
#include <iostream>
#include <nlohmann/json.hpp>
#include <optional>
#include <stdexcept>

#include "dtlab/engine/face_adjacency.hpp"
#include "dtlab/engine/methods.hpp"
#include "dtlab/engine/point_set_info.hpp"
#include "dtlab/engine/repair.hpp"
#include "dtlab/engine/validator.hpp"
#include "dtlab/generators/generators.hpp"
#include "dtlab/io/mesh_writers.hpp"
#include "dtlab/io/point_readers.hpp"
#include "dtlab/predicates/audit.hpp"
#include "input.hpp"

namespace dtlab::cli {
namespace {

// Writes `text` to `path`: a file that cannot be opened, or a write that fails (a full disk,
// /dev/full), is an error, not stats silently lost.
void write_text_file(const std::string& path, const std::string& text) {
  std::ofstream out(path);
  if (!out) throw std::runtime_error(path + ": cannot open for writing");
  out << text;
  out.close();
  if (!out) throw std::runtime_error(path + ": writing failed (is the disk full?)");
}

bool ends_with(const std::string& s, const std::string& suffix) {
  return s.size() >= suffix.size() &&
         s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}

void write_points(const std::string& path, const std::vector<predicates::Point3>& points) {
  if (ends_with(path, ".node")) {
    io::write_node(path, points);
  } else if (ends_with(path, ".xyz")) {
    io::write_xyz(path, points);
  } else {
    throw std::invalid_argument(path + ": output must end in .xyz or .node");
  }
}

// The mesh and the files beside it, as `output` asks. The .vtu gets `cells` as cell arrays.
// `mesh` is read in place; only --canonical makes a (sorted) copy.
void write_mesh(const MeshOutput& output, const std::vector<predicates::Point3>& points,
                const std::vector<engine::Tetrahedron>& mesh,
                const std::vector<io::CellArray>& cells) {
  if (output.path.empty()) return;
  std::vector<engine::Tetrahedron> canonical;
  if (output.canonical) {
    if (!cells.empty()) {
      throw std::invalid_argument("--canonical reorders the tetrahedra: not with cell arrays");
    }
    canonical = engine::canonical_tetrahedra(mesh);
  }
  const std::vector<engine::Tetrahedron>& tets = output.canonical ? canonical : mesh;
  const std::string stem = output.path.substr(0, output.path.size() - 4);
  if (ends_with(output.path, ".ele")) {
    io::write_node(stem + ".node", points);
    io::write_ele(output.path, tets);
  } else {
    io::write_vtu(output.path, points, tets, cells, output.vtu);
  }
  if (output.neighbors || output.hull) {
    const engine::FaceAdjacency adjacency = engine::face_adjacency(tets, points.size());
    if (output.neighbors) io::write_neigh(stem + ".neigh", adjacency.neighbors);
    if (output.hull) {
      io::write_face(stem + ".face", adjacency.boundary_faces, adjacency.boundary_face_tetrahedra);
    }
  }
}

void check_mesh_output(const MeshOutput& output) {
  if (!output.path.empty() && !ends_with(output.path, ".ele") && !ends_with(output.path, ".vtu")) {
    throw std::invalid_argument(output.path + ": output must end in .ele or .vtu");
  }
  if (output.path.empty() && (output.neighbors || output.hull || output.canonical)) {
    throw std::invalid_argument("--neighbors, --hull and --canonical need -o FILE");
  }
}

}  // namespace

int run_generate(const std::string& family, std::int64_t n, std::uint64_t seed,
                 const std::string& output) {
  const generators::GeneratedPoints g = generators::generate(family, n, seed);
  if (!g.note.empty()) std::fprintf(stderr, "dtlab: %s\n", g.note.c_str());
  write_points(output, g.points);
  std::fprintf(stderr, "dtlab: wrote %zu points to %s\n", g.points.size(), output.c_str());
  return 0;
}

int run_methods() {
  auto either = [](bool a, bool b, const char* first, const char* second) {
    return a && b ? std::string(first) + ", " + second : std::string(a ? first : second);
  };
  std::printf("| method | what it does | threads | location | insertion | post-check |\n");
  std::printf("|---|---|---|---|---|---|\n");
  for (const engine::MethodInfo& m : engine::methods()) {
    std::string threads = "T";
    if (!m.parallel) {
      threads = "1";
    } else if (m.min_threads > 1) {
      threads = "T (at least " + std::to_string(m.min_threads) + ")";
    } else if (m.spins) {
      threads = "T (at most " + std::to_string(engine::kSpinningThreadsPerCpu) + " a CPU)";
    }
    std::printf("| `%s` | %s | %s | %s | %s | %s |\n", m.name, m.summary, threads.c_str(),
                either(m.dag, m.walk, "dag", "walk").c_str(),
                either(m.flips, m.cavity, "flips", "cavity").c_str(), m.post_check ? "yes" : "-");
  }
  return 0;
}

int run_info(const std::string& input, std::uint64_t seed) {
  const auto points = load_input(input, seed);
  const engine::PointSetInfo info = engine::analyze(points);
  std::printf("input:               %s\n", input.c_str());
  std::printf("points:              %llu\n", static_cast<unsigned long long>(info.count));
  std::printf("distinct points:     %llu\n", static_cast<unsigned long long>(info.distinct));
  std::printf("exact duplicates:    %llu\n", static_cast<unsigned long long>(info.duplicates));
  std::printf("bounding box:        [%.17g .. %.17g] x [%.17g .. %.17g] x [%.17g .. %.17g]\n",
              info.min.x, info.max.x, info.min.y, info.max.y, info.min.z, info.max.z);
  std::printf("dimension:           %s\n", engine::dimension_name(info.dimension).c_str());
  std::printf("coplanar:            %s\n", info.dimension <= 2 ? "yes" : "no");
  std::printf("collinear:           %s\n", info.dimension <= 1 ? "yes" : "no");
  std::printf("magnitude range:     %.6g .. %.6g (smallest nonzero |coordinate| .. largest)\n",
              info.min_abs_nonzero, info.max_abs);
  const engine::RangeScaling scaling =
      engine::adaptive_range_scaling(info.max_abs, info.min_abs_nonzero);
  if (scaling.lossless) {
    std::printf("scaling:             exact, by 2^%d (largest |coordinate| to [2^99, 2^100))\n",
                scaling.exponent);
  } else {
    std::printf("scaling:             none (2^%d would make nonzero coordinates subnormal)\n",
                scaling.exponent);
  }
  std::printf("expansion range:     %s\n",
              info.within_expansion_range
                  ? "yes (adaptive and filtered kernels never need their GMP fallback)"
                  : "no (adaptive and filtered calls that the float stage cannot decide go to "
                    "GMP: exact, slower)");
  return 0;
}

int run_triangulate(const TriangulateArgs& args) {
  if (!engine::method_info(args.options.method).parallel && args.threads != 1) {
    throw std::invalid_argument(std::string("the ") + engine::to_string(args.options.method) +
                                " method runs on one thread (--threads 1)");
  }
  if (args.threads < 1 || args.threads > 1024) {
    throw std::invalid_argument("--threads must be in [1, 1024]");
  }
  engine::TriangulateOptions options = args.options;
  options.threads = args.threads;
  // What the engine refuses, refused before the input is read.
  if (const auto why = engine::unsupported(options)) throw std::invalid_argument(*why);
  check_mesh_output(args.output);
  if (args.output.canonical && args.validate && ends_with(args.output.path, ".vtu")) {
    throw std::invalid_argument(
        "--canonical with --validate -o FILE.vtu: the non_delaunay cell array follows the "
        "engine's order; write .ele, or validate without --canonical");
  }
  // Moved in, handed back: one copy of the points at the run's peak.
  const engine::Triangulation result =
      engine::triangulate(load_input(args.input, args.options.seed), options);
  const std::vector<predicates::Point3>& points = result.points;

  std::optional<engine::ValidationReport> report;
  if (args.validate)
    report = engine::validate(points, result.tetrahedra, args.validate_with, engine::kAllThreads);

  std::vector<io::CellArray> cells;
  if (report && ends_with(args.output.path, ".vtu")) {
    cells.push_back({"non_delaunay", report->non_delaunay_flags});
  }
  write_mesh(args.output, points, result.tetrahedra, cells);

  const std::string method = engine::to_string(args.options.method);
  std::string json = engine::stats_json(result.stats, options, method, args.threads);
  if (report) {
    json.pop_back();  // '}'
    while (!json.empty() && (json.back() == '\n' || json.back() == ' ')) json.pop_back();
    std::string validation = report->json();
    std::string indented;
    for (const char c : validation) {
      indented += c;
      if (c == '\n') indented += "  ";
    }
    json += ",\n  \"validation\": " + indented + "\n}";
  }
  if (args.stats == "-") {
    std::cout << json << "\n";
  } else {
    if (!args.stats.empty()) {
      write_text_file(args.stats, json + "\n");
    }
    const auto& s = result.stats;
    std::printf(
        "triangulated %llu points (%llu inserted, %llu duplicates, %llu abandoned) into "
        "%llu tetrahedra in %.3f s [%s, %s, %s, %s location, %s insertion, seed %llu]\n",
        static_cast<unsigned long long>(s.points), static_cast<unsigned long long>(s.inserted),
        static_cast<unsigned long long>(s.duplicates),
        static_cast<unsigned long long>(s.abandoned_insertions),
        static_cast<unsigned long long>(s.tetrahedra), s.seconds.total,
        engine::to_string(args.options.kernel), engine::to_string(args.options.bounding),
        method.c_str(), engine::to_string(args.options.location),
        engine::to_string(args.options.insertion),
        static_cast<unsigned long long>(args.options.seed));
    std::printf("  time: location %.3f s, subdivision %.3f s, legalization %.3f s, other %.3f s\n",
                s.seconds.location, s.seconds.subdivision, s.seconds.legalization, s.seconds.other);
    std::printf("  wall: before the first insertion %.3f s, after the last %.3f s\n",
                s.seconds.ordering, s.seconds.output);
    std::printf(
        "  flips: S23 %llu, S32 %llu, S22 %llu, S44 %llu; DAG nodes %llu; peak RSS %.1f MiB\n",
        static_cast<unsigned long long>(s.flips.s23), static_cast<unsigned long long>(s.flips.s32),
        static_cast<unsigned long long>(s.flips.s22), static_cast<unsigned long long>(s.flips.s44),
        static_cast<unsigned long long>(s.dag_nodes),
        static_cast<double>(s.peak_rss_bytes) / (1024.0 * 1024.0));
    if (args.options.insertion == engine::Insertion::Cavity) {
      std::printf(
          "  cavities: %llu points inserted by their cavity (%.2f tetrahedra replaced each), %llu "
          "fell back to flips\n",
          static_cast<unsigned long long>(s.cavity.insertions),
          s.cavity.insertions == 0 ? 0.0
                                   : static_cast<double>(s.cavity.tetrahedra_removed) /
                                         static_cast<double>(s.cavity.insertions),
          static_cast<unsigned long long>(s.cavity.fallbacks));
    }
    if (!s.threads.empty()) {
      engine::ThreadStats sum;
      for (const engine::ThreadStats& t : s.threads) {
        sum.waits += t.waits;
        sum.deadlocks += t.deadlocks;
        sum.give_ups += t.give_ups;
        sum.burglaries += t.burglaries;
        sum.potential_problems += t.potential_problems;
        sum.suspicious_tetrahedra += t.suspicious_tetrahedra;
      }
      std::printf(
          "  threads %d: waits %llu, deadlocks %llu, give-ups %llu, burglaries %llu, "
          "potential problems %llu, suspicious tetrahedra %llu\n",
          args.threads, static_cast<unsigned long long>(sum.waits),
          static_cast<unsigned long long>(sum.deadlocks),
          static_cast<unsigned long long>(sum.give_ups),
          static_cast<unsigned long long>(sum.burglaries),
          static_cast<unsigned long long>(sum.potential_problems),
          static_cast<unsigned long long>(sum.suspicious_tetrahedra));
    }
    if (s.post_check.done) {
      const engine::PostCheck& c = s.post_check;
      std::printf(
          "  post-check: %llu non-Delaunay faces and %llu reflex boundary edges after the "
          "run, mesh consistent: %s",
          static_cast<unsigned long long>(c.non_delaunay_faces),
          static_cast<unsigned long long>(c.reflex_boundary_edges),
          c.mesh_consistent ? "yes" : "no");
      if (c.repaired && !engine::splays(args.options.repair)) {  // star splaying: its own line
        std::printf(
            "; repair (%s): %llu flips on the marks -> %llu, sweep %llu flips -> %llu, "
            "rebuilt: %s -> %llu",
            engine::to_string(args.options.repair), static_cast<unsigned long long>(c.repair_flips),
            static_cast<unsigned long long>(c.non_delaunay_after_marked),
            static_cast<unsigned long long>(c.sweep_flips),
            static_cast<unsigned long long>(c.non_delaunay_after_flips), c.rebuilt ? "yes" : "no",
            static_cast<unsigned long long>(c.non_delaunay_after));
      }
      std::printf("\n");
      if (c.repaired && c.non_delaunay_after > 0 && !engine::splays(args.options.repair)) {
        std::fprintf(stderr,
                     "dtlab: warning: the repair flips got stuck with %llu non-Delaunay faces "
                     "and reflex boundary edges left; --repair=rebuild triangulates again as a "
                     "last resort\n",
                     static_cast<unsigned long long>(c.non_delaunay_after));
      }
    }
    if (s.splay.done && s.splay.proven_by_post_check) {
      std::printf(
          "  repair (star splaying): nothing to do; the post-check's exact validation proved the "
          "mesh the unique (perturbed) Delaunay tetrahedralization in %.3f s\n",
          s.post_check.seconds_check);
    } else if (s.splay.done) {
      const engine::SplayStats& r = s.splay;
      std::printf(
          "  repair (star splaying): %llu non-Delaunay faces (%s), %llu bad tetrahedra, %llu "
          "reflex hull vertices and %llu missing vertices found; %llu seeds, %llu stars splayed, "
          "%llu tetrahedra replaced by %llu in %.3f s\n",
          static_cast<unsigned long long>(r.non_delaunay_faces),
          r.found_by_post_check ? "the post-check's" : "its exact scan's",
          static_cast<unsigned long long>(r.bad_tetrahedra),
          static_cast<unsigned long long>(r.reflex_hull_vertices),
          static_cast<unsigned long long>(r.missing_vertices),
          static_cast<unsigned long long>(r.seeds), static_cast<unsigned long long>(r.stars),
          static_cast<unsigned long long>(r.tetrahedra_removed),
          static_cast<unsigned long long>(r.tetrahedra_created), r.seconds);
      if (r.flipped) {
        std::printf(
            "  repair (flips before the stars): %llu exact flips in %.3f s left %llu non-Delaunay "
            "faces, whose vertices were the seeds above\n",
            static_cast<unsigned long long>(r.flips), r.seconds_flipping,
            static_cast<unsigned long long>(r.faces_left));
      }
    }
    if (s.hull_tetrahedra_lost >= 0) {
      std::printf("  aux-tet: %lld tetrahedra of the exact convex hull triangulation lost\n",
                  static_cast<long long>(s.hull_tetrahedra_lost));
    }
    if (report) {
      std::printf(
          "  validation (%s predicates): %s; non-Delaunay faces %llu, reflex boundary edges %llu, "
          "volume = hull volume: %s, consistent: %s, mesh consistent: %s\n",
          report->kernel.c_str(), report->valid() ? "VALID" : "INVALID",
          static_cast<unsigned long long>(report->non_delaunay_faces),
          static_cast<unsigned long long>(report->reflex_boundary_edges),
          report->volume_mismatch == 0 ? "yes" : "NO", report->consistent() ? "yes" : "no",
          report->mesh_consistent() ? "yes" : "no");
    }
  }
  return report && !report->valid() ? 1 : 0;
}

int run_validate(const std::string& points_path, const std::string& mesh,
                 engine::ValidateWith kernel, int threads, bool any_orientation) {
  const auto points = io::read_points(points_path);
  const int base = io::node_index_base(points_path);
  auto tets = io::read_ele(mesh, points.size(), base);
  const std::uint64_t turned = any_orientation ? engine::orient_positively(points, tets) : 0;
  const engine::ValidationReport report = engine::validate(points, tets, kernel, threads);
  if (any_orientation) {
    auto j = nlohmann::ordered_json::parse(report.json());
    j["turned_tetrahedra"] = turned;
    std::cout << j.dump(2) << "\n";
  } else {
    std::cout << report.json() << "\n";
  }
  return report.valid() ? 0 : 1;
}

int run_repair(const std::string& points_path, const std::string& mesh, const MeshOutput& output,
               const std::string& stats_path, bool validate, int threads) {
  check_mesh_output(output);
  const auto points = io::read_points(points_path);
  const auto tets = io::read_ele(mesh, points.size(), io::node_index_base(points_path));
  engine::SplayStats stats;
  const auto repaired = engine::repair(points, tets, stats, threads);
  std::optional<engine::ValidationReport> report;
  if (validate)
    report =
        engine::validate(points, repaired, engine::ValidateWith::Adaptive, engine::kAllThreads);
  write_mesh(output, points, repaired, {});
  auto j = nlohmann::ordered_json::parse(
      engine::repair_stats_json(stats, points.size(), tets.size(), repaired.size()));
  if (report) j["validation_valid"] = report->valid();
  if (stats_path == "-") {
    std::cout << j.dump(2) << "\n";
  } else {
    if (!stats_path.empty()) {
      write_text_file(stats_path, j.dump(2) + "\n");
    }
    std::printf(
        "repaired %zu tetrahedra on %zu points into the Delaunay tetrahedralization: %zu "
        "tetrahedra; %llu stars splayed, %llu points no tetrahedron used, %llu pieces of "
        "agreeing stars bridged, %.3f s\n",
        tets.size(), points.size(), repaired.size(), static_cast<unsigned long long>(stats.stars),
        static_cast<unsigned long long>(stats.missing_vertices),
        static_cast<unsigned long long>(stats.bridges), stats.seconds);
    if (stats.local) {
      std::printf(
          "  locally: the input was a tetrahedralization of the hull (checked in %.3f s); stars "
          "only around the %llu faces and edges the perturbed Delaunay test rejects\n",
          stats.seconds_checking, static_cast<unsigned long long>(stats.non_delaunay_faces));
    }
    if (report) {
      std::printf("  validation (adaptive predicates): %s\n",
                  report->valid() ? "VALID" : "INVALID");
    }
  }
  return report && !report->valid() ? 1 : 0;
}

int run_predicates_audit(const std::string& input, std::uint64_t seed, engine::KernelKind kernel) {
  const auto points = load_input(input, seed);
  engine::TriangulateOptions options;
  options.kernel = kernel;
  options.seed = seed;
  options.audit = true;
  predicates::audit_counters().reset();
  const engine::Triangulation result = engine::triangulate(points, options);
  std::printf("predicate calls made by triangulating %s (%zu points, seed %llu, %s kernel):\n",
              input.c_str(), points.size(), static_cast<unsigned long long>(seed),
              engine::to_string(kernel));
  std::printf("%s", predicates::audit_table(engine::to_string(kernel)).c_str());
  switch (kernel) {
    case engine::KernelKind::Fast:
      std::printf("(stages apply to the adaptive and filtered kernels only)\n");
      break;
    case engine::KernelKind::Adaptive:
      std::printf(
          "(stage A: float filter; B: exact on rounded differences; C: tail correction; D: exact "
          "expansions; gmp: GMP fallback outside the expansion range. Wrong sign is measured for "
          "the fast kernel only)\n");
      break;
    case engine::KernelKind::Filtered:
      std::printf(
          "(stage A: the semi-static filter decided; every later column is a filter failure: "
          "D: exact expansions, gmp: GMP fallback outside the expansion range. Wrong sign is "
          "measured for the fast kernel only)\n");
      break;
    case engine::KernelKind::Exact:
      std::printf(
          "(stages apply to the adaptive and filtered kernels only; wrong sign is measured for "
          "the fast kernel only, against the exact kernel)\n");
      break;
  }
  std::printf("tetrahedra: %zu, abandoned insertions: %llu\n", result.tetrahedra.size(),
              static_cast<unsigned long long>(result.stats.abandoned_insertions));
  return 0;
}

}  // namespace dtlab::cli
