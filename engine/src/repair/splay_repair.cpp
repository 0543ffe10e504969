// Star splaying on the engine's shared mesh after a run (burglary's marks, the fast kernel's
// errors): the exact scan or the validation's findings, the flips first where asked, the stars,
// and the write-back (docs/design.md). `dtlab repair` of a list is list_repair.cpp.
#include "repair/splay_repair.hpp"

#include <algorithm>
#include <chrono>
#include <memory>
#include <numeric>
#include <stdexcept>

#include "repair/exact_scan.hpp"
#include "repair/mesh_listing.hpp"
#include "repair/splay_common.hpp"
#include "repair/splay_write_back.hpp"
#include "repair/star_splaying.hpp"
#include "repair/walked_mesh_stars.hpp"

namespace dtlab::engine {
namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point t) {
  return std::chrono::duration<double>(Clock::now() - t).count();
}

// splay_shared_mesh, stage by stage: the damage found (scanned, or handed over by a validation),
// the seeds it gives, equal points grouped, the mesh's stars, the flips first where asked, the
// splaying and the write-back.
class MeshSplay {
 public:
  MeshSplay(SharedMesh& mesh, bool exact_mesh, int threads, SplayStats& stats)
      : mesh_(mesh),
        points_(mesh.points),
        exact_mesh_(exact_mesh),
        parts_(std::max(threads, 1)),
        stats_(stats),
        t0_(Clock::now()),
        slots_(mesh.tets.size()),
        seed_(mesh.points.size(), 0) {}

  void run(const std::vector<TetId>& marks, const ValidatedFindings* validated,
           const FlipPass* flips_first) {
    if (validated != nullptr && !exact_mesh_) {
      throw std::logic_error("star splaying: validated findings on a mesh not built exactly");
    }
    stats_.done = true;
    stats_.scan_threads = static_cast<std::uint64_t>(parts_);
    find_damage(validated);
    seed_marks(marks);
    // Nothing to splay (the usual end of a clean run): no star is read.
    if (group_points()) {
      choose_stars(validated);
      std::vector<VertexId> seeds = seeded_vertices();
      if (flips_first != nullptr && walked_ != nullptr && stats_.missing_vertices == 0 &&
          !seeds.empty()) {
        seeds = flip_first(*flips_first, seeds);
      }
      stats_.seeds = seeds.size();
      if (!seeds.empty()) splay(seeds);
    }
    stats_.seconds = seconds_since(t0_);
  }

 private:
  [[nodiscard]] bool is_vertex(VertexId v) const { return listed_.lowest_tetrahedron[v] != kNoTet; }
  void seed_quad(const Quad& q) {
    for (const VertexId v : q) {
      if (v != kInfiniteVertex) seed_[v] = 1;
    }
  }

  // The live tetrahedra in the scan's order (they also serve the incidence lists and the
  // write-back, in that order), and the damage: the exact scan over the run's threads, or with
  // validated findings no scan, the lowest tetrahedron at each vertex alone, the list made later
  // only where a broken mesh needs it.
  void find_damage(const ValidatedFindings* validated) {
    listed_ = live_tetrahedra(mesh_, parts_, validated == nullptr);
    stats_.seconds_listing = seconds_since(t0_);
    if (validated != nullptr) {
      stats_.found_by_post_check = true;
      stats_.non_delaunay_faces = validated->rejected_faces;
      for (const VertexId v : validated->vertices) {
        if (v >= points_.size()) {
          throw std::logic_error("star splaying: a found vertex out of range");
        }
        seed_[v] = 1;
      }
    } else {
      for (const ScanFindings& found : exact_scan(mesh_, listed_.ordered, exact_mesh_, parts_)) {
        stats_.bad_tetrahedra += found.bad_tetrahedra;
        stats_.reflex_hull_vertices += found.reflex_hull_vertices;
        stats_.non_delaunay_faces += found.non_delaunay_faces;
        for (const VertexId v : found.to_seed) seed_[v] = 1;
      }
    }
    stats_.seconds_scan = seconds_since(t0_);
    // `consistent`: built exactly and no flat or inverted tetrahedron found (the walks around a
    // vertex and the skipped grouping of equal points below rely on it too).
    consistent_ = exact_mesh_ && stats_.bad_tetrahedra == 0;
  }

