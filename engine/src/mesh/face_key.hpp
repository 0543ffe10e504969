#pragma once
// A face named by its vertices, for matching the faces of tetrahedra that share it: the
// replacement's generic matching (insertion/tet_replacement.hpp) and the repairs' write-backs
// (repair/splay_repair.cpp, repair/list_repair.cpp).
#include <array>
#include <compare>
#include <cstdint>
#include <utility>

#include "mesh/tet_store.hpp"

namespace dtlab::engine {

// A face's three vertex ids, sorted, as two integers (cheap to compare): the same key from either
// side of the face. Ordered as the sorted ids are, lexicographically.
struct FaceKey {
  std::uint64_t high;  // the lowest id, then the middle one
  std::uint32_t low;   // the highest id
  bool operator==(const FaceKey&) const = default;
  auto operator<=>(const FaceKey&) const = default;
  [[nodiscard]] std::array<VertexId, 3> vertices() const {
    return {static_cast<VertexId>(high >> 32), static_cast<VertexId>(high), low};
  }
};

// The key of face f (the face opposite vertex f) of the tetrahedron with vertices v.
inline FaceKey face_key(const Quad& v, int f) {
  const auto& fv = kFaceVertex[static_cast<std::size_t>(f)];
  VertexId a = v[static_cast<std::size_t>(fv[0])];
  VertexId b = v[static_cast<std::size_t>(fv[1])];
  VertexId c = v[static_cast<std::size_t>(fv[2])];
  if (a > b) std::swap(a, b);
  if (b > c) std::swap(b, c);
  if (a > b) std::swap(a, b);
  return {(static_cast<std::uint64_t>(a) << 32) | b, c};
}

// A face where it lies (ref: a tetrahedron's face, or a new tetrahedron's by its index in a
// write-back), under its key; is_new: the tetrahedron is one the write-back makes.
struct FaceEntry {
  FaceKey key;
  FaceRef ref;
  bool is_new;
};

inline bool by_face_key(const FaceEntry& a, const FaceEntry& b) {
  return a.key < b.key;
}

}  // namespace dtlab::engine
