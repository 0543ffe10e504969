// dtlab: command line entry point.
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <iostream>
#include <map>
#include <string>

#include "commands.hpp"
#include "dtlab/common/build_info.hpp"
#include "dtlab/engine/methods.hpp"
#include "dtlab/engine/triangulate.hpp"
#include "dtlab/experiments/experiment.hpp"
#include "dtlab/io/input_error.hpp"

namespace {

// A finite number at least 0: CLI::NonNegativeNumber lets "nan" through.
const CLI::Validator kFiniteNonNegative(
    [](std::string& text) -> std::string {
      double value = 0;
      if (!CLI::detail::lexical_cast(text, value) || !std::isfinite(value) || value < 0) {
        return "Value " + text + " is not a finite number at least 0";
      }
      return {};
    },
    "FLOAT:FINITE >= 0");

// A std::uint64_t option's text, which CLI11 reads by strtoull, less its two silent wraps: "-1"
// read as 2^64 - 1, and a number above 2^64 - 1 read as 2^64 - 1; either would run with another
// seed or flip bound than asked for. Text that is no number is left to CLI11's own message.
const CLI::Validator kUnsigned64(
    [](std::string& text) -> std::string {
      if (text.find('-') != std::string::npos) return "Value " + text + " is negative";
      errno = 0;
      char* end = nullptr;
      (void)std::strtoull(text.c_str(), &end, 0);
      if (errno == ERANGE) return "Value " + text + " is above 2^64 - 1";
      return {};
    },
    "");

// --threads for a command whose result is the same for every count (default: one per hardware
// thread).
void add_threads_option(CLI::App* command, int& threads, const char* what) {
  command
      ->add_option(
          "--threads", threads,
          std::string(what) +
              " (default: one per hardware thread; the result is the same for every count)")
      ->check(CLI::Range(1, 1024));
}

// -o and what goes beside it, for the commands that write a mesh.
void add_mesh_output_options(CLI::App* command, dtlab::cli::MeshOutput& output) {
  const std::map<std::string, dtlab::io::VtuEncoding> encodings{
      {"ascii", dtlab::io::VtuEncoding::Ascii},
      {"binary", dtlab::io::VtuEncoding::Binary},
      {"zlib", dtlab::io::VtuEncoding::Zlib}};
  command->add_option("-o,--output", output.path,
                      "mesh output: FILE.ele (TetGen; FILE.node beside it) or FILE.vtu (VTK XML)");
  command
      ->add_option("--vtu", output.vtu,
                   "how the .vtu stores its arrays: zlib (default: base64 zlib blocks), binary "
                   "(base64), ascii; all inline, read by ParaView, VTK and meshio")
      ->transform(CLI::CheckedTransformer(encodings, CLI::ignore_case));
  command->add_flag("--neighbors", output.neighbors,
                    "also write FILE.neigh (TetGen): the tetrahedra across each one's four faces, "
                    "opposite vertex 0..3, -1 on the hull");
  command->add_flag("--hull", output.hull,
                    "also write FILE.face (TetGen): the hull's faces, turned outward, with the "
                    "tetrahedron behind each and -1 outside (TetGen's -nn columns)");
  command->add_flag("--canonical", output.canonical,
                    "write the tetrahedra in a canonical order (each from its smallest vertex, "
                    "orientation kept, then sorted), so that runs compare with diff");
}

// The command line's work; main() adds the check of standard output.
int run_command_line(int argc, char** argv) {
  using dtlab::engine::Bounding;
  using dtlab::engine::KernelKind;
  CLI::App app{"dtlab: a testbed for parallel 3D Delaunay triangulation with robust predicates"};
  app.set_version_flag("--version", std::string("dtlab ") + dtlab::version() + " (commit " +
                                        dtlab::build_commit() + ")");
  app.require_subcommand(1);
  const std::map<std::string, KernelKind> kernels{{"fast", KernelKind::Fast},
                                                  {"adaptive", KernelKind::Adaptive},
                                                  {"filtered", KernelKind::Filtered},
                                                  {"exact", KernelKind::Exact}};
  const std::map<std::string, Bounding> boundings{{"infinite", Bounding::Infinite},
                                                  {"aux-tet", Bounding::AuxTet}};

  std::uint64_t seed = 1;
  std::string family;
  std::int64_t count = 0;
  std::string output;
  auto* generate = app.add_subcommand("generate", "write a generated point set (.xyz or .node)");
  generate->add_option("DIST", family, "distribution (uniform, grid, sphere, ...)")->required();
  generate->add_option("N", count, "number of points asked for")->required();
  generate->add_option("--seed", seed, "random seed")->check(kUnsigned64);
  generate->add_option("-o,--output", output, "output file (.xyz or .node)")->required();

  std::string input;
  auto* info = app.add_subcommand("info", "facts about a point set: counts, duplicates, dimension");
  info->add_option("INPUT", input, "point file or generator spec (e.g. uniform:1000)")->required();
  info->add_option("--seed", seed, "seed for a generator spec")->check(kUnsigned64);

  dtlab::cli::TriangulateArgs targs;
  // The fastest exact configuration by default (docs/performance.md); --paper for the paper's.
  targs.options.location = dtlab::engine::Location::Walk;
  targs.options.insertion = dtlab::engine::Insertion::Cavity;
  auto* tri = app.add_subcommand(
      "triangulate",
      "Delaunay tetrahedralization of a point set. Default: adaptive predicates, walk location, "
      "cavity insertion, one thread (the fastest exact configuration); --paper: the paper's DAG "
      "location and flips");
  tri->add_option("INPUT", targs.input, "point file or generator spec")->required();
  tri->add_option("--predicates", targs.options.kernel,
                  "fast | adaptive | filtered | exact (default adaptive). The search for the first "
                  "tetrahedron and the test of the engine's interior point use the exact kernel "
                  "whichever kernel is chosen (so the fast kernel's failure tables do not include "
                  "those two steps)")
      ->transform(CLI::CheckedTransformer(kernels, CLI::ignore_case));
  // The methods as the registry lists them (dtlab/engine/methods.hpp).
  std::map<std::string, dtlab::engine::Method> methods;
  std::string method_help = dtlab::engine::method_names() + ":";
  for (const dtlab::engine::MethodInfo& m : dtlab::engine::methods()) {
    methods.emplace(m.name, m.method);
    method_help += std::string("\n  ") + m.name + ": " + m.summary;
  }
  const std::map<std::string, dtlab::engine::Distribution> distributions{
      {"static", dtlab::engine::Distribution::Static},
      {"dynamic", dtlab::engine::Distribution::Dynamic},
      {"strips", dtlab::engine::Distribution::Strips},
      {"blocks", dtlab::engine::Distribution::Blocks},
      {"auto", dtlab::engine::Distribution::Auto}};
  tri->add_option("--method", targs.options.method, method_help)
      ->transform(CLI::CheckedTransformer(methods, CLI::ignore_case));
  tri->add_option("--threads", targs.threads,
                  "worker threads, 1 to 1024 (batch: T - 1 locating threads and one inserting "
                  "thread, at least one of each, so --threads 1 runs two; optimistic-detect, "
                  "optimistic-prevent, burglary and lock-grid: at most " +
                      std::to_string(dtlab::engine::kSpinningThreadsPerCpu) +
                      " a CPU available, as their waiting threads spin)");
  tri->add_option("--distribution", targs.options.distribution,
                  "static | dynamic | strips | blocks | auto (default: static with --location "
                  "dag, as in the paper; blocks with --location walk, so that threads work apart)")
      ->transform(CLI::CheckedTransformer(distributions, CLI::ignore_case));
  tri->add_flag("--stress", targs.options.stress, "random short delays while locks are held");
  tri->add_option("--points-per-part", targs.options.points_per_part,
                  "partitioned: a pass uses one part (thread) per this many points, at most "
                  "--threads (default 2048; smaller passes run on one thread)")
      ->check(CLI::Range(1u, 1u << 30));
  tri->add_option(
         "--grid-cells", targs.options.lock_grid_cells,
         "lock-grid: cells per axis of the lock grid (default: about 256 points a cell, at "
         "least 2 cbrt(threads) per axis; --stats reports lock_grid_cells)")
      ->check(CLI::Range(1u, 256u));
  std::string repair = "none";
  tri->add_flag("--repair{splay}", repair,
                "repair the mesh after the run by star splaying, exact, from every non-Delaunay "
                "face (and burglary's marks): always ends in the Delaunay tetrahedralization, any "
                "method and kernel. --repair=flips-splay: on a mesh built exactly (burglary's), "
                "exact Lawson flips from those faces first, star splaying from the faces they "
                "leave. Burglary also has the paper's post-check: --repair=flips "
                "(Lawson flips on the marks, then on every face; they can get stuck, and what "
                "they leave is reported) and --repair=rebuild (the same, then a sequential "
                "rebuild as an explicit, reported last resort)")
      ->check(CLI::IsMember({"splay", "flips-splay", "flips", "rebuild"}));
  const std::map<std::string, dtlab::engine::Location> locations{
      {"dag", dtlab::engine::Location::Dag}, {"walk", dtlab::engine::Location::Walk}};
  auto* location_option =
      tri->add_option("--location", targs.options.location,
                      "point location: walk (default: BRIO + Hilbert order, visibility walk, slots "
                      "reused) or dag (the paper's history DAG, random order)")
          ->transform(CLI::CheckedTransformer(locations, CLI::ignore_case));
  const std::map<std::string, dtlab::engine::Insertion> insertions{
      {"flips", dtlab::engine::Insertion::Flips}, {"cavity", dtlab::engine::Insertion::Cavity}};
  auto* insertion_option =
      tri->add_option("--insertion", targs.options.insertion,
                      "how a located point enters the mesh: cavity (default: Bowyer-Watson, every "
                      "tetrahedron in conflict replaced at once; --location walk only, every "
                      "method) or flips (the paper's splits and S23, S32, S22, S44)")
          ->transform(CLI::CheckedTransformer(insertions, CLI::ignore_case));
  bool paper = false;
  tri->add_flag("--paper", paper,
                "the paper's configuration: --location dag --insertion flips (Kohout and "
                "Kolingerova 2003)")
      ->excludes(location_option)
      ->excludes(insertion_option);
  tri->add_option("--bounding", targs.options.bounding, "infinite | aux-tet")
      ->transform(CLI::CheckedTransformer(boundings, CLI::ignore_case));
  tri->add_option("--seed", targs.options.seed, "insertion order (and generator) seed")
      ->check(kUnsigned64);
  add_mesh_output_options(tri, targs.output);
  tri->add_option("--stats", targs.stats, "write stats JSON to FILE, or - for stdout");
  tri->add_flag("--validate", targs.validate, "check the result with the exact validator");
  const std::map<std::string, dtlab::engine::ValidateWith> validators{
      {"adaptive", dtlab::engine::ValidateWith::Adaptive},
      {"exact", dtlab::engine::ValidateWith::Exact}};
  tri->add_option("--validate-with", targs.validate_with,
                  "the validator's kernel: adaptive (default) | exact (GMP, independent)")
      ->transform(CLI::CheckedTransformer(validators, CLI::ignore_case));
  tri->add_option("--watchdog", targs.options.watchdog_seconds,
                  "parallel methods: stop and fail a run in which no insertion finished for this "
                  "many seconds (default 0: 10 s + 100 us per point, at most 60 s)")
      ->check(kFiniteNonNegative);
  tri->add_option("--max-flips", targs.options.max_flips_per_insertion,
                  "flip bound per insertion (abandon beyond)")
      ->check(kUnsigned64);

  std::string points_path;
  std::string mesh_path;
  auto* validate = app.add_subcommand("validate", "exact validation of a mesh (.node + .ele)");
  validate->add_option("POINTS", points_path, "the points (.node, .xyz, ...)")->required();
  validate->add_option("MESH", mesh_path, "the tetrahedra (.ele)")->required();
  dtlab::engine::ValidateWith validate_kernel = dtlab::engine::ValidateWith::Adaptive;
  validate
      ->add_option("--validate-with", validate_kernel,
                   "the validator's kernel: adaptive (default) | exact (GMP, independent)")
      ->transform(CLI::CheckedTransformer(validators, CLI::ignore_case));
  int validate_threads = dtlab::engine::kAllThreads;
  add_threads_option(validate, validate_threads, "threads that share the checks");
  bool any_orientation = false;
  validate->add_flag("--any-orientation", any_orientation,
                     "accept either orientation (Qhull's and other tools' lists): negative "
                     "tetrahedra are turned first and counted (turned_tetrahedra); flat ones stay "
                     "errors");

  dtlab::cli::MeshOutput repair_output;
  std::string repair_stats;
  bool repair_validate = false;
  auto* repair_cmd = app.add_subcommand(
      "repair",
      "the Delaunay tetrahedralization of POINTS from any tetrahedra on them (MESH, .ele), by "
      "star splaying with exact predicates");
  repair_cmd->add_option("POINTS", points_path, "the points (.node, .xyz, ...)")->required();
  repair_cmd->add_option("MESH", mesh_path, "the tetrahedra (.ele): any, even wrong")->required();
  add_mesh_output_options(repair_cmd, repair_output);
  repair_cmd->add_option("--stats", repair_stats, "write stats JSON to FILE, or - for stdout");
  repair_cmd->add_flag("--validate", repair_validate, "check the result with the exact validator");
  int repair_threads = dtlab::engine::kAllThreads;
  add_threads_option(repair_cmd, repair_threads, "threads that build the stars");

  std::string study;
  dtlab::experiments::ExperimentOptions eopts;
  bool list_studies = false;
  bool no_plot = false;
  auto* experiment = app.add_subcommand(
      "experiment",
      "run one study (dtlab experiment --list) and write DIR/NAME.csv, NAME.md, NAME.png and "
      "machine.json. Each study has its own configurations, written in its table (not "
      "triangulate's walk-and-cavity default)");
  std::vector<std::string> merge_dirs;
  experiment->add_option("NAME", study, "the study, or merge (then OUT and the shards' folders)");
  experiment->add_option("DIRS", merge_dirs, "merge: OUT, then the folders of every shard");
  experiment->add_option("--shard", eopts.shard,
                         "K/N: run the K-th of N slices of the plan (1 <= K <= N), for "
                         "dtlab experiment merge OUT DIR... to join");
  experiment->add_flag("--list", list_studies, "name every study and what it measures");
  experiment->add_option("--out", eopts.out_dir, "output directory");
  experiment->add_flag(
      "--quick", eopts.quick,
      "a reduced run (at most two minutes) that checks the files, not the numbers");
  experiment->add_flag("--resume", eopts.resume,
                       "keep DIR/NAME.csv's finished rows and run only the others");
  experiment->add_option("--seeds", eopts.seeds, "seeds (rounds for the timing studies)")
      ->check(CLI::Range(1, 1000));
  experiment->add_option("--threads", eopts.threads, "thread counts, e.g. 1,2,4,8")->delimiter(',');
  experiment->add_option("--sizes", eopts.sizes, "numbers of points, e.g. 10000,100000")
      ->delimiter(',');
  experiment
      ->add_option("--inputs", eopts.inputs,
                   "generator families and model names (files in the data directory)")
      ->delimiter(',');
  experiment->add_option("--location", eopts.locations, "dag, walk or both: dag,walk")
      ->delimiter(',');
  experiment->add_option("--distribution", eopts.distribution,
                         "the parallel runs' distribution: static | dynamic | strips | blocks | "
                         "auto (default: static in DAG mode, blocks in walk mode)");
  experiment->add_option("--data", eopts.data_dir,
                         "the real models' directory (default $DTLAB_DATA_DIR or ../shared/data "
                         "beside the source tree)");
  experiment->add_flag("--no-plot", no_plot, "write no PNG (no python3 or matplotlib needed)");
  experiment
      ->add_option("--timeout", eopts.timeout_seconds,
                   "seconds after which a run is killed and recorded as timed out (default: the "
                   "study's; peers 60, 20 with --quick; the others none)")
      ->check(kFiniteNonNegative);
  experiment
      ->add_option("--tools", eopts.tools,
                   "peers: the tools to run (default all): cgal-epick, cgal-doubles, qhull-Qt, "
                   "qhull-QJ, tetgen, dtlab-fast, dtlab-adaptive, dtlab-filtered")
      ->delimiter(',');
  experiment->add_option("--tetgen", eopts.tetgen,
                         "peers: the TetGen program (default $DTLAB_TETGEN or tetgen on PATH)");

  auto* methods_cmd = app.add_subcommand(
      "methods", "the methods --method takes, what each does and supports (a Markdown table)");

  KernelKind audit_kernel = KernelKind::Adaptive;
  auto* audit =
      app.add_subcommand("predicates-audit", "predicate calls per stage while triangulating INPUT");
  audit->add_option("INPUT", input, "point file or generator spec")->required();
  audit->add_option("--seed", seed, "seed")->check(kUnsigned64);
  audit->add_option("--predicates", audit_kernel, "fast | adaptive | filtered | exact")
      ->transform(CLI::CheckedTransformer(kernels, CLI::ignore_case));

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int code = app.exit(e);
    return code == 0 ? 0 : 2;
  }