  // Burglary's marks that are still live tetrahedra. (A dead mark stands for the live tetrahedra
  // below it in the DAG, which for a mark made early is much of the mesh; the exact scan finds
  // every non-Delaunay face among them anyway.) They are seeds unless the scan proved the mesh
  // Delaunay: on a consistent mesh (an exactly built one is, burglary's included:
  // docs/design.md), every face locally Delaunay under the perturbed test and every tetrahedron
  // positively oriented make it the Delaunay tetrahedralization, so a star at a mark would be
  // splayed into itself, for nothing.
  void seed_marks(const std::vector<TetId>& marks) {
    const bool proven = consistent_ && stats_.non_delaunay_faces == 0;
    for (const TetId t : marks) {
      if (t < slots_ && mesh_.tets.is_alive(t, std::memory_order_acquire)) {
        ++stats_.live_marks;
        if (!proven) seed_quad(mesh_.tets[t].vertex);
      }
    }
    stats_.marks_seeded = !proven && stats_.live_marks > 0;
  }

  // Each set of equal points has one vertex in the result (`canonical_`: the vertex the engine
  // kept, else the lowest index): one that is no vertex yet (an abandoned insertion) is seeded; a
  // second vertex of the same point (an inexact kernel can insert a duplicate) seeds the vertices
  // around it, whose new stars leave it out. (The engine's skipped duplicates are the other
  // points of each set: nothing to do.) Where every point is a vertex of an exactly built mesh
  // with no flat or inverted tetrahedron, no two points are equal (two vertices at one point would
  // make the tetrahedra around them flat, or the mesh cover that point twice), and the grouping
  // is skipped. False: nothing to splay.
  bool group_points() {
    const auto& lowest = listed_.lowest_tetrahedron;
    const bool all_distinct_vertices =
        consistent_ &&
        std::all_of(lowest.begin(), lowest.end(), [](TetId t) { return t != kNoTet; });
    if (all_distinct_vertices) {
      canonical_.resize(points_.size());
      std::iota(canonical_.begin(), canonical_.end(), VertexId{0});
    } else {
      canonical_ = canonical_points(points_, [&](VertexId v) { return is_vertex(v); });
    }
    bool any_seed = false;
    for (VertexId v = 0; v < points_.size(); ++v) {
      if (canonical_[v] == v) {
        vertices_.push_back(v);
        if (!is_vertex(v)) {
          seed_[v] = 1;
          ++stats_.missing_vertices;
        }
        any_seed |= seed_[v] != 0;
      } else if (is_vertex(v)) {
        second_copies_.push_back(v);
      }
    }
    return any_seed || !second_copies_.empty();
  }

  // Where the mesh is consistent (built exactly, every tetrahedron positive, no point twice), the
  // tetrahedra at a vertex are found by a walk around it; elsewhere from incidence lists of the
  // whole mesh (a broken mesh's star need not be connected through its faces). Then the vertices
  // around a second copy of a point are seeds.
  void choose_stars(const ValidatedFindings* validated) {
    stats_.stars_walked = consistent_ && second_copies_.empty();
    if (stats_.stars_walked) {
      auto walker = std::make_unique<WalkedMeshStars>(mesh_, listed_.lowest_tetrahedron);
      walked_ = walker.get();
      stars_of_mesh_ = std::move(walker);
    } else {
      // The list the listing skipped (validated findings) is needed here and in the write-back.
      if (validated != nullptr) listed_.ordered = live_tetrahedra(mesh_, parts_, true).ordered;
      stars_of_mesh_ = std::make_unique<SharedMeshStars>(mesh_, listed_.ordered, parts_);
    }
    std::vector<Quad> around;
    for (const VertexId v : second_copies_) {
      stars_of_mesh_->tetrahedra_of(v, around);
      for (const Quad& q : around) seed_quad(q);
    }
  }

  [[nodiscard]] std::vector<VertexId> seeded_vertices() const {
    std::vector<VertexId> out;
    for (VertexId v = 0; v < points_.size(); ++v) {
      if (seed_[v] != 0 && canonical_[v] == v) out.push_back(v);
    }
    return out;
  }

