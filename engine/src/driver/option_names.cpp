// The options' names as the CLI, the stats and the experiments write them: one table per option,
// in the order of its enumeration (the methods' names are the registry's).
#include <array>

#include "dtlab/engine/methods.hpp"
#include "dtlab/engine/triangulate.hpp"

namespace dtlab::engine {
namespace {

template <class E, std::size_t N>
const char* name_in(const std::array<const char*, N>& names, E value) {
  const auto i = static_cast<std::size_t>(value);
  return i < N ? names[i] : "?";
}

}  // namespace

const char* to_string(KernelKind k) {
  return name_in(std::array{"fast", "adaptive", "filtered", "exact"}, k);
}
const char* to_string(Bounding b) {
  return name_in(std::array{"infinite", "aux-tet"}, b);
}
const char* to_string(Location l) {
  return name_in(std::array{"dag", "walk"}, l);
}
const char* to_string(Insertion i) {
  return name_in(std::array{"flips", "cavity"}, i);
}
const char* to_string(Method m) {
  return method_info(m).name;
}
const char* to_string(Distribution d) {
  return name_in(std::array{"static", "dynamic", "strips", "blocks", "auto"}, d);
}
const char* to_string(Repair r) {
  return name_in(std::array{"none", "flips", "rebuild", "splay", "flips-splay"}, r);
}

}  // namespace dtlab::engine
