// TetGen through its program, as a user runs it: the points as a .node file in the run's scratch
// folder, `tetgen -Q FILE.node`, then FILE.1.node and FILE.1.ele read back (the output nodes
// mapped to the input ids by their coordinates). The program runs in a child process
// that dies with the run (PR_SET_PDEATHSIG), so the study's timeout ends it too.
#include <fcntl.h>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <cerrno>
#include <csignal>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>

#include "../process_status.hpp"
#include "dtlab/io/mesh_writers.hpp"
#include "dtlab/io/point_readers.hpp"
#include "peer_tools.hpp"

namespace dtlab::experiments {
namespace {

// The last non-empty line the program wrote (its error message, when it gives one).
std::string last_line(const std::string& path) {
  std::ifstream in(path);
  std::string line;
  std::string last;
  while (std::getline(in, line)) {
    if (line.find_first_not_of(" \t\r") != std::string::npos) last = line;
  }
  return last.empty() ? "(no message)" : last;
}

[[noreturn]] void exec_tetgen(const std::string& program, const std::string& node,
                              const std::string& output) {
  prctl(PR_SET_PDEATHSIG, SIGKILL);
  const int fd = open(output.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  if (fd >= 0) {
    dup2(fd, STDOUT_FILENO);
    dup2(fd, STDERR_FILENO);
    close(fd);
  }
  const char* argv[] = {program.c_str(), "-Q", node.c_str(), nullptr};
  execvp(program.c_str(), const_cast<char* const*>(argv));
  std::fprintf(stderr, "cannot run %s: %s\n", program.c_str(), std::strerror(errno));
  _exit(127);
}

// The input id of each output node: the first input point with exactly its coordinates (TetGen
// writes 17 significant digits, which read back to the same double).
std::vector<std::uint32_t> input_ids(const std::vector<predicates::Point3>& nodes,
                                     const std::vector<predicates::Point3>& points) {
  using Key = std::array<double, 3>;
  std::map<Key, std::uint32_t> first;
  for (std::size_t i = 0; i < points.size(); ++i) {
    first.emplace(Key{points[i].x, points[i].y, points[i].z}, static_cast<std::uint32_t>(i));
  }
  std::vector<std::uint32_t> ids(nodes.size());
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    const auto it = first.find(Key{nodes[i].x, nodes[i].y, nodes[i].z});
    if (it == first.end()) {
      throw std::runtime_error("its output node " + std::to_string(i) + " is no input point");
    }
    ids[i] = it->second;
  }
  return ids;
}

}  // namespace

PeerMesh run_tetgen_peer(const std::vector<predicates::Point3>& points, const std::string& program,
                         const std::string& scratch_dir) {
  namespace fs = std::filesystem;
  const std::string node = (fs::path(scratch_dir) / "points.node").string();
  const std::string output = (fs::path(scratch_dir) / "tetgen-output.txt").string();
  io::write_node(node, points);
  std::fflush(nullptr);
  const pid_t pid = fork();
  if (pid < 0) throw std::runtime_error("fork failed");
  if (pid == 0) exec_tetgen(program, node, output);
  const int status = wait_for(pid);
  if (WIFSIGNALED(status)) {
    throw PeerCrashed("tetgen ended by signal " + signal_name(WTERMSIG(status)) + ": " +
                      last_line(output));
  }
  if (WEXITSTATUS(status) != 0) {
    throw PeerRefused("tetgen exit code " + std::to_string(WEXITSTATUS(status)) + ": " +
                      last_line(output));
  }
  const std::string ele = (fs::path(scratch_dir) / "points.1.ele").string();
  if (!fs::exists(ele)) throw PeerRefused("tetgen wrote no .ele: " + last_line(output));
  PeerMesh mesh;
  try {
    // TetGen numbers its output nodes afresh (it drops duplicates): its .ele refers to them.
    const std::string out_node = (fs::path(scratch_dir) / "points.1.node").string();
    const bool renumbered = fs::exists(out_node);
    const std::vector<predicates::Point3> nodes = renumbered ? io::read_points(out_node) : points;
    mesh.tetrahedra =
        io::read_ele(ele, nodes.size(), renumbered ? io::node_index_base(out_node) : 0);
    const std::vector<std::uint32_t> input_id = input_ids(nodes, points);
    for (engine::Tetrahedron& tet : mesh.tetrahedra) {
      for (std::uint32_t& v : tet) v = input_id[v];
    }
  } catch (const std::exception& e) {
    // A file the program wrote but that is no mesh of these points: an invalid answer.
    throw PeerInvalidOutput(std::string("tetgen wrote an unreadable mesh: ") + e.what());
  }
  return mesh;
}

}  // namespace dtlab::experiments
