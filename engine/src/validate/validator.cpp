#include "dtlab/engine/validator.hpp"

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <nlohmann/json.hpp>
#include <numeric>
#include <stdexcept>
#include <thread>
#include <tuple>

#include "dtlab/engine/point_set_info.hpp"
#include "dtlab/predicates/kernels.hpp"
#include "dtlab/predicates/perturbation.hpp"
#include "mesh/tet_store.hpp"
#include "support/json_fields.hpp"
#include "support/parallel_ranges.hpp"
#include "validate/boundary_checks.hpp"
#include "validate/exact_volume.hpp"
#include "validate/probe_coverage.hpp"
#include "validate/vertex_buckets.hpp"

namespace dtlab::engine {
namespace {

struct FaceEntry {
  std::array<std::uint32_t, 3> key;  // sorted vertex ids
  std::uint32_t tet;
  std::uint8_t face;
  std::uint8_t parity;  // parity of the permutation from the sorted key to the outward triple
};

// By key, then tetrahedron, then face; the key compared as two 64-bit words.
bool face_order(const FaceEntry& a, const FaceEntry& b) {
  const std::uint64_t a01 = (std::uint64_t{a.key[0]} << 32) | a.key[1];
  const std::uint64_t b01 = (std::uint64_t{b.key[0]} << 32) | b.key[1];
  if (a01 != b01) return a01 < b01;
  const std::uint64_t a2 = (std::uint64_t{a.key[2]} << 32) | a.tet;
  const std::uint64_t b2 = (std::uint64_t{b.key[2]} << 32) | b.tet;
  if (a2 != b2) return a2 < b2;
  return a.face < b.face;
}

std::uint8_t permutation_parity(const std::array<std::uint32_t, 3>& triple) {
  int inversions = 0;
  for (int i = 0; i < 3; ++i) {
    for (int j = i + 1; j < 3; ++j) {
      if (triple[static_cast<std::size_t>(i)] > triple[static_cast<std::size_t>(j)]) ++inversions;
    }
  }
  return static_cast<std::uint8_t>(inversions & 1);
}

std::array<std::uint32_t, 3> oriented_face(const Tetrahedron& t, int f) {
  const auto& fv = kFaceVertex[static_cast<std::size_t>(f)];
  return {t[static_cast<std::size_t>(fv[0])], t[static_cast<std::size_t>(fv[1])],
          t[static_cast<std::size_t>(fv[2])]};
}

// What one thread found among the faces of its range of buckets (check() below).
struct FaceFindings {
  std::uint64_t interior_faces = 0;
  std::uint64_t boundary_faces = 0;
  std::uint64_t inconsistent_faces = 0;
  std::uint64_t non_manifold_faces = 0;
  std::uint64_t distinct_faces = 0;
  std::vector<std::array<std::uint32_t, 3>> boundary;  // outward-oriented boundary faces
  std::vector<SignedFace> unbalanced;                  // faces of non-zero multiplicity
};

// Every check of the report on `threads` threads, one stage a member. Faces and edges are grouped
// by their lowest vertex (vertex_buckets.hpp) and sorted inside each bucket, so the lists are in
// key order and the report does not depend on the thread count.
template <class K>
struct MeshCheck {
  MeshCheck(const std::vector<Point3>& points, const std::vector<Tetrahedron>& tetrahedra,
            int threads, bool list, ValidationReport& report)
      : pts(points),
        tets(tetrahedra),
        n(points.size()),
        parts(std::max(threads, 1)),
        list_violations(list),
        r(report),
        usable(tetrahedra.size(), 0),
        positive(tetrahedra.size(), 0),
        used(points.size(), 0),
        near_reflex(points.size(), 0) {}

  void run() {
    tetrahedra();
    group_faces();
    delaunay_faces();
    merge_faces();
    boundary_edges();
    boundary_vertices();
    vertex_coverage();
    euler_characteristic();
    global_cover();
  }

