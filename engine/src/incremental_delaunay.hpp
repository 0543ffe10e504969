#pragma once
// The insertion kernel: DAG location, 1->4 / 2->6 / k->2k subdivision, and legalization by the
// swaps S23, S32, S22 and S44 (Kohout and Kolingerova 2003, Sect. 4). Templated on the predicate
// kernel K so that a kernel costs nothing to choose. See docs/design.md.
//
// The vertex at infinity. Every hull face carries an infinite tetrahedron, so every face has two
// sides and S22 is the S44 whose ring contains the infinite vertex. For orientation tests the
// infinite vertex stands for the point "behind" a fixed interior point O, in the sense of
// oriented projective geometry: orient(..., inf, ...) is minus orient(..., O, ...). O is the exact
// centroid of the first tetrahedron, kept symbolic (a rounded centroid of a flat first
// tetrahedron can land on its face plane): K::orient3d_centroid decides it exactly. An infinite
// tetrahedron (a, b, c, inf) then is the unbounded cone from O beyond the hull face abc, so finite
// and infinite tetrahedra tile all of space, every flip is checked geometrically, and the DAG
// partitions space as the paper's auxiliary tetrahedron does. The insphere test of an infinite
// tetrahedron does not use O: a point conflicts with (a, b, c, inf) iff it lies beyond the plane
// abc, or on it inside circle abc.
#include <algorithm>
#include <array>
#include <chrono>
#include <cstdint>
#include <stdexcept>
#include <vector>

#include "dtlab/engine/tet_mesh.hpp"
#include "dtlab/engine/triangulate.hpp"
#include "dtlab/predicates/perturbation.hpp"

namespace dtlab::engine {

template <class K>
class IncrementalDelaunay {
 public:
  enum class Outcome { Inserted, Duplicate, Abandoned };

  IncrementalDelaunay(const std::vector<Point3>& points, const TriangulateOptions& options,
                      TriangulationStats& stats)
      : points_(points), options_(options), stats_(stats) {}

  // Builds the first tetrahedron abcd (affinely independent) and its four infinite neighbours.
  void start(VertexId a, VertexId b, VertexId c, VertexId d) {
    const Point3 &pa = points_[a], &pb = points_[b], &pc = points_[c], &pd = points_[d];
    first_ = {pa, pb, pc, pd};
    int o = K::orient3d(pa, pb, pc, pd);
    if (o == 0) throw TriangulationError("the first tetrahedron is flat under this kernel");
    if (o < 0) std::swap(a, b);
    // O as a plain point when the rounded centroid lies strictly inside the first tetrahedron
    // (checked exactly): one orient3d instead of four. Otherwise O stays the symbolic centroid.
    const Point3 rounded{(pa.x + pb.x + pc.x + pd.x) / 4, (pa.y + pb.y + pc.y + pd.y) / 4,
                         (pa.z + pb.z + pc.z + pd.z) / 4};
    const Point3 &qa = points_[a], &qb = points_[b];
    origin_is_point_ = predicates::ExactKernel::orient3d(rounded, qb, pc, pd) > 0 &&
                       predicates::ExactKernel::orient3d(qa, rounded, pc, pd) > 0 &&
                       predicates::ExactKernel::orient3d(qa, qb, rounded, pd) > 0 &&
                       predicates::ExactKernel::orient3d(qa, qb, pc, rounded) > 0;
    origin_ = rounded;
    const std::array<VertexId, 4> first{a, b, c, d};
    scratch_new_.clear();
    scratch_new_.push_back(first);
    for (const auto& f : kFaceVertex) {
      scratch_new_.push_back({first[static_cast<std::size_t>(f[0])],
                              first[static_cast<std::size_t>(f[1])],
                              first[static_cast<std::size_t>(f[2])], kInfiniteVertex});
    }
    scratch_old_.clear();
    scratch_parent_.assign(scratch_new_.size(), -1);
    scratch_source_.assign(scratch_new_.size(), {kNoTet, 0});
    if (!replace()) throw std::logic_error("dtlab: the first tetrahedron does not close up");
    roots_ = scratch_created_;
  }

