#pragma once
// The one validator (CLI, tests, fuzzers, experiments). It rebuilds adjacency from the
// tetrahedron list alone and decides every check exactly, with the adaptive kernel (exact for
// every finite double), after the engine's power-of-two scaling when that is lossless.
#include <cstdint>
#include <string>
#include <vector>

#include "dtlab/engine/tetrahedron.hpp"
#include "dtlab/predicates/point.hpp"

namespace dtlab::engine {

using predicates::Point3;

struct ValidationReport {
  std::uint64_t points = 0;
  std::uint64_t tetrahedra = 0;
  std::uint64_t interior_faces = 0;
  std::uint64_t boundary_faces = 0;
  // Violations, each counted:
  std::uint64_t invalid_tetrahedra = 0;        // vertex id out of range or repeated
  std::uint64_t non_positive_orientation = 0;  // orient3d <= 0 (flat or inverted)
  std::uint64_t non_manifold_faces = 0;        // a face shared by more than two tetrahedra
  std::uint64_t inconsistent_faces = 0;        // two tetrahedra on the same side of their face
  std::uint64_t non_delaunay_faces = 0;        // opposite vertex strictly inside the circumsphere
  std::uint64_t open_boundary_edges = 0;       // boundary edge not on exactly two boundary faces
  std::uint64_t reflex_boundary_edges = 0;     // boundary not convex there (union != convex hull)
  std::uint64_t reflex_boundary_vertices = 0;  // boundary not convex at a vertex (e.g. a fan
                                               // winding twice round it, with convex edges)
  std::uint64_t missing_points = 0;            // distinct input point that is no vertex
  std::uint64_t repeated_duplicates = 0;       // duplicate set used as a vertex more than once
  std::int64_t euler_characteristic = 0;       // V - E + F - T; 1 for a triangulated ball
  // Ties, no violation (a Delaunay mesh of cospherical or coplanar points may have them), but
  // what decides whether it is the unique tetrahedralization of the engine's perturbation
  // (predicates/perturbation.hpp):
  std::uint64_t tied_faces = 0;  // interior: the opposite vertex exactly on the circumsphere
  // Of those, the ones the perturbation decides against (the perturbed test puts the opposite
  // vertex inside); counted where the face's first tetrahedron is positively oriented.
  std::uint64_t tied_faces_against_perturbation = 0;
  std::uint64_t flat_boundary_edges = 0;  // boundary edge between two coplanar boundary faces
  // Of those, the ones where the perturbation puts the second face's apex in conflict with the
  // vertex at infinity over the first (the engine's infinite tetrahedra would be flipped there).
  std::uint64_t flat_boundary_edges_against_perturbation = 0;
  // Global check: the exact sum of the tetrahedra's signed volumes against the exact volume of
  // the convex hull of the input points, computed independently of the mesh (CGAL's hull). Equal
  // volumes pin the number of times consistent tetrahedra cover the hull to one.
  std::uint64_t volume_mismatch = 0;  // 1 when the two exact volumes differ
  // Where the boundary is not convex (reflex edges or vertices) the volumes differ by
  // construction: probe points strictly inside tetrahedra (near the reflex places, and a sample
  // elsewhere) are counted exactly instead; one inside two tetrahedra means the mesh overlaps.
  std::uint64_t volume_excess = 0;  // 1 when the tetrahedra's volume exceeds the hull's (overlap)
  std::uint64_t probe_points = 0;   // probes tested (0: the boundary is convex)
  std::uint64_t probes_covered_twice = 0;  // probes inside (or on) a second tetrahedron
  bool probe_check_complete = true;        // false: its work budget (2^28 steps) ran out
  std::string kernel;                      // the kernel that decided: "adaptive" or "exact" (GMP)
  // Per tetrahedron: 1 if it has a non-Delaunay face (for the .vtu "non_delaunay" array).
  std::vector<std::int32_t> non_delaunay_flags;
  // What the perturbed test rejects: interior faces that are non-Delaunay or tied against the
  // perturbation, boundary edges that are reflex or flat against it. Counted; their vertices
  // listed only when validate() is asked to (a face's two tetrahedra's eight, an edge's two
  // boundary faces' four; unsorted, with repeats). On a mesh_consistent() mesh these are the
  // faces that star splaying's exact scan finds, so burglary's post-check hands the list to the
  // repair instead of a second scan (docs/design.md, "The post-check's findings").
  std::uint64_t perturbed_violations = 0;
  std::vector<std::uint32_t> perturbed_violation_vertices;

  [[nodiscard]] bool consistent() const;  // everything but the Delaunay property
  // A sound mesh whose boundary may be non-convex: everything but the Delaunay property and the
  // convexity of the boundary (reflex edges and vertices), with the global check that fits the
  // boundary: equal volumes where it is convex, no probe covered twice where it is not, and never
  // more volume than the hull. With the vertex at infinity, a reflex boundary edge is a
  // non-Delaunay face of an infinite tetrahedron (burglary can leave one; docs/design.md).
  [[nodiscard]] bool mesh_consistent() const;
  [[nodiscard]] bool valid() const;  // consistent and Delaunay
  // Valid, and no tie (interior face or flat boundary edge) decided against the perturbation:
  // then every face, the infinite tetrahedra's included, is strictly locally Delaunay under the
  // perturbation, which makes the mesh the unique perturbed Delaunay tetrahedralization (the one
  // dtlab's engine and star splaying build; docs/design.md, "The validator").
  [[nodiscard]] bool is_perturbed_delaunay() const;
  [[nodiscard]] std::string json() const;
};

// The kernel that decides the validator's predicates: adaptive (the default, the code under test
// in most runs) or the independent GMP reference.
enum class ValidateWith { Adaptive, Exact };
const char* to_string(ValidateWith k);

// `threads`: how many threads share the work (the report is the same for every count);
// kAllThreads: one per hardware thread.
inline constexpr int kAllThreads = 0;
// `list_perturbed_violations`: fill ValidationReport::perturbed_violation_vertices.
ValidationReport validate(const std::vector<Point3>& points, const std::vector<Tetrahedron>& tets,
                          ValidateWith kernel = ValidateWith::Adaptive, int threads = 1,
                          bool list_perturbed_violations = false);

}  // namespace dtlab::engine
