#pragma once
// A face of a Bowyer-Watson cavity's boundary (cavity_search.hpp finds them,
// TetReplacement::replace_cavity builds on them).
#include "mesh/tet_store.hpp"

namespace dtlab::engine {

// Face `face` of cavity tetrahedron `inside`, whose neighbour across (`outside`) is not in
// conflict. The new tetrahedron on it is `inside` with the vertex at `face` replaced by p.
struct CavityFace {
  TetId inside;
  int face;
  FaceRef outside;
};

}  // namespace dtlab::engine