  Outcome insert(VertexId p) {
    using Clock = std::chrono::steady_clock;
    const auto t0 = Clock::now();
    std::array<int, 4> o{};
    const TetId t = locate(p, o);
    const auto t1 = Clock::now();
    stats_.seconds.location += std::chrono::duration<double>(t1 - t0).count();
    if (t == kNoTet) return Outcome::Abandoned;

    const Outcome split = subdivide(t, p, o);
    const auto t2 = Clock::now();
    stats_.seconds.subdivision += std::chrono::duration<double>(t2 - t1).count();
    if (split != Outcome::Inserted) return split;

    const bool complete = legalize(p);
    stats_.seconds.legalization += std::chrono::duration<double>(Clock::now() - t2).count();
    return complete ? Outcome::Inserted : Outcome::Abandoned;
  }

  // Live finite tetrahedra whose vertices are all below `vertex_limit` (so not auxiliary). Each
  // set of duplicate points is named by its lowest input index, whichever of them was inserted,
  // so that the output does not depend on the insertion order.
  std::vector<Tetrahedron> finite_tetrahedra(VertexId vertex_limit) const {
    std::vector<VertexId> representative;
    if (!duplicates_.empty()) {
      representative.resize(points_.size());
      for (std::size_t i = 0; i < representative.size(); ++i)
        representative[i] = static_cast<VertexId>(i);
      for (const auto& [duplicate, vertex] : duplicates_) {
        representative[vertex] = std::min(representative[vertex], duplicate);
      }
    }
    std::vector<Tetrahedron> out;
    const std::size_t n = tets_.size();
    for (std::size_t i = 0; i < n; ++i) {
      const Tet& t = tets_[static_cast<TetId>(i)];
      if (!t.alive.load(std::memory_order_acquire) || t.is_infinite()) continue;
      if (t.vertex[0] >= vertex_limit || t.vertex[1] >= vertex_limit ||
          t.vertex[2] >= vertex_limit || t.vertex[3] >= vertex_limit) {
        continue;
      }
      out.push_back(t.vertex);
      if (!representative.empty()) {
        for (auto& v : out.back()) v = representative[v];
      }
    }
    return out;
  }

  [[nodiscard]] std::uint64_t dag_nodes() const { return tets_.size(); }
  [[nodiscard]] std::uint64_t predicate_calls() const { return predicate_calls_; }
  [[nodiscard]] std::uint64_t location_steps() const { return location_steps_; }

 private:
  using Quad = std::array<VertexId, 4>;

  // Only finite vertices are looked up: the infinite vertex never reaches a point lookup.
  const Point3& point(VertexId v) const { return points_[v]; }

  int orient(const Quad& q) {
    ++predicate_calls_;
    int inf = 3;
    while (inf >= 0 && q[static_cast<std::size_t>(inf)] != kInfiniteVertex) --inf;
    if (inf < 0) return K::orient3d(point(q[0]), point(q[1]), point(q[2]), point(q[3]));
    // orient(q) = -orient(q with inf -> O); move O to the last slot (a swap: one more sign).
    Quad r = q;
    std::swap(r[static_cast<std::size_t>(inf)], r[3]);
    const int s = origin_is_point_
                      ? K::orient3d(point(r[0]), point(r[1]), point(r[2]), origin_)
                      : K::orient3d_centroid(point(r[0]), point(r[1]), point(r[2]), first_);
    return inf == 3 ? -s : s;
  }

  // Orientation of tetrahedron t with its vertex at position i replaced by v.
  int orient_replaced(const Tet& t, int i, VertexId v) {
    Quad q = t.vertex;
    q[static_cast<std::size_t>(i)] = v;
    return orient(q);
  }

  // Whether p lies strictly inside the (perturbed) circumsphere of t.
  bool in_conflict(const Tet& t, VertexId p) {
    ++predicate_calls_;
    const int inf = t.index_of(kInfiniteVertex);
    const auto& v = t.vertex;
    if (inf < 0) {
      return predicates::insphere_perturbed<K>(point(v[0]), point(v[1]), point(v[2]), point(v[3]),
                                               point(p)) > 0;
    }
    // kFaceVertex lists the face with the opposite (infinite) vertex on its negative side;
    // reversed, the infinite vertex lies on the positive side, as the predicate expects.
    const auto& f = kFaceVertex[static_cast<std::size_t>(inf)];
    return predicates::infinite_insphere_perturbed<K>(
               point(v[static_cast<std::size_t>(f[0])]), point(v[static_cast<std::size_t>(f[2])]),
               point(v[static_cast<std::size_t>(f[1])]), point(p)) > 0;
  }

  // p inside or on the boundary of t; `o` receives the four orientations.
  bool contains(TetId t, VertexId p, std::array<int, 4>& o) {
    const Tet& tet = tets_[t];
    for (int i = 0; i < 4; ++i) {
      o[static_cast<std::size_t>(i)] = orient_replaced(tet, i, p);
      if (o[static_cast<std::size_t>(i)] < 0) return false;
    }
    return true;
  }

