#pragma once
// The dtlab subcommands. Each returns the process exit code: 0 success, 1 a check failed
// (validation), 2 an error (bad input, unreadable file).
#include <cstdint>
#include <string>

#include "dtlab/engine/triangulate.hpp"
#include "dtlab/engine/validator.hpp"
#include "dtlab/io/mesh_writers.hpp"

namespace dtlab::cli {

// What the mesh files hold besides the tetrahedra, and how (every command that writes a mesh).
struct MeshOutput {
  std::string path;  // .ele (with its .node) or .vtu; empty: none
  io::VtuEncoding vtu = io::VtuEncoding::Zlib;
  bool neighbors = false;  // PATH's stem .neigh (TetGen)
  bool hull = false;       // PATH's stem .face (TetGen): the hull faces, outward
  bool canonical = false;  // tetrahedra in engine::canonical_tetrahedra's order
};

struct TriangulateArgs {
  std::string input;
  MeshOutput output;
  std::string stats;
  int threads = 1;
  bool validate = false;
  engine::ValidateWith validate_with = engine::ValidateWith::Adaptive;
  engine::TriangulateOptions options;
};

int run_generate(const std::string& family, std::int64_t n, std::uint64_t seed,
                 const std::string& output);
int run_info(const std::string& input, std::uint64_t seed);
int run_triangulate(const TriangulateArgs& args);
// threads: engine::kAllThreads for one per hardware thread.
// any_orientation: negative tetrahedra are turned first (lists from tools that do not orient).
int run_validate(const std::string& points, const std::string& mesh, engine::ValidateWith kernel,
                 int threads, bool any_orientation);
int run_repair(const std::string& points, const std::string& mesh, const MeshOutput& output,
               const std::string& stats, bool validate, int threads);
// The method registry (dtlab/engine/methods.hpp) as a Markdown table: docs/design.md holds it.
int run_methods();
int run_predicates_audit(const std::string& input, std::uint64_t seed, engine::KernelKind kernel);

}  // namespace dtlab::cli
