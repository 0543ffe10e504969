#pragma once
// The engine's option names (the CLI's) back to their values, with the choices in the error.
#include <stdexcept>
#include <string>

namespace dtlab::python {

// The value of E among [0, count) whose to_string() is `name`; std::invalid_argument otherwise.
template <class E>
E named(const std::string& name, int count, const char* what) {
  std::string choices;
  for (int i = 0; i < count; ++i) {
    const auto value = static_cast<E>(i);
    if (name == to_string(value)) return value;
    if (i > 0) choices += ", ";
    choices += to_string(value);
  }
  std::string message = what;
  message.append(" must be one of ").append(choices).append(" (got '").append(name).append("')");
  throw std::invalid_argument(message);
}

}  // namespace dtlab::python