  // Descends the history DAG from the roots to the live tetrahedron that contains p.
  TetId locate(VertexId p, std::array<int, 4>& o) {
    TetId t = kNoTet;
    for (const TetId r : roots_) {
      if (contains(r, p, o)) {
        t = r;
        break;
      }
    }
    std::uint64_t steps = 0;
    bool tested = true;  // whether `o` holds t's orientations
    while (t != kNoTet && !tets_[t].alive.load(std::memory_order_acquire)) {
      if (++steps > options_.max_location_steps) return kNoTet;
      const Tet& node = tets_[t];
      int count = 0;
      while (count < 4 && node.child[static_cast<std::size_t>(count)].load(
                              std::memory_order_acquire) != kNoTet) {
        ++count;
      }
      // The children cover their parent: when all but the last fail, p is in the last one
      // (verified at the leaf, which only an inexact kernel can fail).
      TetId next = node.child[static_cast<std::size_t>(count - 1)].load(std::memory_order_acquire);
      tested = false;
      for (int k = 0; k + 1 < count; ++k) {
        const TetId c = node.child[static_cast<std::size_t>(k)].load(std::memory_order_acquire);
        if (contains(c, p, o)) {
          next = c;
          tested = true;
          break;
        }
      }
      t = next;
    }
    location_steps_ += steps;
    if (t != kNoTet && !tested && !contains(t, p, o)) return kNoTet;
    return t;
  }

  // Adds to scratch_new_ tetrahedron t's copy with the vertex at `position` replaced by v. Its
  // face `position` is t's face `position`: replace() links it without searching.
  void push_replaced(TetId t, int position, VertexId v, int parent) {
    Quad q = tets_[t].vertex;
    q[static_cast<std::size_t>(position)] = v;
    scratch_new_.push_back(q);
    scratch_parent_.push_back(parent);
    scratch_source_.push_back({t, position});
  }

  // 1->4 inside, 2->6 on a face, k->2k on an edge; a point on a vertex is a duplicate.
  Outcome subdivide(TetId t, VertexId p, const std::array<int, 4>& o) {
    scratch_old_.clear();
    scratch_new_.clear();
    scratch_parent_.clear();
    scratch_source_.clear();
    const int zeros = static_cast<int>(std::count(o.begin(), o.end(), 0));
    if (zeros == 0) {
      scratch_old_.push_back(t);
      for (int i = 0; i < 4; ++i) push_replaced(t, i, p, 0);
    } else if (zeros == 1) {
      const int i0 = static_cast<int>(std::find(o.begin(), o.end(), 0) - o.begin());
      const FaceRef across = tets_[t].neighbor[static_cast<std::size_t>(i0)];
      const TetId t2 = ref_tet(across);
      scratch_old_ = {t, t2};
      for (int i = 0; i < 4; ++i) {
        if (i != i0) push_replaced(t, i, p, 0);
        if (i != ref_face(across)) push_replaced(t2, i, p, 1);
      }
    } else if (zeros == 2) {
      std::array<int, 2> edge{};
      int k = 0;
      for (int i = 0; i < 4; ++i) {
        if (o[static_cast<std::size_t>(i)] != 0) edge[static_cast<std::size_t>(k++)] = i;
      }
      const VertexId a = tets_[t].vertex[static_cast<std::size_t>(edge[0])];
      const VertexId b = tets_[t].vertex[static_cast<std::size_t>(edge[1])];
      if (!collect_edge_ring(t, a, b)) return Outcome::Abandoned;
      for (std::size_t r = 0; r < scratch_old_.size(); ++r) {
        const Tet& ring_tet = tets_[scratch_old_[r]];
        push_replaced(scratch_old_[r], ring_tet.index_of(a), p, static_cast<int>(r));
        push_replaced(scratch_old_[r], ring_tet.index_of(b), p, static_cast<int>(r));
      }
    } else if (zeros == 3) {
      const int m = static_cast<int>(
          std::find_if(o.begin(), o.end(), [](int s) { return s != 0; }) - o.begin());
      const VertexId v = tets_[t].vertex[static_cast<std::size_t>(m)];
      if (v != kInfiniteVertex && points_[v] == points_[p]) {
        duplicates_.push_back({p, v});
        return Outcome::Duplicate;
      }
      return Outcome::Abandoned;  // inconsistent signs from an inexact kernel
    } else {
      return Outcome::Abandoned;
    }
    if (!replace()) return Outcome::Abandoned;
    stack_.assign(scratch_created_.begin(), scratch_created_.end());
    return Outcome::Inserted;
  }

