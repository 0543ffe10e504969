#include "flat_json.hpp"

namespace dtlab::experiments {
namespace {

void flatten_into(const nlohmann::ordered_json& value, const std::string& prefix,
                  std::vector<std::pair<std::string, std::string>>& out) {
  if (value.is_object()) {
    for (const auto& [key, child] : value.items()) {
      flatten_into(child, prefix.empty() ? key : prefix + "." + key, out);
    }
  } else if (value.is_array()) {
    return;
  } else if (value.is_null()) {
    out.emplace_back(prefix, "");
  } else if (value.is_string()) {
    out.emplace_back(prefix, value.get<std::string>());
  } else {
    out.emplace_back(prefix, value.dump());
  }
}

}  // namespace

std::vector<std::pair<std::string, std::string>> flatten(const nlohmann::ordered_json& object) {
  std::vector<std::pair<std::string, std::string>> out;
  flatten_into(object, "", out);
  return out;
}

}  // namespace dtlab::experiments
