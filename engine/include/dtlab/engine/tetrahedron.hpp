#pragma once
// The engine's output element: a tetrahedron as four input point ids, positively oriented
// (orient3d > 0). The mesh writers and readers (dtlab/io) take the same four ids.
#include <array>
#include <cstdint>

namespace dtlab::engine {

using Tetrahedron = std::array<std::uint32_t, 4>;

}  // namespace dtlab::engine
