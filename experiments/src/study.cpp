// The study types' small helpers: names, inputs.
#include <algorithm>
#include <filesystem>

#include "dtlab/generators/generators.hpp"
#include "study.hpp"

namespace dtlab::experiments {

const char* to_string(Engine e) {
  switch (e) {
    case Engine::Dtlab:
      return "dtlab";
    case Engine::CgalSequential:
      return "cgal";
    case Engine::CgalParallel:
      return "cgal-parallel";
    case Engine::Peer:
      return "peer";
  }
  return "?";
}

RunSpec dtlab_run(const std::string& input, const std::string& source, std::int64_t size,
                  std::uint64_t seed) {
  RunSpec spec;
  spec.input = input;
  spec.source = source;
  spec.size = size;
  spec.options.seed = seed;
  return spec;
}

bool is_generator_family(const std::string& name) {
  const auto& families = generators::families();
  return std::find(families.begin(), families.end(), name) != families.end();
}

std::string model_path(const std::string& data_dir, const std::string& name) {
  namespace fs = std::filesystem;
  if (name.find('/') != std::string::npos) return fs::is_regular_file(name) ? name : "";
  for (const char* extension : {"", ".xyz", ".ply", ".ply.xz", ".off", ".node"}) {
    const fs::path candidate = fs::path(data_dir) / (name + extension);
    if (fs::is_regular_file(candidate)) return candidate.string();
  }
  return "";
}

}  // namespace dtlab::experiments
