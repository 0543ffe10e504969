#pragma once
// The other meshers the `peers` study judges (docs/experiments.md, "peers"): each takes dtlab's
// points and returns its tetrahedra as input point ids, or says why it has none. They run inside
// the study's forked child, so a tool that aborts or loops ends that child, not the study.
#include <stdexcept>
#include <string>
#include <vector>

#include "dtlab/engine/tetrahedron.hpp"
#include "dtlab/predicates/point.hpp"

namespace dtlab::experiments {

// The tool reported that it has no tetrahedralization for the input (an error message, an error
// exit, a lower-dimensional result): the row's status is "error", its outcome "refused".
class PeerRefused : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// The tool ended abnormally (a signal, or a failed internal assertion that would end the program
// that called it): the row's status is "crashed".
class PeerCrashed : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// The tool returned something that is no list of tetrahedra of these points (an unreadable file,
// an id out of range): its outcome is "invalid", with the reason in the row's error.
class PeerInvalidOutput : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct PeerMesh {
  std::vector<engine::Tetrahedron> tetrahedra;
  bool oriented = true;  // false: the tool does not orient its tetrahedra (Qhull)
};

struct PeerTool {
  const char* name;         // the study's variant: "cgal-epick", "qhull-Qt", ...
  const char* description;  // what runs, for --help and the docs
};

// Every peer, in the study's column order.
const std::vector<PeerTool>& peer_tools();
bool is_peer_tool(const std::string& name);

// Runs `tool` on `points`. `tetgen_program` is the TetGen executable (a name on PATH or a path);
// `scratch_dir`, an empty folder for the tool's files, which the caller removes.
// Throws PeerRefused, PeerCrashed or PeerInvalidOutput as above; std::invalid_argument for an
// unknown tool.
PeerMesh run_peer(const std::string& tool, const std::vector<predicates::Point3>& points,
                  const std::string& tetgen_program, const std::string& scratch_dir);

// The implementations, one file each.
PeerMesh run_cgal_peer(const std::vector<predicates::Point3>& points, bool exact_predicates);
PeerMesh run_qhull_peer(const std::vector<predicates::Point3>& points, const char* options);
PeerMesh run_tetgen_peer(const std::vector<predicates::Point3>& points, const std::string& program,
                         const std::string& scratch_dir);
bool qhull_available();

// The tool's version as its library or package says ("CGAL 5.5.1", "Qhull 2020.2 ...", "tetgen
// 1.5.0-5 (Debian package)").
std::string peer_version(const std::string& tool, const std::string& tetgen_program);
std::string cgal_version();
std::string qhull_version();

// The path of `program` (a path, or a name found on PATH); empty when it is no executable file.
std::string find_program(const std::string& program);
// True when `program` names an executable file (a path, or a name found on PATH).
bool program_found(const std::string& program);

}  // namespace dtlab::experiments