  // Per tetrahedron: usable and positive; per point: used.
  void tetrahedra() {
    std::vector<std::array<std::uint64_t, 2>> tet_counts(static_cast<std::size_t>(parts), {0, 0});
    in_parallel_ranges(tets.size(), parts,
                       [&](std::size_t begin, std::size_t end, std::size_t part) {
                         auto& [invalid, non_positive] = tet_counts[part];
                         for (std::size_t i = begin; i < end; ++i) {
                           const Tetrahedron& t = tets[i];
                           bool ok = true;
                           for (std::size_t a = 0; a < 4; ++a) {
                             if (t[a] >= n) ok = false;
                             for (std::size_t b = a + 1; b < 4; ++b) {
                               if (t[a] == t[b]) ok = false;
                             }
                           }
                           if (!ok) {
                             ++invalid;
                             continue;
                           }
                           usable[i] = 1;
                           for (const std::uint32_t v : t)
                             std::atomic_ref<char>(used[v]).store(1, std::memory_order_relaxed);
                           if (K::orient3d(pts[t[0]], pts[t[1]], pts[t[2]], pts[t[3]]) <= 0) {
                             ++non_positive;
                           } else {
                             positive[i] = 1;
                           }
                         }
                       });
    for (const auto& [invalid, non_positive] : tet_counts) {
      r.invalid_tetrahedra += invalid;
      r.non_positive_orientation += non_positive;
    }
  }

  // The faces matched: interior, boundary, inconsistent, non-manifold.
  void group_faces() {
    // Faces: a tetrahedron's four, grouped by their lowest vertex, then by key inside a bucket.
    // Equal keys are one face; (tet, face) orders a group's entries.
    // across[4 i + f]: 4 j + g where face f of tetrahedron i is face g of tetrahedron j and i < j
    // (kNoFace elsewhere), for the Delaunay test below.
    across.assign(4 * tets.size(), kNoFace);
    found.assign(static_cast<std::size_t>(parts), FaceFindings{});
    {
      const VertexBuckets<FaceEntry> faces =
          bucket_by_vertex<FaceEntry>(n, tets.size(), parts, [&](std::size_t i, const auto& sink) {
            if (usable[i] == 0) return;
            for (int f = 0; f < 4; ++f) {
              const auto triple = oriented_face(tets[i], f);
              auto key = triple;
              std::sort(key.begin(), key.end());
              sink(key[0], FaceEntry{key, static_cast<std::uint32_t>(i),
                                     static_cast<std::uint8_t>(f), permutation_parity(triple)});
            }
          });
      in_parallel_buckets(faces, parts, [&](std::size_t begin, std::size_t end, std::size_t part) {
        FaceFindings& mine = found[part];
        FaceEntry* const items = faces.items.get();
        std::vector<FaceEntry> scratch;
        std::vector<std::size_t> counts;
        for (std::size_t bucket = begin; bucket < end; ++bucket) {
          FaceEntry* const first = items + faces.first[bucket];
          FaceEntry* const last = items + faces.first[bucket + 1];
          sort_bucket(
              first, last, bucket << faces.shift, faces.shift,
              [](const FaceEntry& e) { return e.key[0]; }, face_order, scratch, counts);
          for (FaceEntry* i = first; i != last;) {
            FaceEntry* j = i;
            std::int32_t multiplicity = 0;
            while (j != last && j->key == i->key) {
              multiplicity += j->parity == 0 ? 1 : -1;
              ++j;
            }
            ++mine.distinct_faces;
            if (multiplicity != 0) mine.unbalanced.push_back({i->key, multiplicity});
            const auto count = static_cast<std::size_t>(j - i);
            if (count == 1) {
              ++mine.boundary_faces;
              mine.boundary.push_back(oriented_face(tets[i->tet], i->face));
            } else if (count == 2) {
              ++mine.interior_faces;
              if (i[0].parity == i[1].parity) ++mine.inconsistent_faces;
              across[4 * std::size_t{i[0].tet} + i[0].face] = 4 * i[1].tet + i[1].face;
            } else {
              ++mine.non_manifold_faces;
            }
            i = j;
          }
        }
      });
    }
  }