  // Flips first (--repair=flips-splay), on a consistent mesh where every distinct point is a
  // vertex: the tetrahedra at the seeds hold every non-Delaunay face, and what the flips leave of
  // those is what the stars must repair (the new seeds, returned). The flips keep the mesh
  // consistent, so the walks still serve, from a live tetrahedron at each vertex: where a
  // vertex's died, one of the flips' new ones at it is alive (a flip keeps its vertices). So
  // `lowest_tetrahedron` is from here on a walk's start, not always the lowest.
  std::vector<VertexId> flip_first(const FlipPass& flips, const std::vector<VertexId>& seeds) {
    const auto flipping = Clock::now();
    std::vector<TetId> at_seeds;
    std::vector<TetId> around_seed;
    for (const VertexId v : seeds) {
      walked_->tetrahedron_ids_of(v, around_seed);
      at_seeds.insert(at_seeds.end(), around_seed.begin(), around_seed.end());
    }
    std::sort(at_seeds.begin(), at_seeds.end());
    at_seeds.erase(std::unique(at_seeds.begin(), at_seeds.end()), at_seeds.end());
    std::vector<TetId> made;
    std::vector<Quad> left;
    stats_.flipped = true;
    stats_.flips = flips(at_seeds, made, left);
    for (const TetId t : made) {
      if (!mesh_.tets.is_alive(t, std::memory_order_relaxed)) continue;
      for (const VertexId v : mesh_.tets[t].vertex) {
        if (v == kInfiniteVertex) continue;
        const TetId start = listed_.lowest_tetrahedron[v];
        if (!mesh_.tets.is_alive(start, std::memory_order_relaxed) ||
            mesh_.tets[start].index_of(v) < 0) {
          listed_.lowest_tetrahedron[v] = t;
          ++stats_.walk_starts_moved;
        }
      }
    }
    stats_.faces_left = left.size() / 2;
    std::fill(seed_.begin(), seed_.end(), 0);
    for (const Quad& q : left) seed_quad(q);
    stats_.seconds_flipping = seconds_since(flipping);
    return seeded_vertices();
  }

  // The seeds' stars (built on the run's threads), made consistent, written back.
  void splay(const std::vector<VertexId>& seeds) {
    const NearGrid grid(points_, [&] {  // the vertices of the mesh
      std::vector<VertexId> present;
      for (const VertexId v : vertices_) {
        if (is_vertex(v)) present.push_back(v);
      }
      return present;
    });
    const MeshStars& stars_of_mesh = *stars_of_mesh_;
    StarSplayer splayer(points_, stars_of_mesh, canonical_, pool_of(points_, vertices_),
                        [&](VertexId x, std::vector<VertexId>& out) {
                          grid.near(x, out);
                          std::vector<Quad> around;
                          const std::size_t found = out.size();
                          for (std::size_t i = 0; i < found; ++i) {  // and their neighbours
                            stars_of_mesh.tetrahedra_of(out[i], around);
                            for (const Quad& q : around) {
                              for (const VertexId y : q) {
                                if (y != kInfiniteVertex) out.push_back(y);
                              }
                            }
                          }
                        });
    const auto building = Clock::now();
    splayer.activate_all(seeds, parts_);
    const auto enforcing = Clock::now();
    stats_.seconds_building = std::chrono::duration<double>(enforcing - building).count();
    splayer.run();
    stats_.seconds_enforcing = seconds_since(enforcing);
    write_back(mesh_, splayer, canonical_, listed_.ordered, walked_, stats_);
  }

  SharedMesh& mesh_;
  const std::vector<Point3>& points_;
  bool exact_mesh_;
  int parts_;
  SplayStats& stats_;
  Clock::time_point t0_;
  std::size_t slots_;  // the store's slots before the repair
  LiveTetrahedra listed_;
  std::vector<char> seed_;
  bool consistent_ = false;
  std::vector<VertexId> canonical_;
  std::vector<VertexId> vertices_;
  std::vector<VertexId> second_copies_;
  std::unique_ptr<MeshStars> stars_of_mesh_;
  const WalkedMeshStars* walked_ = nullptr;  // stars_of_mesh_ when its stars are walked
};

}  // namespace

ValidatedFindings validated_findings(const ValidationReport& report, std::size_t input_count,
                                     const std::vector<std::pair<VertexId, VertexId>>& duplicates) {
  std::vector<VertexId> mesh_vertex(input_count);
  std::iota(mesh_vertex.begin(), mesh_vertex.end(), VertexId{0});
  std::vector<VertexId> output_name = mesh_vertex;
  for (const auto& [duplicate, vertex] : duplicates) {
    output_name[vertex] = std::min(output_name[vertex], duplicate);
  }
  for (const auto& [duplicate, vertex] : duplicates) mesh_vertex[output_name[vertex]] = vertex;
  ValidatedFindings found;
  found.rejected_faces = report.perturbed_violations;
  found.vertices.reserve(report.perturbed_violation_vertices.size());
  for (const std::uint32_t v : report.perturbed_violation_vertices) {
    found.vertices.push_back(mesh_vertex.at(v));
  }
  return found;
}

void splay_shared_mesh(SharedMesh& mesh, const std::vector<TetId>& marks, bool exact_mesh,
                       int threads, SplayStats& stats, const ValidatedFindings* validated,
                       const FlipPass* flips_first) {
  MeshSplay(mesh, exact_mesh, threads, stats).run(marks, validated, flips_first);
}

}  // namespace dtlab::engine
