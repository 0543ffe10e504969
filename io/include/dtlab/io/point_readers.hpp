#pragma once
// Point set input: .xyz, .ply (ASCII, binary little/big endian), .off, TetGen .node, each also
// xz-compressed (.xyz.xz, .ply.xz, ...). Every reader throws InputError on bad input, naming the
// file and the line or element; coordinates must be finite.
#include <string>
#include <string_view>
#include <vector>

#include "dtlab/io/input_error.hpp"
#include "dtlab/predicates/point.hpp"

namespace dtlab::io {

using predicates::Point3;

// Reads a point file; the format follows the extension (after stripping a trailing .xz).
std::vector<Point3> read_points(const std::string& path);

// The parsers, on the file's contents (`name` only labels error messages).
std::vector<Point3> parse_xyz(std::string_view text, const std::string& name);
std::vector<Point3> parse_ply(std::string_view bytes, const std::string& name);
std::vector<Point3> parse_off(std::string_view text, const std::string& name);
std::vector<Point3> parse_node(std::string_view text, const std::string& name);

// Whole file contents, decompressing .xz transparently.
std::string read_file_bytes(const std::string& path);

}  // namespace dtlab::io