  // All tetrahedra around edge ab, starting from t, into scratch_old_.
  bool collect_edge_ring(TetId t, VertexId a, VertexId b) {
    scratch_old_.clear();
    TetId current = t;
    TetId previous = kNoTet;
    for (std::size_t guard = 0; guard < 100000; ++guard) {
      scratch_old_.push_back(current);
      const Tet& tet = tets_[current];
      TetId next = kNoTet;
      for (int i = 0; i < 4; ++i) {
        const VertexId v = tet.vertex[static_cast<std::size_t>(i)];
        if (v == a || v == b) continue;
        const TetId candidate = ref_tet(tet.neighbor[static_cast<std::size_t>(i)]);
        if (candidate != previous) {
          next = candidate;
          break;
        }
      }
      previous = current;
      current = next;
      if (current == t) return true;
      if (current == kNoTet) return false;
    }
    return false;
  }

  // Legalizes the faces opposite p of the tetrahedra on stack_; false when the flip bound was hit.
  bool legalize(VertexId p) {
    std::uint64_t flips = 0;
    while (!stack_.empty()) {
      const TetId t = stack_.back();
      stack_.pop_back();
      const Tet& tet = tets_[t];
      if (!tet.alive.load(std::memory_order_acquire)) continue;
      const int ip = tet.index_of(p);
      const FaceRef across = tet.neighbor[static_cast<std::size_t>(ip)];
      const TetId t2 = ref_tet(across);
      const VertexId y = tets_[t2].vertex[static_cast<std::size_t>(ref_face(across))];
      if (!in_conflict(tets_[t2], p)) continue;
      if (++flips > options_.max_flips_per_insertion) {
        stack_.clear();
        return false;
      }
      // Where does segment p-y pass face F = t minus p? o[m] is the orientation of t with F's
      // vertex m replaced by y: all positive, through F's interior; one negative, outside the
      // edge opposite m; one zero, through that edge (p, y and the edge coplanar).
      int negative = -1;
      int zero = -1;
      int negatives = 0;
      int zeros = 0;
      std::array<int, 4> o{};
      for (int m = 0; m < 4; ++m) {
        if (m == ip) continue;
        o[static_cast<std::size_t>(m)] = orient_replaced(tet, m, y);
        if (o[static_cast<std::size_t>(m)] < 0) {
          negative = m;
          ++negatives;
        } else if (o[static_cast<std::size_t>(m)] == 0) {
          zero = m;
          ++zeros;
        }
      }
      if (negatives == 0 && zeros == 0) {
        flip23(t, t2, ip, y);
      } else if (negatives == 1 && zeros == 0) {
        flip32(t, t2, ip, negative, y);
      } else if (zeros == 1 && negatives == 0) {
        flip44(t, t2, ip, zero, y);
      }
      // Otherwise the face is not flippable now; a later flip removes it (Joe 1991).
    }
    return true;
  }

  // S23: abcp + abcy -> three tetrahedra around the new edge py.
  void flip23(TetId t, TetId t2, int ip, VertexId y) {
    begin_flip({t, t2});
    for (int m = 0; m < 4; ++m) {
      if (m != ip) push_replaced(t, m, y, -1);
    }
    if (finish_flip()) ++stats_.flips.s23;
  }

  // S32: the reflex edge opposite F's vertex `m` has exactly three tetrahedra (t, t2 and the one
  // across t's face m, which must contain y); they become two around the face (p, y, F[m]).
  void flip32(TetId t, TetId t2, int ip, int m, VertexId y) {
    const FaceRef across = tets_[t].neighbor[static_cast<std::size_t>(m)];
    const TetId t3 = ref_tet(across);
    if (tets_[t3].vertex[static_cast<std::size_t>(ref_face(across))] != y) return;
    begin_flip({t, t2, t3});
    for (int j = 0; j < 4; ++j) {
      if (j != ip && j != m) push_replaced(t, j, y, -1);
    }
    if (finish_flip()) ++stats_.flips.s32;
  }

