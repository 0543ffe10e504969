// `dtlab repair`: the Delaunay tetrahedralization of a point set from any list of tetrahedra on
// it, by star splaying with exact predicates (docs/design.md, "dtlab repair, locally"). A list
// that is already a tetrahedralization of the hull is repaired locally, as the engine's mesh is
// after a run (splay_repair.cpp); any other list has a star built at every point.
#include <algorithm>
#include <array>
#include <atomic>
#include <chrono>
#include <cmath>
#include <numeric>
#include <optional>
#include <stdexcept>
#include <thread>

#include "dtlab/engine/point_set_info.hpp"
#include "dtlab/engine/repair.hpp"
#include "dtlab/engine/validator.hpp"
#include "insertion/sync.hpp"
#include "mesh/topology_commit.hpp"
#include "repair/splay_common.hpp"
#include "repair/splay_repair.hpp"
#include "repair/star_pieces.hpp"
#include "repair/star_splaying.hpp"
#include "repair/walked_mesh_stars.hpp"
#include "support/parallel_ranges.hpp"

namespace dtlab::engine {
namespace {

using Clock = std::chrono::steady_clock;

// A tetrahedron list as MeshStars (ids already checked and mapped to representatives).
class ListMeshStars : public MeshStars {
 public:
  ListMeshStars(std::size_t n, const std::vector<Tetrahedron>& tets) : first_(n + 1, 0) {
    for (const Tetrahedron& t : tets) {
      for (const VertexId v : t) ++first_[v + 1];
    }
    std::partial_sum(first_.begin(), first_.end(), first_.begin());
    of_.resize(first_.back());
    std::vector<std::uint32_t> fill(first_.begin(), first_.end() - 1);
    for (std::size_t i = 0; i < tets.size(); ++i) {
      for (const VertexId v : tets[i]) of_[fill[v]++] = static_cast<std::uint32_t>(i);
    }
    tets_ = &tets;
  }
  void tetrahedra_of(VertexId x, std::vector<Quad>& out) const override {
    out.clear();
    for (std::uint32_t i = first_[x]; i < first_[x + 1]; ++i) out.push_back((*tets_)[of_[i]]);
  }