  // The Delaunay test of every interior face.
  void delaunay_faces() {
    // Every interior face locally Delaunay, tested from its lower tetrahedron in the list's order,
    // where one tetrahedron's points are mostly the last one's, rather than in the buckets' order.
    r.non_delaunay_flags.assign(tets.size(), 0);
    // Per part: non-Delaunay faces, tied faces, tied faces decided against the perturbation; and
    // the vertices of the faces the perturbed test rejects (both kinds of violation).
    std::vector<std::array<std::uint64_t, 3>> delaunay_counts(static_cast<std::size_t>(parts),
                                                              {0, 0, 0});
    std::vector<std::vector<std::uint32_t>> rejected_vertices(static_cast<std::size_t>(parts));
    in_parallel_ranges(
        tets.size(), parts, [&](std::size_t begin, std::size_t end, std::size_t part) {
          // A neighbour's record and its apex point can lie anywhere in the list and the point
          // array: requested a few tetrahedra ahead, so that the misses overlap
          // (docs/performance.md, "Measured choices").
          constexpr std::size_t kRecordsAhead = 8;
          constexpr std::size_t kApexAhead = 4;
          for (std::size_t i = begin; i < end; ++i) {
            if (i + kRecordsAhead < end) {
              for (std::size_t f = 0; f < 4; ++f) {
                const std::uint32_t other = across[4 * (i + kRecordsAhead) + f];
                if (other != kNoFace) __builtin_prefetch(&tets[other / 4]);
              }
            }
            if (i + kApexAhead < end) {
              for (std::size_t f = 0; f < 4; ++f) {
                const std::uint32_t other = across[4 * (i + kApexAhead) + f];
                if (other != kNoFace) __builtin_prefetch(&pts[tets[other / 4][other % 4]]);
              }
            }
            for (std::size_t f = 0; f < 4; ++f) {
              const std::uint32_t other = across[4 * i + f];
              if (other == kNoFace) continue;
              const Tetrahedron& t = tets[i];
              const std::uint32_t opposite = tets[other / 4][other % 4];
              auto& [non_delaunay, tied, tied_against] = delaunay_counts[part];
              const int side =
                  K::insphere(pts[t[0]], pts[t[1]], pts[t[2]], pts[t[3]], pts[opposite]);
              bool rejected = side > 0;
              if (side == 0) {
                ++tied;
                if (positive[i] != 0 &&
                    predicates::insphere_perturbed<K>(pts[t[0]], pts[t[1]], pts[t[2]], pts[t[3]],
                                                      pts[opposite]) > 0) {
                  ++tied_against;
                  rejected = true;
                }
              }
              if (rejected && list_violations) {
                std::vector<std::uint32_t>& mine = rejected_vertices[part];
                mine.insert(mine.end(), t.begin(), t.end());
                mine.insert(mine.end(), tets[other / 4].begin(), tets[other / 4].end());
              }
              if (side > 0) {
                ++non_delaunay;
                // Two threads may flag one tetrahedron (its neighbours lie in both ranges).
                std::atomic_ref<std::int32_t>(r.non_delaunay_flags[i])
                    .store(1, std::memory_order_relaxed);
                std::atomic_ref<std::int32_t>(r.non_delaunay_flags[other / 4])
                    .store(1, std::memory_order_relaxed);
              }
            }
          }
        });
    for (const auto& [non_delaunay, tied, tied_against] : delaunay_counts) {
      r.non_delaunay_faces += non_delaunay;
      r.tied_faces += tied;
      r.tied_faces_against_perturbation += tied_against;
    }
    r.perturbed_violations = r.non_delaunay_faces + r.tied_faces_against_perturbation;
    for (const std::vector<std::uint32_t>& mine : rejected_vertices) {
      r.perturbed_violation_vertices.insert(r.perturbed_violation_vertices.end(), mine.begin(),
                                            mine.end());
    }
  }