  try {
    if (*generate) return dtlab::cli::run_generate(family, count, seed, output);
    if (*info) return dtlab::cli::run_info(input, seed);
    if (*tri) {
      // The DAG mode inserts by flips only: --location dag alone means the paper's insertion.
      const bool dag_alone = location_option->count() > 0 && insertion_option->count() == 0 &&
                             targs.options.location == dtlab::engine::Location::Dag;
      if (paper || dag_alone) {
        targs.options.location = dtlab::engine::Location::Dag;
        targs.options.insertion = dtlab::engine::Insertion::Flips;
      }
      targs.options.progress = isatty(STDERR_FILENO) != 0;
      targs.options.repair = repair == "splay"         ? dtlab::engine::Repair::Splay
                             : repair == "flips-splay" ? dtlab::engine::Repair::FlipsThenSplay
                             : repair == "flips"       ? dtlab::engine::Repair::Flips
                             : repair == "rebuild"     ? dtlab::engine::Repair::Rebuild
                                                       : dtlab::engine::Repair::None;
      return dtlab::cli::run_triangulate(targs);
    }
    if (*validate) {
      return dtlab::cli::run_validate(points_path, mesh_path, validate_kernel, validate_threads,
                                      any_orientation);
    }
    if (*repair_cmd) {
      return dtlab::cli::run_repair(points_path, mesh_path, repair_output, repair_stats,
                                    repair_validate, repair_threads);
    }
    if (*audit) return dtlab::cli::run_predicates_audit(input, seed, audit_kernel);
    if (*methods_cmd) return dtlab::cli::run_methods();
    if (*experiment) {
      if (list_studies) {
        for (const auto& s : dtlab::experiments::list_studies()) {
          std::printf("%-18s %s\n", s.name.c_str(), s.summary.c_str());
        }
        return 0;
      }
      if (study.empty()) {
        std::fprintf(stderr, "dtlab: error: name a study (dtlab experiment --list)\n");
        return 2;
      }
      eopts.plot = !no_plot;
      for (int i = 0; i < argc; ++i) {
        eopts.command_line += (i == 0 ? std::string("dtlab") : " " + std::string(argv[i]));
      }
      if (study == "merge") {
        if (merge_dirs.size() < 2 || !eopts.out_dir.empty()) {
          std::fprintf(stderr,
                       "dtlab: error: dtlab experiment merge OUT DIR... (OUT, then "
                       "every shard's folder; no --out)\n");
          return 2;
        }
        eopts.out_dir = merge_dirs.front();
        return dtlab::experiments::merge_experiment(
            std::vector<std::string>(merge_dirs.begin() + 1, merge_dirs.end()), eopts);
      }
      if (!merge_dirs.empty()) {
        std::fprintf(stderr, "dtlab: error: unexpected arguments after the study's name\n");
        return 2;
      }
      return dtlab::experiments::run_experiment(study, eopts);
    }
  } catch (const dtlab::io::InputError& e) {
    std::fprintf(stderr, "dtlab: error: %s\n", e.what());
    return 2;
  } catch (const dtlab::engine::TriangulationError& e) {
    std::fprintf(stderr, "dtlab: error: %s\n", e.what());
    return 2;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "dtlab: error: %s\n", e.what());
    return 2;
  }
  return 2;
}

}  // namespace

int main(int argc, char** argv) {
  const int code = run_command_line(argc, argv);
  // A write to standard output that failed (a full disk, /dev/full, a closed descriptor; a pipe
  // whose reader is gone ends the process by SIGPIPE first) lost what the command printed: the
  // stats JSON of --stats -, the tables. Not a success.
  std::cout.flush();
  if (!std::cout || std::fflush(stdout) != 0 || std::ferror(stdout) != 0) {
    std::fprintf(stderr, "dtlab: error: writing to standard output failed\n");
    return 2;
  }
  return code;
}
