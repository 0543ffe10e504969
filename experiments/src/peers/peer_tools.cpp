#include "peer_tools.hpp"

#include "../machine_record.hpp"

#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>

namespace dtlab::experiments {

const std::vector<PeerTool>& peer_tools() {
  static const std::vector<PeerTool> tools = {
      {"cgal-epick",
       "CGAL Delaunay_triangulation_3, Exact_predicates_inexact_constructions_kernel"},
      {"cgal-doubles", "CGAL Delaunay_triangulation_3, Simple_cartesian<double> (plain doubles)"},
      {"qhull-Qt", "Qhull (libqhull_r), options d Qbb Qt (triangulated output)"},
      {"qhull-QJ", "Qhull (libqhull_r), options d Qbb QJ (joggled input)"},
      {"tetgen", "the tetgen program, tetgen -Q FILE.node, in a child process"},
  };
  return tools;
}

bool is_peer_tool(const std::string& name) {
  const auto& tools = peer_tools();
  return std::any_of(tools.begin(), tools.end(), [&](const PeerTool& t) { return name == t.name; });
}

PeerMesh run_peer(const std::string& tool, const std::vector<predicates::Point3>& points,
                  const std::string& tetgen_program, const std::string& scratch_dir) {
  if (tool == "cgal-epick") return run_cgal_peer(points, true);
  if (tool == "cgal-doubles") return run_cgal_peer(points, false);
  if (tool == "qhull-Qt") return run_qhull_peer(points, "d Qbb Qt");
  if (tool == "qhull-QJ") return run_qhull_peer(points, "d Qbb QJ");
  if (tool == "tetgen") return run_tetgen_peer(points, tetgen_program, scratch_dir);
  throw std::invalid_argument("unknown peer tool " + tool);
}

std::string find_program(const std::string& program) {
  if (program.empty()) return "";
  if (program.find('/') != std::string::npos) {
    return access(program.c_str(), X_OK) == 0 ? program : "";
  }
  const char* path = std::getenv("PATH");
  const std::string dirs = path != nullptr ? path : "/usr/bin:/bin";
  std::size_t start = 0;
  while (start <= dirs.size()) {
    const std::size_t end = std::min(dirs.find(':', start), dirs.size());
    const std::string dir = dirs.substr(start, end - start);
    if (!dir.empty() && access((dir + "/" + program).c_str(), X_OK) == 0) {
      return dir + "/" + program;
    }
    start = end + 1;
  }
  return "";
}

bool program_found(const std::string& program) {
  return !find_program(program).empty();
}

namespace {

// TetGen prints no version of its own: the Debian package that installed the program says it.
std::string tetgen_version(const std::string& program) {
  std::error_code error;
  const std::string found = find_program(program);
  const std::filesystem::path real = std::filesystem::canonical(found, error);
  if (found.empty() || error) return "";
  if (real.string().find('\'') != std::string::npos) return "program " + real.string();
  const std::string owner = command_output("dpkg-query -S '" + real.string() + "' 2>/dev/null");
  const std::string package = owner.substr(0, owner.find(':'));
  if (owner.empty() || package.empty()) return "program " + real.string() + " (no package)";
  const std::string version =
      command_output("dpkg-query -W -f='${Version}\\n' '" + package + "' 2>/dev/null");
  return package + " " + version + " (Debian package)";
}

}  // namespace

std::string peer_version(const std::string& tool, const std::string& tetgen_program) {
  if (tool.rfind("cgal", 0) == 0) return cgal_version();
  if (tool.rfind("qhull", 0) == 0) return qhull_version();
  if (tool == "tetgen") return tetgen_version(tetgen_program);
  return "";
}

}  // namespace dtlab::experiments
