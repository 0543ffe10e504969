// Parsers: any bytes as .xyz, .ply, .off and .node: a clear InputError or finite points, never a
// crash.
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <string>
#include <string_view>

#include "dtlab/io/point_readers.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view bytes(reinterpret_cast<const char*>(data), size);
  using Parser = std::vector<dtlab::io::Point3> (*)(std::string_view, const std::string&);
  for (const Parser parse :
       {static_cast<Parser>(dtlab::io::parse_xyz), static_cast<Parser>(dtlab::io::parse_ply),
        static_cast<Parser>(dtlab::io::parse_off), static_cast<Parser>(dtlab::io::parse_node)}) {
    try {
      for (const auto& p : parse(bytes, "fuzz")) {
        if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z)) std::abort();
      }
    } catch (const dtlab::io::InputError&) {
    }
  }
  return 0;
}
