#pragma once
// What all inserting threads share: the points, the tetrahedron store (mesh and DAG), the DAG
// roots and the interior point O. Written by one thread in start(), read-only afterwards except
// for the store, whose records follow the locking rules of docs/design.md.
#include <algorithm>
#include <atomic>
#include <thread>
#include <utility>
#include <vector>

#include "dtlab/engine/tet_mesh.hpp"
#include "dtlab/engine/triangulate.hpp"
#include "dtlab/predicates/kernels.hpp"

namespace dtlab::engine {

struct SharedMesh {
  explicit SharedMesh(const std::vector<Point3>& input) : points(input) {}

  const std::vector<Point3>& points;
  mutable TetStore tets;  // mutable: take_finite_tetrahedra releases it
  std::vector<TetId> roots;
  predicates::Tetrahedron4 first{};  // O is the centroid of these four points...
  Point3 origin{0, 0, 0};            // ...or this point, strictly inside them, when
  bool origin_is_point = false;      // origin_is_point

  // Live finite tetrahedra whose vertices are all below `vertex_limit` (so not auxiliary), in
  // slot order. Each set of duplicate points is named by its lowest input index, whichever of
  // them was inserted, so that the output does not depend on the insertion order.
  std::vector<Tetrahedron> finite_tetrahedra(
      VertexId vertex_limit, const std::vector<std::pair<VertexId, VertexId>>& duplicates,
      int threads = 1) const {
    return collect(vertex_limit, duplicates, false, threads);
  }
  // The same, releasing the store's blocks as they are read: the output does not coexist with
  // the whole store (at 1M uniform points it is 108 bytes per point). The store is unusable
  // afterwards; the last thing a run does.
  std::vector<Tetrahedron> take_finite_tetrahedra(
      VertexId vertex_limit, const std::vector<std::pair<VertexId, VertexId>>& duplicates,
      int threads = 1) {
    return collect(vertex_limit, duplicates, true, threads);
  }

 private:
  // The store's blocks are counted, then copied, by `threads` threads: each takes its share of
  // the blocks, and a block's tetrahedra go after those of every lower block. The copy goes a
  // group of `threads` blocks at a time: the output grows (and is paged in) by one group while
  // the group's blocks are let go, so the two never coexist whole.
  std::vector<Tetrahedron> collect(VertexId vertex_limit,
                                   const std::vector<std::pair<VertexId, VertexId>>& duplicates,
                                   bool release, int threads) const {
    std::vector<VertexId> representative;
    if (!duplicates.empty()) {
      representative.resize(points.size());
      for (std::size_t i = 0; i < representative.size(); ++i) {
        representative[i] = static_cast<VertexId>(i);
      }
      for (const auto& [duplicate, vertex] : duplicates) {
        representative[vertex] = std::min(representative[vertex], duplicate);
      }
    }
    auto kept = [&](TetId id) {
      const Tet& t = tets[id];
      return tets.is_alive(id, std::memory_order_acquire) && !t.is_infinite() &&
             t.vertex[0] < vertex_limit && t.vertex[1] < vertex_limit &&
             t.vertex[2] < vertex_limit && t.vertex[3] < vertex_limit;
    };
    const std::size_t n = tets.size();
    const std::size_t blocks = (n + TetStore::kBlockSize - 1) / TetStore::kBlockSize;
    const std::size_t parts = std::clamp<std::size_t>(static_cast<std::size_t>(threads), 1,
                                                      std::max<std::size_t>(blocks, 1));
    auto slots_of = [&](std::size_t block) {
      return std::pair{block * TetStore::kBlockSize,
                       std::min(n, (block + 1) * TetStore::kBlockSize)};
    };
    // Runs work(block) for blocks [begin, end), `parts` threads each over a contiguous share.
    auto over_blocks = [&](std::size_t begin, std::size_t end, auto work) {
      const std::size_t count = end - begin;
      const std::size_t used = std::min(parts, count);
      auto share = [&](std::size_t part) {
        for (std::size_t b = begin + count * part / used; b < begin + count * (part + 1) / used;
             ++b) {
          work(b);
        }
      };
      std::vector<std::thread> helpers;
      for (std::size_t part = 0; part + 1 < used; ++part) helpers.emplace_back(share, part);
      if (used > 0) share(used - 1);
      for (std::thread& h : helpers) h.join();
    };
    // first[b]: where block b's first kept tetrahedron goes.
    std::vector<std::size_t> first(blocks + 1, 0);
    over_blocks(0, blocks, [&](std::size_t block) {
      const auto [begin, end] = slots_of(block);
      std::size_t count = 0;
      for (std::size_t i = begin; i < end; ++i) count += kept(static_cast<TetId>(i)) ? 1 : 0;
      first[block + 1] = count;
    });
    for (std::size_t b = 0; b < blocks; ++b) first[b + 1] += first[b];
    std::vector<Tetrahedron> out;
    out.reserve(first[blocks]);  // exactly the size needed: no growth while blocks are let go
    for (std::size_t group = 0; group < blocks; group += parts) {
      const std::size_t group_end = std::min(blocks, group + parts);
      out.resize(first[group_end]);
      over_blocks(group, group_end, [&](std::size_t block) {
        const auto [begin, end] = slots_of(block);
        std::size_t at = first[block];
        for (std::size_t i = begin; i < end; ++i) {
          if (!kept(static_cast<TetId>(i))) continue;
          Tetrahedron& t = out[at++];
          t = tets[static_cast<TetId>(i)].vertex;
          if (!representative.empty()) {
            for (auto& v : t) v = representative[v];
          }
        }
        if (release && begin < end) tets.release_block_of(static_cast<TetId>(begin));
      });
    }
    return out;
  }
};

// Neighbour references are read by walking threads that hold no lock, so they are written with
// release (after the tetrahedron they name is complete) and read with acquire (plain moves on
// x86).
inline FaceRef load_neighbor(const Tet& tet, int f) {
  return std::atomic_ref<FaceRef>(const_cast<FaceRef&>(tet.neighbor[static_cast<std::size_t>(f)]))
      .load(std::memory_order_acquire);
}
inline void store_neighbor(Tet& tet, int f, FaceRef r) {
  std::atomic_ref<FaceRef>(tet.neighbor[static_cast<std::size_t>(f)])
      .store(r, std::memory_order_release);
}

// What a lock refused during legalization leads to: GiveUp (undo the insertion: detect, prevent),
// Continue (a burglary victim whose part of the mesh is intact) or Stop (a burglary victim whose
// part was changed: the rest of its legalization is dropped and marked suspicious).
enum class Resume { GiveUp, Continue, Stop };

// The sequential engine's synchronization: none. Every hook is an empty inline function, so the
// sequential build pays nothing for the parallel methods' policy slots.
struct NoSync {
  static constexpr bool kLocks = false;
  bool acquire(TetId /*t*/) { return true; }  // false: give the insertion up
  void before_write(TetId /*t*/) {}           // undo log entry before the first write to t
  void created(TetId /*t*/, bool /*last_write*/ = false) {}  // a new tetrahedron, owned from birth
  void commit() {}                                           // the insertion is complete: unlock
  void rollback() {}                                         // give up: undo everything, unlock
  void killed(TetId /*t*/, bool /*last_write*/ = false) {}   // t dies by this thread's write
  Resume resume() { return Resume::GiveUp; }  // a lock was refused during legalization
  void mark_suspicious(TetId /*t*/) {}        // burglary: for the post-check
};

}  // namespace dtlab::engine
