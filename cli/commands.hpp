#pragma once
// The dtlab subcommands. Each returns the process exit code: 0 success, 1 a check failed
// (validation), 2 an error (bad input, unreadable file).
#include <cstdint>
#include <string>

#include "dtlab/engine/triangulate.hpp"
#include "dtlab/engine/validator.hpp"

namespace dtlab::cli {

struct TriangulateArgs {
  std::string input;
  std::string output;
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
int run_validate(const std::string& points, const std::string& mesh, engine::ValidateWith kernel,
                 int threads);
int run_repair(const std::string& points, const std::string& mesh, const std::string& output,
               const std::string& stats, bool validate, int threads);
// The method registry (dtlab/engine/methods.hpp) as a Markdown table: docs/design.md holds it.
int run_methods();
int run_predicates_audit(const std::string& input, std::uint64_t seed, engine::KernelKind kernel);

}  // namespace dtlab::cli