  // The threads' face findings, into the report and one boundary.
  void merge_faces() {
    across = {};
    for (FaceFindings& mine : found) {
      r.interior_faces += mine.interior_faces;
      r.boundary_faces += mine.boundary_faces;
      r.inconsistent_faces += mine.inconsistent_faces;
      r.non_manifold_faces += mine.non_manifold_faces;
      distinct_faces += mine.distinct_faces;
      boundary.insert(boundary.end(), mine.boundary.begin(), mine.boundary.end());
      unbalanced.insert(unbalanced.end(), mine.unbalanced.begin(), mine.unbalanced.end());
      mine = {};
    }
  }

  // The boundary's edges: closed and convex; its vertices: locally convex (boundary_checks.hpp).
  void boundary_edges() {
    detail::check_boundary_edges<K>(pts, boundary, list_violations, r, near_reflex);
  }
  void boundary_vertices() { detail::check_boundary_vertices<K>(pts, boundary, r, near_reflex); }

  // The points' use as vertices.
  void vertex_coverage() {
    // Vertex coverage: every distinct point is a vertex, each duplicate set exactly once.
    vertex_count = static_cast<std::int64_t>(std::count(used.begin(), used.end(), 1));
    std::vector<std::uint32_t> by_point(n);
    for (std::size_t i = 0; i < n; ++i) by_point[i] = static_cast<std::uint32_t>(i);
    std::sort(by_point.begin(), by_point.end(), [&](std::uint32_t a, std::uint32_t b) {
      return predicates::lexicographically_less(pts[a], pts[b]);
    });
    for (std::size_t i = 0; i < n;) {
      std::size_t j = i;
      int uses = 0;
      while (j < n && pts[by_point[j]] == pts[by_point[i]])
        uses += used[by_point[j++]] != 0 ? 1 : 0;
      if (uses == 0) ++r.missing_points;
      if (uses > 1) ++r.repeated_duplicates;
      i = j;
    }
  }

  // V - E + F - T.
  void euler_characteristic() {
    // Euler characteristic of the complex: the edges grouped by their lower vertex, each group's
    // higher vertices sorted and counted once each.
    std::vector<std::int64_t> edge_counts(static_cast<std::size_t>(parts), 0);
    {
      const VertexBuckets<std::uint64_t> edges = bucket_by_vertex<std::uint64_t>(
          n, tets.size(), parts, [&](std::size_t i, const auto& sink) {
            if (usable[i] == 0) return;
            const Tetrahedron& t = tets[i];
            for (std::size_t a = 0; a < 4; ++a) {
              for (std::size_t b = a + 1; b < 4; ++b) {
                const std::uint32_t u = std::min(t[a], t[b]);
                const std::uint32_t v = std::max(t[a], t[b]);
                sink(u, (std::uint64_t{u} << 32) | v);
              }
            }
          });
      in_parallel_buckets(edges, parts, [&](std::size_t begin, std::size_t end, std::size_t part) {
        std::uint64_t* const items = edges.items.get();
        std::vector<std::uint64_t> scratch;
        std::vector<std::size_t> counts;
        for (std::size_t bucket = begin; bucket < end; ++bucket) {
          std::uint64_t* const first = items + edges.first[bucket];
          std::uint64_t* const last = items + edges.first[bucket + 1];
          sort_bucket(
              first, last, bucket << edges.shift, edges.shift,
              [](std::uint64_t e) { return e >> 32; }, std::less<>(), scratch, counts);
          edge_counts[part] += std::unique(first, last) - first;
        }
      });
    }
    const std::int64_t edge_count =
        std::accumulate(edge_counts.begin(), edge_counts.end(), std::int64_t{0});
    const auto usable_tets = static_cast<std::int64_t>(std::count(usable.begin(), usable.end(), 1));
    r.euler_characteristic =
        vertex_count - edge_count + static_cast<std::int64_t>(distinct_faces) - usable_tets;
  }

