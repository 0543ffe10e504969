#pragma once
// One vertex's star for star splaying (Shewchuk, SoCG 2005; docs/design.md): the tetrahedra
// around the centre v in the Delaunay tetrahedralization of v, the vertices offered to it so far
// (`known`) and the vertex at infinity. Every tetrahedron is a positively oriented quad that
// contains v. Offering a vertex w is one step of an incremental convex hull in the lifted view:
// the tetrahedra whose circumsphere holds w leave the star (a disk of v's link, since they are
// the part at v of w's cavity, a ball with v on its boundary), and w is joined to the boundary of
// that disk. Decided by exact predicates with the engine's perturbation (conflict.hpp), whatever
// kernel built the mesh being repaired.
#include <array>
#include <cstdint>
#include <cstring>
#include <vector>

#include "dtlab/predicates/point.hpp"
#include "mesh/conflict.hpp"

namespace dtlab::engine {

// Working space of VertexStar::offer, shared by every star of a repair (a star keeps only what
// it is).
struct StarScratch {
  struct OpenFace {
    VertexId key;  // the face's vertex other than the centre and the offered one
    int quad;
    int face;
  };
  std::vector<char> conflict;
  std::vector<char> visited;
  std::vector<int> stack;
  std::vector<int> remap;
  std::vector<Quad> next_quads;
  std::vector<Quad> next_keys;
  std::vector<std::array<int, 4>> next_across;
  std::vector<OpenFace> open;
};

class VertexStar {
 public:
  // The star of v over {a, b, c} (not coplanar with v) and the vertex at infinity: the finite
  // tetrahedron and its three infinite neighbours through v.
  void start(const std::vector<predicates::Point3>& points, VertexId v, VertexId a, VertexId b,
             VertexId c);

  // Offers w: false when w was known already or enters no tetrahedron (it is no Delaunay
  // neighbour of v over the known vertices); else the star changed and `removed` received the
  // tetrahedra that left it.
  bool offer(const std::vector<predicates::Point3>& points, VertexId w, std::vector<Quad>& removed,
             StarScratch& scratch);

  // Whether a tetrahedron with these vertices (sorted) is in the star.
  [[nodiscard]] bool has(const Quad& sorted) const;
  [[nodiscard]] bool knows(VertexId w) const;
  [[nodiscard]] VertexId center() const { return center_; }
  [[nodiscard]] const std::vector<Quad>& tetrahedra() const { return quads_; }
  // Every vertex of the star's tetrahedra but the centre (the vertex at infinity included).
  void link_vertices(std::vector<VertexId>& out) const;

 private:
  static constexpr int kOutside = -1;    // no finite cone holds the direction
  static constexpr int kUndecided = -2;  // a tie on a cone's boundary, or the walk ran long
  // The finite tetrahedron whose open cone at the centre holds w's direction (then no other
  // closed cone holds it: it is the one offer's search in order would find), or kOutside, or
  // kUndecided (offer then searches the closed cones in order).
  [[nodiscard]] int cone_of(const std::vector<predicates::Point3>& points, VertexId w) const;
  void make_keys();

  VertexId center_ = kInfiniteVertex;
  std::vector<Quad> quads_;
  std::vector<Quad> keys_;  // keys_[i]: quads_[i] sorted (has() compares without sorting)
  // across_[i][j]: the quad across face j of quad i (the face opposite quads_[i][j]) when that
  // face contains the centre; -1 for the face opposite the centre.
  std::vector<std::array<int, 4>> across_;
  std::vector<VertexId> known_;  // sorted
};

// A quad's vertices in increasing order (the vertex at infinity last): a tetrahedron's identity.
inline Quad sorted_quad(Quad q) {
  for (std::size_t i = 1; i < 4; ++i) {
    for (std::size_t j = i; j > 0 && q[j - 1] > q[j]; --j) std::swap(q[j - 1], q[j]);
  }
  return q;
}

// Whether two quads name the same vertices in the same places (inline: std::array's == calls
// memcmp, and the stars compare quads in their inner loops), as two 64-bit words.
inline bool same_quad(const Quad& a, const Quad& b) {
  std::array<std::uint64_t, 2> x{};
  std::array<std::uint64_t, 2> y{};
  static_assert(sizeof(x) == sizeof(Quad));
  std::memcpy(x.data(), a.data(), sizeof(Quad));
  std::memcpy(y.data(), b.data(), sizeof(Quad));
  return ((x[0] ^ y[0]) | (x[1] ^ y[1])) == 0;
}

}  // namespace dtlab::engine
