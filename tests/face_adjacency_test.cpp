// engine::face_adjacency and engine::orient_positively on hand-made lists (the Python tests
// compare them with scipy on real meshes).
#include "dtlab/engine/face_adjacency.hpp"

#include <gtest/gtest.h>

#include <stdexcept>

#include "dtlab/predicates/kernels.hpp"

namespace {

using dtlab::engine::Tetrahedron;
using dtlab::predicates::Point3;

// Two positive tetrahedra on the face (0, 1, 2): apexes 3 above and 4 below.
const std::vector<Point3> kPoints{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {0.2, 0.2, -1}};
const std::vector<Tetrahedron> kTwo{{0, 1, 2, 3}, {0, 2, 1, 4}};

TEST(FaceAdjacency, NeighbourIsOppositeTheVertex) {
  ASSERT_GT(
      dtlab::predicates::ExactKernel::orient3d(kPoints[0], kPoints[1], kPoints[2], kPoints[3]), 0);
  ASSERT_GT(
      dtlab::predicates::ExactKernel::orient3d(kPoints[0], kPoints[2], kPoints[1], kPoints[4]), 0);
  const auto a = dtlab::engine::face_adjacency(kTwo, kPoints.size());
  // The shared face (0, 1, 2) is opposite vertex 3 in the first and 4 in the second.
  EXPECT_EQ(a.neighbors[0], (std::array<std::int32_t, 4>{-1, -1, -1, 1}));
  EXPECT_EQ(a.neighbors[1], (std::array<std::int32_t, 4>{-1, -1, -1, 0}));
  EXPECT_EQ(a.boundary_faces.size(), 6u);
  EXPECT_EQ(a.boundary_face_tetrahedra.size(), 6u);
}

TEST(FaceAdjacency, BoundaryFacesFaceOutward) {
  const auto a = dtlab::engine::face_adjacency(kTwo, kPoints.size());
  for (std::size_t f = 0; f < a.boundary_faces.size(); ++f) {
    const auto& face = a.boundary_faces[f];
    const Tetrahedron& t = kTwo[a.boundary_face_tetrahedra[f]];
    std::uint32_t apex = 0;
    for (const std::uint32_t v : t) {
      if (v != face[0] && v != face[1] && v != face[2]) apex = v;
    }
    // (b - a) x (c - a) points away from the tetrahedron's fourth vertex: orient3d < 0.
    EXPECT_LT(dtlab::predicates::ExactKernel::orient3d(kPoints[face[0]], kPoints[face[1]],
                                                       kPoints[face[2]], kPoints[apex]),
              0);
  }
}

TEST(FaceAdjacency, RefusesAFaceOnThreeTetrahedraAndIdsOutOfRange) {
  const std::vector<Tetrahedron> three{{0, 1, 2, 3}, {0, 2, 1, 4}, {0, 1, 2, 4}};
  EXPECT_THROW(dtlab::engine::face_adjacency(three, kPoints.size()), std::invalid_argument);
  EXPECT_THROW(dtlab::engine::face_adjacency({{0, 1, 2, 5}}, kPoints.size()),
               std::invalid_argument);
}

TEST(OrientPositively, TurnsNegativeTetrahedraAndLeavesFlatOnes) {
  std::vector<Tetrahedron> tets{{0, 1, 3, 2}, {0, 1, 2, 3}, {0, 1, 1, 2}};
  EXPECT_EQ(dtlab::engine::orient_positively(kPoints, tets), 1u);
  EXPECT_EQ(tets[0], (Tetrahedron{0, 1, 2, 3}));
  EXPECT_EQ(tets[1], (Tetrahedron{0, 1, 2, 3}));
  EXPECT_EQ(tets[2], (Tetrahedron{0, 1, 1, 2}));
}

}  // namespace