  // S44 (S22 on the hull): p, y and the edge opposite F's vertex `m` are coplanar and the edge has
  // exactly four tetrahedra; the edge is replaced by py.
  void flip44(TetId t, TetId t2, int ip, int m, VertexId y) {
    const Tet& tet = tets_[t];
    const VertexId vm = tet.vertex[static_cast<std::size_t>(m)];
    const FaceRef across3 = tet.neighbor[static_cast<std::size_t>(m)];
    const TetId t3 = ref_tet(across3);
    const VertexId w = tets_[t3].vertex[static_cast<std::size_t>(ref_face(across3))];
    const int m2 = tets_[t2].index_of(vm);
    const FaceRef across4 = tets_[t2].neighbor[static_cast<std::size_t>(m2)];
    const TetId t4 = ref_tet(across4);
    if (tets_[t4].vertex[static_cast<std::size_t>(ref_face(across4))] != w) return;
    std::array<int, 2> edge{};
    int k = 0;
    for (int j = 0; j < 4; ++j) {
      if (j != ip && j != m) edge[static_cast<std::size_t>(k++)] = j;
    }
    // The two new tetrahedra on w's side must be positively oriented too.
    const Tet& tet3 = tets_[t3];
    const int e0 = tet3.index_of(tet.vertex[static_cast<std::size_t>(edge[0])]);
    const int e1 = tet3.index_of(tet.vertex[static_cast<std::size_t>(edge[1])]);
    if (orient_replaced(tet3, e0, y) <= 0 || orient_replaced(tet3, e1, y) <= 0) return;
    begin_flip({t, t2, t3, t4});
    push_replaced(t, edge[0], y, -1);
    push_replaced(t, edge[1], y, -1);
    push_replaced(t3, e0, y, -1);
    push_replaced(t3, e1, y, -1);
    if (!finish_flip()) return;
    if (vm == kInfiniteVertex || w == kInfiniteVertex) {
      ++stats_.flips.s22;
    } else {
      ++stats_.flips.s44;
    }
  }

  void begin_flip(std::initializer_list<TetId> old) {
    scratch_old_.assign(old.begin(), old.end());
    scratch_new_.clear();
    scratch_parent_.clear();
    scratch_source_.clear();
  }
  // False when the flip cannot be applied (inexact kernel only); the mesh is then unchanged.
  bool finish_flip() {
    if (!replace()) return false;
    stack_.insert(stack_.end(), scratch_created_.begin(), scratch_created_.end());
    return true;
  }

  // A face's vertex set as two integers (sorted ids): cheap to compare.
  struct FaceKey {
    std::uint64_t high;
    std::uint32_t low;
    bool operator==(const FaceKey&) const = default;
  };
  struct OpenFace {
    FaceKey key;
    FaceRef ref;  // an existing tetrahedron's face, or (is_new) 4 * new index + face
    bool is_new;
  };
  struct FaceMatch {
    FaceRef ref;
    bool is_new;
    bool set;
  };

  static FaceKey face_key(const Quad& v, int f) {
    const auto& fv = kFaceVertex[static_cast<std::size_t>(f)];
    VertexId a = v[static_cast<std::size_t>(fv[0])];
    VertexId b = v[static_cast<std::size_t>(fv[1])];
    VertexId c = v[static_cast<std::size_t>(fv[2])];
    if (a > b) std::swap(a, b);
    if (b > c) std::swap(b, c);
    if (a > b) std::swap(a, b);
    return {(static_cast<std::uint64_t>(a) << 32) | b, c};
  }