  // The cover of the hull: exact volumes, or probes.
  void global_cover() {
    // Global: positively oriented, locally consistent tetrahedra with a closed boundary cover the
    // hull a constant number of times; equal exact volumes pin that number to one.
    const ExactGrid grid(pts);
    const auto mesh_volume = six_mesh_volume(pts, unbalanced, grid);
    const auto hull_volume = six_hull_volume(pts, grid);
    r.volume_mismatch = mesh_volume == hull_volume ? 0 : 1;
    // Tetrahedra on input points that do not overlap fill at most the hull: more is an exact proof
    // of overlap, whatever the boundary.
    r.volume_excess = mesh_volume > hull_volume ? 1 : 0;
    // Where the boundary is not convex the volumes differ by construction: probe points instead.
    if (r.reflex_boundary_edges > 0 || r.reflex_boundary_vertices > 0) {
      constexpr std::size_t kMaxProbes = std::size_t{1} << 16;
      const detail::ProbeCoverage coverage =
          detail::probe_coverage<K>(pts, tets, positive, near_reflex, kMaxProbes);
      r.probe_points = coverage.probes;
      r.probes_covered_twice = coverage.covered_twice;
      r.probe_check_complete = coverage.complete;
    }
  }

  static constexpr std::uint32_t kNoFace = ~std::uint32_t{0};

