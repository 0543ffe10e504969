#include "dtlab/io/mesh_writers.hpp"

#include <charconv>

#include "atomic_file.hpp"
#include "dtlab/io/point_readers.hpp"
#include "text_scanner.hpp"

namespace dtlab::io {

std::string format_double(double v) {
  char buf[32];
  const auto [ptr, ec] = std::to_chars(buf, buf + sizeof buf, v);
  (void)ec;
  return std::string(buf, ptr);
}

void write_node(const std::string& path, const std::vector<Point3>& points) {
  detail::AtomicFile file(path);
  auto& out = file.stream();
  out << "# dtlab point list, index base 0, input order (duplicates included)\n";
  out << points.size() << " 3 0 0\n";
  std::string line;
  for (std::size_t i = 0; i < points.size(); ++i) {
    line = std::to_string(i);
    line += ' ';
    line += format_double(points[i].x);
    line += ' ';
    line += format_double(points[i].y);
    line += ' ';
    line += format_double(points[i].z);
    line += '\n';
    out << line;
  }
  file.commit();
}

std::string format_xyz_line(const Point3& p) {
  std::string line = format_double(p.x);
  line += ' ';
  line += format_double(p.y);
  line += ' ';
  line += format_double(p.z);
  line += '\n';
  return line;
}

void write_xyz(const std::string& path, const std::vector<Point3>& points) {
  detail::AtomicFile file(path);
  auto& out = file.stream();
  for (const Point3& p : points) out << format_xyz_line(p);
  file.commit();
}

void write_ele(const std::string& path, const std::vector<Tetrahedron>& tets) {
  detail::AtomicFile file(path);
  auto& out = file.stream();
  out << "# dtlab tetrahedra, index base 0, positively oriented (orient3d > 0)\n";
  out << tets.size() << " 4 0\n";
  for (std::size_t i = 0; i < tets.size(); ++i) {
    const Tetrahedron& t = tets[i];
    out << i << ' ' << t[0] << ' ' << t[1] << ' ' << t[2] << ' ' << t[3] << '\n';
  }
  file.commit();
}

void write_vtu(const std::string& path, const std::vector<Point3>& points,
               const std::vector<Tetrahedron>& tets, const std::vector<CellArray>& cell_data) {
  detail::AtomicFile file(path);
  auto& out = file.stream();
  out << "<?xml version=\"1.0\"?>\n"
         "<VTKFile type=\"UnstructuredGrid\" version=\"0.1\" byte_order=\"LittleEndian\">\n"
         "<UnstructuredGrid>\n<Piece NumberOfPoints=\""
      << points.size() << "\" NumberOfCells=\"" << tets.size() << "\">\n";
  out << "<Points>\n<DataArray type=\"Float64\" NumberOfComponents=\"3\" format=\"ascii\">\n";
  for (const Point3& p : points) {
    out << format_double(p.x) << ' ' << format_double(p.y) << ' ' << format_double(p.z) << '\n';
  }
  out << "</DataArray>\n</Points>\n<Cells>\n"
         "<DataArray type=\"Int64\" Name=\"connectivity\" format=\"ascii\">\n";
  for (const Tetrahedron& t : tets)
    out << t[0] << ' ' << t[1] << ' ' << t[2] << ' ' << t[3] << '\n';
  out << "</DataArray>\n<DataArray type=\"Int64\" Name=\"offsets\" format=\"ascii\">\n";
  for (std::size_t i = 0; i < tets.size(); ++i) out << 4 * (i + 1) << '\n';
  out << "</DataArray>\n<DataArray type=\"UInt8\" Name=\"types\" format=\"ascii\">\n";
  for (std::size_t i = 0; i < tets.size(); ++i) out << "10\n";  // VTK_TETRA
  out << "</DataArray>\n</Cells>\n";
  if (!cell_data.empty()) {
    out << "<CellData>\n";
    for (const CellArray& array : cell_data) {
      out << "<DataArray type=\"Int32\" Name=\"" << array.name << "\" format=\"ascii\">\n";
      for (const std::int32_t v : array.values) out << v << '\n';
      out << "</DataArray>\n";
    }
    out << "</CellData>\n";
  }
  out << "</Piece>\n</UnstructuredGrid>\n</VTKFile>\n";
  file.commit();
}

int node_index_base(const std::string& path) {
  if (path.size() < 5 || path.compare(path.size() - 5, 5, ".node") != 0) return 0;
  const std::string bytes = read_file_bytes(path);
  detail::TextScanner scan(bytes, path);
  std::string_view line;
  if (!scan.next_content_line(line) || !scan.next_content_line(line)) return 0;
  std::string_view token;
  detail::TextScanner::next_token(line, token);
  return token == "1" ? 1 : 0;
}

std::vector<Tetrahedron> read_ele(const std::string& path, std::size_t point_count,
                                  int node_index_base) {
  const std::string bytes = read_file_bytes(path);
  detail::TextScanner scan(bytes, path);
  std::string_view line;
  if (!scan.next_content_line(line)) scan.fail("empty file, expected an .ele header");
  std::string_view token;
  detail::TextScanner::next_token(line, token);
  const std::int64_t count = scan.parse_integer(token, "tetrahedron count");
  if (count < 0) scan.fail("negative tetrahedron count");
  if (detail::TextScanner::next_token(line, token) && token != "4") {
    scan.fail("only 4-node tetrahedra are supported");
  }
  std::vector<Tetrahedron> tets;
  tets.reserve(static_cast<std::size_t>(std::min<std::int64_t>(count, 1 << 24)));
  for (std::int64_t i = 0; i < count; ++i) {
    if (!scan.next_content_line(line)) {
      scan.fail("truncated: header announces " + std::to_string(count) +
                " tetrahedra, file ends after " + std::to_string(i));
    }
    detail::TextScanner::next_token(line, token);  // the tetrahedron's own index
    Tetrahedron t{};
    for (int k = 0; k < 4; ++k) {
      if (!detail::TextScanner::next_token(line, token)) scan.fail("expected four vertex ids");
      const std::int64_t v = scan.parse_integer(token, "vertex id") - node_index_base;
      if (v < 0 || static_cast<std::size_t>(v) >= point_count) {
        scan.fail("vertex id " + std::string(token) + " is not a point of the .node (" +
                  std::to_string(point_count) + " points, base " + std::to_string(node_index_base) +
                  ")");
      }
      t[static_cast<std::size_t>(k)] = static_cast<std::uint32_t>(v);
    }
    tets.push_back(t);
  }
  return tets;
}

}  // namespace dtlab::io
