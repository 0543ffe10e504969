#pragma once
// Mesh output: TetGen .node + .ele, VTK XML .vtu (ParaView), and the .ele reader that
// `dtlab validate` uses. Writers go through a temporary file that is renamed into place only
// when complete, so an error never leaves a half-written output behind.
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "dtlab/predicates/point.hpp"

namespace dtlab::io {

using predicates::Point3;
// Four point ids: the same type as engine::Tetrahedron (the engine's output), named here so
// that io does not depend on the engine.
using Tetrahedron = std::array<std::uint32_t, 4>;

// A named per-tetrahedron array for the .vtu (e.g. "non_delaunay", "suspicious").
struct CellArray {
  std::string name;
  std::vector<std::int32_t> values;
};

// Writes `points` (input order, duplicates included) as TetGen .node, index base 0.
void write_node(const std::string& path, const std::vector<Point3>& points);
// Writes the tetrahedra as TetGen .ele, index base 0, vertices referring to the .node.
void write_ele(const std::string& path, const std::vector<Tetrahedron>& tets);
void write_xyz(const std::string& path, const std::vector<Point3>& points);
// How a .vtu's arrays are stored: as text; inline binary (base64 of a 64-bit byte count and the
// little-endian bytes); or the same with each array zlib-compressed in 32 KiB blocks (VTK's
// vtkZLibDataCompressor layout). All three are inline, which meshio and VTK's reader both read.
enum class VtuEncoding { Ascii, Binary, Zlib };
void write_vtu(const std::string& path, const std::vector<Point3>& points,
               const std::vector<Tetrahedron>& tets, const std::vector<CellArray>& cell_data,
               VtuEncoding encoding = VtuEncoding::Zlib);
// TetGen's neighbour file: line i lists the tetrahedra across the faces opposite the four
// vertices of tetrahedron i, -1 on the hull; index base 0 like the .ele.
void write_neigh(const std::string& path,
                 const std::vector<std::array<std::int32_t, 4>>& neighbors);
// TetGen's face file with the boundary faces (marker 1), and the two tetrahedra on each face as
// TetGen's -nn adds them: the one inside, and -1 for the outside.
void write_face(const std::string& path, const std::vector<std::array<std::uint32_t, 3>>& faces,
                const std::vector<std::uint32_t>& adjacent_tetrahedra);

// Reads a TetGen .ele (index base 0 or 1, taken from the first tetrahedron's index and the
// referenced .node's base); returns 0-based vertex ids. `point_count` bounds the ids.
std::vector<Tetrahedron> read_ele(const std::string& path, std::size_t point_count,
                                  int node_index_base);

// Index base of a .node file (0 or 1), or 0 when the file is not a .node.
int node_index_base(const std::string& path);

// Shortest text that parses back to exactly `v`.
std::string format_double(double v);
// One line of a .xyz file as write_xyz writes it: "x y z\n", each by format_double.
std::string format_xyz_line(const Point3& p);

}  // namespace dtlab::io