  const std::vector<Point3>& pts;
  const std::vector<Tetrahedron>& tets;
  const std::size_t n;
  const int parts;
  const bool list_violations;
  ValidationReport& r;
  // Bytes, not bits: the threads write neighbouring entries.
  std::vector<char> usable;       // per tetrahedron: valid, distinct vertex ids
  std::vector<char> positive;     // per tetrahedron: usable and positively oriented
  std::vector<char> used;         // per point: a vertex of a usable tetrahedron
  std::vector<char> near_reflex;  // per point: a vertex where the boundary is not convex
  // across[4 i + f]: 4 j + g where face f of tetrahedron i is face g of tetrahedron j and i < j
  // (kNoFace elsewhere), for the Delaunay test.
  std::vector<std::uint32_t> across;
  std::vector<FaceFindings> found;                     // per thread
  std::vector<std::array<std::uint32_t, 3>> boundary;  // outward-oriented boundary faces
  std::vector<SignedFace> unbalanced;
  std::size_t distinct_faces = 0;
  std::int64_t vertex_count = 0;
};

template <class K>
void check(const std::vector<Point3>& pts, const std::vector<Tetrahedron>& tets, int threads,
           bool list_violations, ValidationReport& r) {
  MeshCheck<K>(pts, tets, threads, list_violations, r).run();
}

}  // namespace

bool ValidationReport::consistent() const {
  return invalid_tetrahedra == 0 && non_positive_orientation == 0 && non_manifold_faces == 0 &&
         inconsistent_faces == 0 && open_boundary_edges == 0 && reflex_boundary_edges == 0 &&
         reflex_boundary_vertices == 0 && missing_points == 0 && repeated_duplicates == 0 &&
         euler_characteristic == 1 && volume_mismatch == 0;
}

// With a convex boundary the volumes must match. A reflex boundary edge or vertex means the union
// of the tetrahedra is not the hull, so the volumes differ by construction; there the global check
// is the probe count: no probe point inside two tetrahedra.
bool ValidationReport::mesh_consistent() const {
  const bool convex = reflex_boundary_edges == 0 && reflex_boundary_vertices == 0;
  return invalid_tetrahedra == 0 && non_positive_orientation == 0 && non_manifold_faces == 0 &&
         inconsistent_faces == 0 && open_boundary_edges == 0 && missing_points == 0 &&
         repeated_duplicates == 0 && euler_characteristic == 1 && volume_excess == 0 &&
         (convex ? volume_mismatch == 0 : probes_covered_twice == 0);
}

bool ValidationReport::valid() const {
  return consistent() && non_delaunay_faces == 0;
}

bool ValidationReport::is_perturbed_delaunay() const {
  return valid() && tied_faces_against_perturbation == 0 &&
         flat_boundary_edges_against_perturbation == 0;
}

std::string ValidationReport::json() const {
  Json j;
  put(j, {{"valid", valid()},
          {"consistent", consistent()},
          {"mesh_consistent", mesh_consistent()},
          {"points", points},
          {"tetrahedra", tetrahedra},
          {"interior_faces", interior_faces},
          {"boundary_faces", boundary_faces},
          {"invalid_tetrahedra", invalid_tetrahedra},
          {"non_positive_orientation", non_positive_orientation},
          {"non_manifold_faces", non_manifold_faces},
          {"inconsistent_faces", inconsistent_faces},
          {"non_delaunay_faces", non_delaunay_faces},
          {"open_boundary_edges", open_boundary_edges},
          {"reflex_boundary_edges", reflex_boundary_edges},
          {"reflex_boundary_vertices", reflex_boundary_vertices},
          {"missing_points", missing_points},
          {"repeated_duplicates", repeated_duplicates},
          {"euler_characteristic", euler_characteristic},
          {"tied_faces", tied_faces},
          {"tied_faces_against_perturbation", tied_faces_against_perturbation},
          {"flat_boundary_edges", flat_boundary_edges},
          {"flat_boundary_edges_against_perturbation", flat_boundary_edges_against_perturbation},
          {"perturbed_violations", perturbed_violations},
          {"perturbed_delaunay", is_perturbed_delaunay()},
          {"volume_mismatch", volume_mismatch},
          {"volume_excess", volume_excess},
          {"probe_points", probe_points},
          {"probe_check_complete", probe_check_complete},
          {"probes_covered_twice", probes_covered_twice},
          {"kernel", kernel}});
  return j.dump(2);
}

const char* to_string(ValidateWith k) {
  return k == ValidateWith::Exact ? "exact" : "adaptive";
}

ValidationReport validate(const std::vector<Point3>& points, const std::vector<Tetrahedron>& tets,
                          ValidateWith kernel, int threads, bool list_perturbed_violations) {
  ValidationReport r;
  r.points = points.size();
  r.tetrahedra = tets.size();
  const CoordinateMagnitudes magnitudes = coordinate_magnitudes(points);
  // Non-finite points are refused by the readers and by triangulate(); here they cannot be judged.
  if (!magnitudes.finite) throw std::invalid_argument("validate: a coordinate is NaN or infinite");
  // Faces are named 4 * tetrahedron + face in 32 bits.
  if (tets.size() >= (std::size_t{1} << 30)) {
    throw std::length_error("validate: more than 2^30 - 1 tetrahedra");
  }
  r.kernel = to_string(kernel);
  if (threads == kAllThreads)
    threads = static_cast<int>(std::max(1U, std::thread::hardware_concurrency()));
  if (kernel == ValidateWith::Exact) {
    check<predicates::ExactKernel>(points, tets, threads, list_perturbed_violations,
                                   r);  // the independent reference
    return r;
  }
  // The adaptive kernel is exact for every finite double (GMP fallback outside the expansion
  // range); the same lossless power-of-two scaling as the engine keeps most calls off that path.
  const RangeScaling scaling =
      adaptive_range_scaling(magnitudes.max_abs, magnitudes.min_abs_nonzero);
  if (scaling.lossless) {
    std::vector<Point3> scaled = points;
    for (Point3& p : scaled) {
      p = {std::ldexp(p.x, scaling.exponent), std::ldexp(p.y, scaling.exponent),
           std::ldexp(p.z, scaling.exponent)};
    }
    check<predicates::AdaptiveKernel>(scaled, tets, threads, list_perturbed_violations, r);
  } else {
    check<predicates::AdaptiveKernel>(points, tets, threads, list_perturbed_violations, r);
  }
  return r;
}

}  // namespace dtlab::engine
