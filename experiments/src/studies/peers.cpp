// peers: other meshers (CGAL with exact and with plain-double predicates, Qhull with and without
// its joggle, TetGen) beside dtlab's kernels on every generator family, each output judged by the
// exact validator; every run is valid, invalid, refused, crashed or hung.
#include <algorithm>
#include <map>

#include "../peers/peer_tools.hpp"
#include "studies.hpp"

namespace dtlab::experiments {
namespace {

struct DtlabTool {
  const char* name;
  engine::KernelKind kernel;
};

constexpr DtlabTool kDtlabTools[] = {{"dtlab-fast", engine::KernelKind::Fast},
                                     {"dtlab-adaptive", engine::KernelKind::Adaptive},
                                     {"dtlab-filtered", engine::KernelKind::Filtered}};

constexpr const char* kOutcomes[] = {"valid", "invalid", "refused", "crashed", "hung"};

std::vector<RunSpec> plan(const StudyParams& p) {
  // Asked once, here (the TetGen version asks the package manager), not in every timed run.
  std::map<std::string, std::string> versions;
  for (const std::string& tool : p.tools) versions[tool] = peer_version(tool, p.tetgen_program);
  std::vector<RunSpec> runs;
  for_each_base_run(p, [&](RunSpec base) {
    for (const std::string& tool : p.tools) {
      RunSpec spec = base;
      spec.variant = tool;
      const auto dtlab = std::find_if(std::begin(kDtlabTools), std::end(kDtlabTools),
                                      [&](const DtlabTool& d) { return tool == d.name; });
      if (dtlab != std::end(kDtlabTools)) {
        // What `dtlab triangulate` runs by default: the walk and cavities, sequential.
        spec.options.kernel = dtlab->kernel;
        spec.options.location = engine::Location::Walk;
        spec.options.insertion = engine::Insertion::Cavity;
        spec.validate = true;
      } else {
        spec.engine = Engine::Peer;
        spec.tetgen_program = p.tetgen_program;
        spec.tool_version = versions[tool];
      }
      runs.push_back(spec);
    }
  });
  return runs;
}

// Coplanar and collinear points have no tetrahedralization: refusing them is the right answer.
bool has_tetrahedralization(const std::string& input) {
  return input != "coplanar" && input != "collinear";
}

bool right_answer(const std::string& input, const std::string& outcome) {
  return has_tetrahedralization(input) ? outcome == "valid" : outcome == "refused";
}

// "3 valid", "1 invalid, 2 crashed"; the wrong ones in bold.
std::string outcome_cell(const CsvTable& t, const std::vector<const Row*>& rows,
                         const std::string& input) {
  std::string cell;
  for (const char* outcome : kOutcomes) {
    std::size_t n = 0;
    for (const Row* r : rows) n += t.get(*r, "outcome") == outcome ? 1 : 0;
    if (n == 0) continue;
    const std::string part = std::to_string(n) + " " + outcome;
    cell += (cell.empty() ? "" : ", ") + (right_answer(input, outcome) ? part : "**" + part + "**");
  }
  return cell.empty() ? "-" : cell;
}

// The invalid runs' violations, summed by kind over the rows: "12 non-Delaunay, 3 flat/inverted".
std::string violations(const CsvTable& t, const std::vector<const Row*>& rows) {
  const std::pair<const char*, const char*> kinds[] = {
      {"validation.non_delaunay_faces", "non-Delaunay faces"},
      {"validation.non_positive_orientation", "flat or inverted"},
      {"validation.non_manifold_faces", "non-manifold faces"},
      {"validation.inconsistent_faces", "inconsistent faces"},
      {"validation.missing_points", "missing points"},
      {"validation.invalid_tetrahedra", "bad ids"},
      {"validation.open_boundary_edges", "open boundary edges"},
      {"validation.reflex_boundary_edges", "reflex boundary edges"},
      {"validation.volume_mismatch", "volume mismatches"},
      {"validation.probes_covered_twice", "probes covered twice"}};
  std::string out;
  for (const auto& [column, name] : kinds) {
    double sum = 0;
    for (const Row* r : rows) {
      const Aggregate a = aggregate_of(t, {r}, column);
      if (a.count > 0) sum += a.max;
    }
    if (sum > 0) out += (out.empty() ? "" : ", ") + thousands(sum) + " " + name;
  }
  return out;
}

// The tools in the rows, in the study's column order (--tools may pick some; a resumed CSV's rows
// come in the order they ran).
std::vector<std::string> tools_in(const CsvTable& t) {
  std::vector<std::string> tools;
  for (const std::string& known : peers_study_tools()) {
    const bool present = std::any_of(t.rows.begin(), t.rows.end(),
                                     [&](const Row& r) { return t.get(r, "variant") == known; });
    if (present) tools.push_back(known);
  }
  return tools;
}

std::string summarize(const CsvTable& t) {
  const std::vector<std::string> tools = tools_in(t);
  const auto every = [](const Row&) { return true; };
  std::vector<std::string> header = {"input", "points", "has a tetrahedralization"};
  for (const std::string& tool : tools) header.push_back(tool);
  MarkdownTable outcomes(header);
  std::map<std::string, std::map<std::string, std::size_t>> per_tool;  // tool -> class -> runs
  std::string invalid_list;
  for (const RowGroup& g : group_rows(t, {"input", "size_asked"}, every)) {
    const std::string& input = g.key[0];
    std::vector<std::string> row = {input, thousands(aggregate_of(t, g.rows, "points").median),
                                    has_tetrahedralization(input) ? "yes" : "no"};
    for (const std::string& tool : tools) {
      std::vector<const Row*> mine;
      for (const Row* r : g.rows) {
        if (t.get(*r, "variant") != tool) continue;
        mine.push_back(r);
        const std::string& outcome = t.get(*r, "outcome");
        auto& counts = per_tool[tool];
        ++counts["runs"];
        ++counts[right_answer(input, outcome) ? "right" : outcome];
        if (outcome == "invalid") {
          const std::string found = violations(t, {r});
          invalid_list += "- " + input + ":" + t.get(*r, "size_asked") + " seed " +
                          t.get(*r, "seed") + ", " + tool + ": " +
                          (found.empty() ? t.get(*r, "error") : found) + "\n";
        }
      }
      row.push_back(outcome_cell(t, mine, input));
    }
    outcomes.add(row);
  }
  MarkdownTable totals({"tool", "runs", "right answers", "invalid meshes", "refused a valid input",
                        "crashed", "hung", "version"});
  for (const std::string& tool : tools) {
    auto& c = per_tool[tool];
    std::string version;
    for (const Row& r : t.rows) {
      if (t.get(r, "variant") == tool && !t.get(r, "peer.version").empty()) {
        version = t.get(r, "peer.version");
      }
    }
    totals.add({tool, std::to_string(c["runs"]), std::to_string(c["right"]),
                std::to_string(c["invalid"]), std::to_string(c["refused"]),
                std::to_string(c["crashed"]), std::to_string(c["hung"]),
                version.empty() ? (tool.rfind("dtlab", 0) == 0 ? "this commit" : "-") : version});
  }
  return "### Outcomes per input and tool\n\n" + outcomes.str() +
         "\nEach cell counts the runs (seeds) by outcome: valid (the exact validator accepts the "
         "mesh: consistent, convex, every distinct point a vertex, Delaunay), invalid (it does "
         "not), refused (the tool said it has no answer: an error message or exit code), crashed "
         "(a signal, or a failed internal assertion that would end the calling program), hung (no "
         "result within the timeout). Wrong answers are in bold: anything but valid where a "
         "tetrahedralization exists, anything but refused where none does (coplanar and collinear "
         "points). Qhull does not orient its tetrahedra: negative ones are turned before the "
         "validator sees them (column peer.turned_tetrahedra); flat ones stay errors.\n\n"
         "### Per tool\n\n" +
         totals.str() +
         (invalid_list.empty()
              ? std::string()
              : "\n### Invalid meshes: what the validator found\n\n" + invalid_list);
}

}  // namespace

Study peers_study() {
  return {"peers",
          "other meshers (CGAL exact and plain doubles, Qhull Qt and QJ, TetGen) and dtlab's "
          "kernels on every generator family, judged by the exact validator: valid, invalid, "
          "refused, crashed or hung",
          {2,
           1,
           {},
           {},
           {1000, 10000},
           {300},
           {"uniform", "normal", "cluster", "grid", "sphere", "planes", "cospherical", "duplicates",
            "near-duplicates", "coplanar", "collinear", "lattice", "tiny", "huge"},
           // No input where a tool hangs: --quick stays short (the hang is tested at --timeout 3).
           {"uniform", "grid", "coplanar", "tiny"},
           {engine::Location::Walk},
           60.0,
           20.0},
          plan,
          summarize,
          true};
}

std::vector<std::string> peers_study_tools() {
  std::vector<std::string> tools;
  for (const PeerTool& t : peer_tools()) tools.emplace_back(t.name);
  for (const DtlabTool& d : kDtlabTools) tools.emplace_back(d.name);
  return tools;
}

}  // namespace dtlab::experiments