  // Replaces the tetrahedra scratch_old_ by scratch_new_ (same region), linking the new ones to
  // each other and to the outside by their shared faces. scratch_parent_[j] is the index in
  // scratch_old_ of new tetrahedron j's only DAG parent, or -1 when it is a child of every old one.
  // Every face is matched before anything is written: when the new tetrahedra do not close up
  // (only possible with an inexact kernel's contradictory signs) nothing changes and the result
  // is false. The new ids land in scratch_created_.
  bool replace() {
    auto is_old = [&](TetId t) {
      return std::find(scratch_old_.begin(), scratch_old_.end(), t) != scratch_old_.end();
    };
    // Direct links: new tetrahedron j's face `position` is its source's face `position`.
    matched_.assign(4 * scratch_new_.size(), FaceMatch{0, false, false});
    claimed_.clear();
    for (std::size_t j = 0; j < scratch_new_.size(); ++j) {
      const auto [source, position] = scratch_source_[j];
      if (source == kNoTet) continue;
      const FaceRef outside = tets_[source].neighbor[static_cast<std::size_t>(position)];
      if (is_old(ref_tet(outside))) continue;
      matched_[4 * j + static_cast<std::size_t>(position)] = {outside, false, true};
      claimed_.push_back(face_ref(source, position));
    }
    // The other faces of the region's boundary, seen from outside.
    open_faces_.clear();
    for (const TetId o : scratch_old_) {
      const Tet& tet = tets_[o];
      for (int f = 0; f < 4; ++f) {
        const FaceRef outside = tet.neighbor[static_cast<std::size_t>(f)];
        if (is_old(ref_tet(outside))) continue;
        if (std::find(claimed_.begin(), claimed_.end(), face_ref(o, f)) != claimed_.end()) continue;
        open_faces_.push_back({face_key(tet.vertex, f), outside, false});
      }
    }
    // Match the remaining new faces before writing anything.
    for (std::size_t j = 0; j < scratch_new_.size(); ++j) {
      for (int f = 0; f < 4; ++f) {
        const auto self = static_cast<FaceRef>(4 * j + static_cast<std::size_t>(f));
        if (matched_[self].set) continue;
        const auto key = face_key(scratch_new_[j], f);
        const auto match = std::find_if(open_faces_.begin(), open_faces_.end(),
                                        [&](const OpenFace& of) { return of.key == key; });
        if (match == open_faces_.end()) {
          open_faces_.push_back({key, self, true});
          continue;
        }
        matched_[self] = {match->ref, match->is_new, true};
        if (match->is_new) matched_[match->ref] = {self, true, true};
        *match = open_faces_.back();
        open_faces_.pop_back();
      }
    }
    if (!open_faces_.empty()) return false;

    scratch_created_.clear();
    for (const Quad& q : scratch_new_) {
      const TetId id = tets_.allocate();
      Tet& tet = tets_[id];
      tet.vertex = q;
      for (auto& c : tet.child) c.store(kNoTet, std::memory_order_relaxed);
      scratch_created_.push_back(id);
    }
    for (std::size_t j = 0; j < scratch_created_.size(); ++j) {
      Tet& tet = tets_[scratch_created_[j]];
      for (int f = 0; f < 4; ++f) {
        const FaceMatch m = matched_[4 * j + static_cast<std::size_t>(f)];
        if (m.is_new) {
          tet.neighbor[static_cast<std::size_t>(f)] =
              face_ref(scratch_created_[ref_tet(m.ref)], ref_face(m.ref));
        } else {
          tet.neighbor[static_cast<std::size_t>(f)] = m.ref;
          tets_[ref_tet(m.ref)].neighbor[static_cast<std::size_t>(ref_face(m.ref))] =
              face_ref(scratch_created_[j], f);
        }
      }
    }
    // History: children first (release), then the old tetrahedra die, then the new ones live.
    for (std::size_t r = 0; r < scratch_old_.size(); ++r) {
      Tet& old = tets_[scratch_old_[r]];
      int slot = 0;
      for (std::size_t j = 0; j < scratch_created_.size(); ++j) {
        if (scratch_parent_[j] == -1 || scratch_parent_[j] == static_cast<int>(r)) {
          old.child[static_cast<std::size_t>(slot++)].store(scratch_created_[j],
                                                            std::memory_order_release);
        }
      }
      old.alive.store(false, std::memory_order_release);
    }
    for (const TetId id : scratch_created_) tets_[id].alive.store(true, std::memory_order_release);
    return true;
  }

  const std::vector<Point3>& points_;
  const TriangulateOptions& options_;
  TriangulationStats& stats_;
  predicates::Tetrahedron4 first_{};  // O is the centroid of these four points...
  Point3 origin_{0, 0, 0};            // ...or this point, strictly inside them, when
  bool origin_is_point_ = false;      // origin_is_point_
  TetStore tets_;
  std::vector<TetId> roots_;
  std::uint64_t predicate_calls_ = 0;
  std::uint64_t location_steps_ = 0;
  std::vector<std::pair<VertexId, VertexId>> duplicates_;  // (skipped point, its vertex)

  // Scratch buffers reused across insertions (no allocation per insertion once warm).
  std::vector<TetId> scratch_old_;
  std::vector<Quad> scratch_new_;
  std::vector<int> scratch_parent_;
  std::vector<TetId> scratch_created_;
  std::vector<OpenFace> open_faces_;
  std::vector<FaceMatch> matched_;
  std::vector<FaceRef> claimed_;
  std::vector<std::pair<TetId, int>> scratch_source_;  // (old tetrahedron, replaced position)
  std::vector<TetId> stack_;
};

}  // namespace dtlab::engine
