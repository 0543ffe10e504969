#pragma once
// Keys and values appended to a JSON object in the order given (nlohmann's ordered_json keeps
// it): the --stats object and the validator's report list their fields so, one table each.
#include <initializer_list>
#include <utility>

#include <nlohmann/json.hpp>

namespace dtlab::engine {

using Json = nlohmann::ordered_json;
using JsonFields = std::initializer_list<std::pair<const char*, Json>>;

inline void put(Json& object, JsonFields fields) {
  for (const auto& [key, value] : fields) object[key] = value;
}

}  // namespace dtlab::engine
