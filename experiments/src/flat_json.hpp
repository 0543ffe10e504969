#pragma once
// A JSON object as (dotted key, text) pairs: {"a": {"b": 1}} -> ("a.b", "1"). Arrays are left out
// (the per-thread counters; their sums are top-level keys), null is the empty text.
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

namespace dtlab::experiments {

std::vector<std::pair<std::string, std::string>> flatten(const nlohmann::ordered_json& object);

}  // namespace dtlab::experiments
