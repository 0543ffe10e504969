#include <algorithm>
#include <filesystem>

#include "dtlab/generators/generators.hpp"
#include "study.hpp"

namespace dtlab::experiments {

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
