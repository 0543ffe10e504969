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

void write_neigh(const std::string& path,
                 const std::vector<std::array<std::int32_t, 4>>& neighbors) {
  detail::AtomicFile file(path);
  auto& out = file.stream();
  out << "# dtlab neighbours (TetGen .neigh), index base 0: neighbour i is opposite vertex i of "
         "the "
         ".ele's tetrahedron, -1 on the hull\n";
  out << neighbors.size() << " 4\n";
  for (std::size_t i = 0; i < neighbors.size(); ++i) {
    const auto& n = neighbors[i];
    out << i << ' ' << n[0] << ' ' << n[1] << ' ' << n[2] << ' ' << n[3] << '\n';
  }
  file.commit();
}

void write_face(const std::string& path, const std::vector<std::array<std::uint32_t, 3>>& faces,
                const std::vector<std::uint32_t>& adjacent_tetrahedra) {
  detail::AtomicFile file(path);
  auto& out = file.stream();
  out << "# dtlab hull faces (TetGen .face), index base 0, each turned outward: (b - a) x (c - a) "
         "points out; marker 1 (boundary); then the two tetrahedra on the face as TetGen's -nn "
         "writes them: the .ele tetrahedron inside it, -1 outside\n";
  out << faces.size() << " 1\n";
  for (std::size_t i = 0; i < faces.size(); ++i) {
    const auto& f = faces[i];
    out << i << ' ' << f[0] << ' ' << f[1] << ' ' << f[2] << " 1";
    if (i < adjacent_tetrahedra.size()) out << ' ' << adjacent_tetrahedra[i] << " -1";
    out << '\n';
  }
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