 private:
  std::vector<std::uint32_t> first_;
  std::vector<std::uint32_t> of_;
  const std::vector<Tetrahedron>* tets_ = nullptr;
};

}  // namespace

std::vector<Tetrahedron> splay_tetrahedra(const std::vector<Point3>& points,
                                          const std::vector<Tetrahedron>& tets, SplayStats& stats,
                                          int threads) {
  const auto t0 = Clock::now();
  stats.done = true;
  // Duplicates: each set is named by its lowest index.
  const std::vector<VertexId> representative =
      canonical_points(points, [](VertexId /*v*/) { return false; });
  std::vector<VertexId> vertices;
  for (VertexId v = 0; v < points.size(); ++v) {
    if (representative[v] == v) vertices.push_back(v);
  }
  std::vector<Tetrahedron> mapped;
  mapped.reserve(tets.size());
  for (Tetrahedron t : tets) {
    for (auto& v : t) v = representative[v];
    mapped.push_back(t);
  }
  const ListMeshStars stars_of_mesh(points.size(), mapped);
  const NearGrid grid(points, [&] { return vertices; });
  StarSplayer splayer(points, stars_of_mesh, representative, pool_of(points, vertices),
                      [&](VertexId x, std::vector<VertexId>& out) { grid.near(x, out); });
  std::vector<Quad> around;
  for (const VertexId v : vertices) {
    stars_of_mesh.tetrahedra_of(v, around);
    if (around.empty()) ++stats.missing_vertices;
  }
  splayer.activate_all(vertices, threads);
  stats.seeds = vertices.size();
  splayer.run();
  // Stars that agree but fall apart into pieces (a lone input tetrahedron keeps its four to
  // itself): each piece is bridged to another by its closest pair across, an edge every star
  // keeps, until one piece holds every vertex (star_pieces.hpp). Each round must leave fewer
  // pieces; one that does not is an error, not a loop without end.
  std::size_t bridged_before = vertices.size();
  for (;;) {
    const auto bridges =
        closest_pairs_across(points, vertices, pieces_of_stars(points.size(), vertices, splayer));
    if (bridges.empty()) break;
    if (bridges.size() >= bridged_before) {
      throw std::logic_error("star splaying: bridging did not join the pieces of agreeing stars");
    }
    bridged_before = bridges.size();
    stats.bridges += bridges.size();
    for (const auto& [x, y] : bridges) splayer.introduce(x, y);
    splayer.run();
  }
  stats.stars = splayer.counts().stars;
  stats.offers = splayer.counts().offers;
  stats.changes = splayer.counts().changes;
  std::vector<Tetrahedron> out;
  for (const VertexId v : vertices) {
    for (const Quad& q : splayer.star(v).tetrahedra()) {
      if (std::find(q.begin(), q.end(), kInfiniteVertex) != q.end()) continue;
      if (*std::min_element(q.begin(), q.end()) == v) out.push_back(q);
    }
  }
  stats.tetrahedra_created = out.size();
  stats.seconds = std::chrono::duration<double>(Clock::now() - t0).count();
  return out;
}

namespace {

// A tetrahedron list as a SharedMesh closed by the vertex at infinity, as the engine builds one:
// a slot per tetrahedron, neighbours matched by face keys, and an infinite tetrahedron on every
// boundary face (its face listed with the finite tetrahedron's vertex on the negative side, then
// the vertex at infinity), those matched with each other across the boundary edges. False where
// a face or a boundary edge is not on exactly two, or where the boundary is not one sphere (one
// component, V - E + F = 2: a ball beside a solid torus passes the validator's Euler
// characteristic, 1 + 0, but no walk or star would ever join the two); the store is then unusable.
bool close_into_mesh(const std::vector<Tetrahedron>& tets, SharedMesh& mesh) {
  mesh.tets.keep_children(false);
  mesh.tets.keep_lock_words(false);
  // Through the store's one write path, in slots numbered in order (the infinite tetrahedra's
  // follow the finite ones'), alive as they are written: nobody else reads this mesh yet.
  NoSync no_sync;
  StoreSlots slots(mesh.tets);
  TopologyCommit<NoSync, StoreSlots> commit(mesh, no_sync, slots, /*recycle=*/false);
  auto add = [&](const Quad& q) {
    const TetId t = commit.allocate();
    commit.record(t).vertex = q;
    commit.created(t);
    commit.born(t);
    return t;
  };
  std::vector<FaceEntry> faces;
  faces.reserve(4 * tets.size());
  for (const Tetrahedron& q : tets) {
    const TetId t = add(q);
    for (int f = 0; f < 4; ++f) faces.push_back({face_key(q, f), face_ref(t, f), false});
  }
  std::sort(faces.begin(), faces.end(), by_face_key);
  // Pairs are linked; a face met once is on the boundary and gets its infinite tetrahedron.
  std::vector<FaceEntry> hull_edges;
  auto link = [&](FaceRef a, FaceRef b) { commit.link(a, b); };
  for (std::size_t i = 0; i < faces.size();) {
    std::size_t j = i;
    while (j < faces.size() && faces[j].key == faces[i].key) ++j;
    if (j - i > 2) return false;
    if (j - i == 2) {
      link(faces[i].ref, faces[i + 1].ref);
    } else {
      const Tet& finite = mesh.tets[ref_tet(faces[i].ref)];
      const auto& fv = kFaceVertex[static_cast<std::size_t>(ref_face(faces[i].ref))];
      const Quad q{finite.vertex[static_cast<std::size_t>(fv[0])],
                   finite.vertex[static_cast<std::size_t>(fv[1])],
                   finite.vertex[static_cast<std::size_t>(fv[2])], kInfiniteVertex};
      const TetId u = add(q);
      link(faces[i].ref, face_ref(u, 3));
      for (int f = 0; f < 3; ++f) hull_edges.push_back({face_key(q, f), face_ref(u, f), false});
    }
    i = j;
  }
  std::sort(hull_edges.begin(), hull_edges.end(), by_face_key);
  const std::size_t boundary_faces = hull_edges.size() / 3;
  if (boundary_faces == 0) return false;
  // The boundary's pieces: its faces (the infinite tetrahedra, slots after the finite ones) joined
  // across the edges they share.
  const auto first_infinite = static_cast<TetId>(tets.size());
  std::vector<TetId> piece(boundary_faces);
  std::iota(piece.begin(), piece.end(), TetId{0});
  auto find = [&](TetId x) {
    while (piece[x] != x) x = piece[x] = piece[piece[x]];
    return x;
  };
  for (std::size_t i = 0; i < hull_edges.size(); i += 2) {
    if (i + 1 >= hull_edges.size() || hull_edges[i].key != hull_edges[i + 1].key ||
        (i + 2 < hull_edges.size() && hull_edges[i + 2].key == hull_edges[i].key)) {
      return false;
    }
    link(hull_edges[i].ref, hull_edges[i + 1].ref);
    const TetId a = find(ref_tet(hull_edges[i].ref) - first_infinite);
    const TetId b = find(ref_tet(hull_edges[i + 1].ref) - first_infinite);
    piece[std::max(a, b)] = std::min(a, b);
  }
  for (TetId f = 0; f < boundary_faces; ++f) {
    if (find(f) != 0) return false;
  }
  std::vector<VertexId> on_boundary;
  for (TetId f = 0; f < boundary_faces; ++f) {
    const Tet& u = mesh.tets[first_infinite + f];
    on_boundary.insert(on_boundary.end(), u.vertex.begin(), u.vertex.begin() + 3);
  }
  std::sort(on_boundary.begin(), on_boundary.end());
  const auto boundary_vertices = static_cast<std::size_t>(
      std::unique(on_boundary.begin(), on_boundary.end()) - on_boundary.begin());
  const std::size_t boundary_edges = hull_edges.size() / 2;
  return boundary_vertices + boundary_faces == boundary_edges + 2;
}

// Whether the tetrahedra at every vertex are connected through the faces that contain it: the
// walks of WalkedMeshStars then find them all. The validator's mesh_consistent() does not say so
// for any list: two fans that meet at one vertex only, their boundaries closed, pass it.
bool every_star_connected(const SharedMesh& mesh, std::size_t point_count,
                          std::vector<TetId>& some_tetrahedron, int threads) {
  std::vector<std::uint32_t> incident(point_count, 0);
  some_tetrahedron.assign(point_count, kNoTet);
  for (TetId t = 0; t < mesh.tets.size(); ++t) {
    for (const VertexId v : mesh.tets[t].vertex) {
      if (v == kInfiniteVertex) continue;
      ++incident[v];
      if (some_tetrahedron[v] == kNoTet) some_tetrahedron[v] = t;
    }
  }
  const WalkedMeshStars walks(mesh, some_tetrahedron);
  std::atomic<bool> connected{true};
  in_parallel_ranges(point_count, std::max(threads, 1),
                     [&](std::size_t begin, std::size_t end, std::size_t /*part*/) {
                       std::vector<TetId> around;
                       for (std::size_t v = begin; v < end && connected.load(); ++v) {
                         if (incident[v] == 0) continue;
                         walks.tetrahedron_ids_of(static_cast<VertexId>(v), around);
                         if (around.size() != incident[v]) connected.store(false);
                       }
                     });
  return connected.load();
}

// dtlab repair of a list that is already a tetrahedralization of the hull of distinct points,
// Delaunay or not: closed by the vertex at infinity into a mesh whose boundary is one sphere and
// whose vertex stars are connected (the cheap checks first), then judged consistent() by the
// exact validator (oriented, manifold, every point a vertex, Euler characteristic 1, a convex
// boundary and the hull's exact volume: one cover of the hull, proven, not sampled). Such a list
// is the mesh burglary's post-check hands over, and is splayed the same way, from the faces the
// validation rejected only (docs/design.md, "dtlab repair, locally"). Empty for any other list
// (the caller splays every vertex); `seconds_checking` is then what the checks took.
std::optional<std::vector<Tetrahedron>> repair_locally(const std::vector<Point3>& points,
                                                       const std::vector<Tetrahedron>& tets,
                                                       SplayStats& stats, int threads) {
  const auto t0 = Clock::now();
  auto give_up = [&]() -> std::optional<std::vector<Tetrahedron>> {
    stats.seconds_checking = std::chrono::duration<double>(Clock::now() - t0).count();
    return std::nullopt;
  };
  const std::vector<VertexId> canonical =
      canonical_points(points, [](VertexId /*v*/) { return false; });
  for (VertexId v = 0; v < points.size(); ++v) {
    if (canonical[v] != v) return give_up();  // equal points: named as the global path names
  }
  SharedMesh mesh(points);
  std::vector<TetId> some_tetrahedron;
  if (!close_into_mesh(tets, mesh) ||
      !every_star_connected(mesh, points.size(), some_tetrahedron, threads)) {
    return give_up();
  }
  const ValidationReport report = validate(points, tets, ValidateWith::Adaptive, threads, true);
  if (!report.consistent()) return give_up();
  stats.seconds_checking = std::chrono::duration<double>(Clock::now() - t0).count();
  const ValidatedFindings found = validated_findings(report, points.size(), {});
  splay_shared_mesh(mesh, {}, true, threads, stats, &found);
  stats.local = true;
  std::vector<Tetrahedron> out =
      mesh.finite_tetrahedra(static_cast<VertexId>(points.size()), {}, threads);
  stats.seconds = std::chrono::duration<double>(Clock::now() - t0).count();
  return out;
}

// The local repair where the list allows it, else every vertex splayed (`seconds` then includes
// the checks that sent it there).
std::vector<Tetrahedron> repair_list(const std::vector<Point3>& points,
                                     const std::vector<Tetrahedron>& tets, SplayStats& stats,
                                     int threads) {
  if (auto local = repair_locally(points, tets, stats, threads)) return *std::move(local);
  const double checking = stats.seconds_checking;
  std::vector<Tetrahedron> out = splay_tetrahedra(points, tets, stats, threads);
  stats.seconds += checking;
  return out;
}

}  // namespace

std::vector<Tetrahedron> repair(const std::vector<Point3>& points,
                                const std::vector<Tetrahedron>& tets, SplayStats& stats,
                                int threads) {
  if (threads == kAllThreads) {
    threads = static_cast<int>(std::max(1U, std::thread::hardware_concurrency()));
  }
  const CoordinateMagnitudes magnitudes = coordinate_magnitudes(points);
  if (!magnitudes.finite) throw TriangulationError("input has a NaN or infinite coordinate");
  for (const Tetrahedron& t : tets) {
    for (const VertexId v : t) {
      if (v >= points.size()) throw TriangulationError("a tetrahedron names a missing vertex");
    }
  }
  if (analyze(points).dimension < 3) {
    throw TriangulationError("no tetrahedralization exists: the points span less than 3D");
  }
  // The engine's lossless power-of-two scaling keeps the exact stages off their GMP fallback.
  const RangeScaling scaling =
      adaptive_range_scaling(magnitudes.max_abs, magnitudes.min_abs_nonzero);
  if (!scaling.lossless) return repair_list(points, tets, stats, threads);
  std::vector<Point3> scaled = points;
  for (Point3& p : scaled) {
    p = {std::ldexp(p.x, scaling.exponent), std::ldexp(p.y, scaling.exponent),
         std::ldexp(p.z, scaling.exponent)};
  }
  return repair_list(scaled, tets, stats, threads);
}

}  // namespace dtlab::engine
