#pragma once
// Star splaying applied: to the engine's shared mesh after a run (burglary's marks, the fast
// kernel's errors), and to any tetrahedron list (dtlab repair). Exact predicates throughout.
#include <cstdint>
#include <functional>
#include <utility>
#include <vector>

#include "dtlab/engine/triangulate.hpp"
#include "dtlab/engine/validator.hpp"
#include "mesh/conflict.hpp"
#include "mesh/shared_mesh.hpp"

namespace dtlab::engine {

// What an exact validation of the whole mesh found, where it judged the mesh consistent
// (burglary's post-check: ValidationReport::perturbed_violations and the vertices listed with
// them, named as the mesh names them). On such a mesh the validator's perturbed tests reject
// exactly the faces that splay_shared_mesh's exact scan would, so the scan is skipped and these
// vertices are its seeds (docs/design.md, "The post-check's findings").
struct ValidatedFindings {
  std::uint64_t rejected_faces = 0;
  std::vector<VertexId> vertices;
};

// The findings of a validation of SharedMesh::finite_tetrahedra's output (listed:
// validate(..., true)) in the mesh's names: the output names each set of equal points by its
// lowest index, the mesh by the point of the set that was inserted. `duplicates`: the engine's
// (skipped point, its vertex) pairs, as finite_tetrahedra took them.
ValidatedFindings validated_findings(const ValidationReport& report, std::size_t input_count,
                                     const std::vector<std::pair<VertexId, VertexId>>& duplicates);

// --repair=flips-splay's first stage, the engine's (LawsonPass::flip_from): exact Lawson
// flips from every face of the live tetrahedra `tets`. Returns the flips; `created` gets the
// tetrahedra they made, `left` the vertices of both tetrahedra of each face still non-Delaunay
// after them (where no flip applied, or still queued when the pass's bound stopped it).
using FlipPass = std::function<std::uint64_t(const std::vector<TetId>& tets,
                                             std::vector<TetId>& created, std::vector<Quad>& left)>;

// Repairs the live tetrahedra of `mesh` (infinite ones included) into the Delaunay
// tetrahedralization of its points, locally: stars are splayed from the vertices of `marks` (those
// still live), of every non-Delaunay face and of every flat or
// inverted finite tetrahedron, from every point that should be a vertex and is none (an abandoned
// insertion), and around a second vertex of one point; the rest of the mesh is kept.
// `exact_mesh`: the mesh was built with exact predicates (each face is then scanned from one side
// only). The store pass and the exact scan run on `threads` threads (the run's own); the
// splaying and the write-back on the caller's. `stats` gets the counts and the times.
// `validated`: the faces found already; no exact scan. Only for a mesh built exactly
// (`exact_mesh`, checked), with the vertex at infinity (no auxiliary vertices, which the
// validation of finite tetrahedra does not see) and judged mesh_consistent() by that validation
// (the one-sided tests and the walks around vertices rely on it): the caller's to ensure.
// `flips_first`: where the mesh is consistent (built exactly, no flat or inverted tetrahedron,
// every point one vertex), the faces of the tetrahedra at the seeds are handed to it first, and
// only the faces it leaves seed the stars (docs/design.md, "Flips, then star splaying").
void splay_shared_mesh(SharedMesh& mesh, const std::vector<TetId>& marks, bool exact_mesh,
                       int threads, SplayStats& stats, const ValidatedFindings* validated = nullptr,
                       const FlipPass* flips_first = nullptr);

// The Delaunay tetrahedralization of `points` from any list of tetrahedra on them (ids checked by
// the caller): every distinct point gets a star, from its neighbours in `tets` (near points for a
// point no tetrahedron uses). Duplicate points are named by their lowest index.
std::vector<Tetrahedron> splay_tetrahedra(const std::vector<Point3>& points,
                                          const std::vector<Tetrahedron>& tets, SplayStats& stats,
                                          int threads = 1);

}  // namespace dtlab::engine
