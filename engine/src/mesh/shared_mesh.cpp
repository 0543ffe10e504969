#include "mesh/shared_mesh.hpp"

#include <algorithm>

#include "support/parallel_ranges.hpp"

namespace dtlab::engine {

// Each thread takes a contiguous share of the store's blocks; a block's tetrahedra go after those
// of every lower block (per-block counts first). The copy goes a group of `threads` blocks at a
// time: the output grows (and is paged in, by the calling thread: resize zeroes it) by one group
// while the group's blocks are let go, so the two never coexist whole.
std::vector<Tetrahedron> SharedMesh::collect(
    VertexId vertex_limit, const std::vector<std::pair<VertexId, VertexId>>& duplicates,
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
           t.vertex[0] < vertex_limit && t.vertex[1] < vertex_limit && t.vertex[2] < vertex_limit &&
           t.vertex[3] < vertex_limit;
  };
  const std::size_t n = tets.size();
  const std::size_t blocks = (n + TetStore::kBlockSize - 1) / TetStore::kBlockSize;
  const int parts = std::max(threads, 1);
  auto slots_of = [&](std::size_t block) {
    return std::pair{block * TetStore::kBlockSize, std::min(n, (block + 1) * TetStore::kBlockSize)};
  };
  // Runs work(block) for the blocks [begin, end), the threads each over a contiguous share.
  auto over_blocks = [&](std::size_t begin, std::size_t end, auto work) {
    in_parallel_ranges(
        end - begin, parts,
        [&](std::size_t from, std::size_t to, std::size_t) {
          for (std::size_t b = begin + from; b < begin + to; ++b) work(b);
        },
        1);
  };
  auto copy_kept = [&](std::size_t i, Tetrahedron& t) {
    t = tets[static_cast<TetId>(i)].vertex;
    if (!representative.empty()) {
      for (auto& v : t) v = representative[v];
    }
  };
  if (parts == 1 && !tets.has_children()) {
    // One thread: one pass, into room for every slot (reserved, so untouched beyond what the
    // kept tetrahedra fill). Two passes, counting first, are what lets threads write their
    // shares in place; alone they would read the store twice. Not in DAG mode, where most slots
    // are dead history and room for all of them would be a reservation some 8 times the output.
    std::vector<Tetrahedron> out;
    out.reserve(n);
    for (std::size_t block = 0; block < blocks; ++block) {
      const auto [begin, end] = slots_of(block);
      for (std::size_t i = begin; i < end; ++i) {
        if (kept(static_cast<TetId>(i))) copy_kept(i, out.emplace_back());
      }
      if (release && begin < end) tets.release_block_of(static_cast<TetId>(begin));
    }
    return out;
  }
  // block_start[b]: where block b's first kept tetrahedron goes.
  std::vector<std::size_t> block_start(blocks + 1, 0);
  over_blocks(0, blocks, [&](std::size_t block) {
    const auto [begin, end] = slots_of(block);
    std::size_t count = 0;
    for (std::size_t i = begin; i < end; ++i) count += kept(static_cast<TetId>(i)) ? 1 : 0;
    block_start[block + 1] = count;
  });
  for (std::size_t b = 0; b < blocks; ++b) block_start[b + 1] += block_start[b];
  std::vector<Tetrahedron> out;
  out.reserve(block_start[blocks]);  // exactly the size needed: no growth while blocks are let go
  const auto group_size = static_cast<std::size_t>(parts);
  for (std::size_t group = 0; group < blocks; group += group_size) {
    const std::size_t group_end = std::min(blocks, group + group_size);
    out.resize(block_start[group_end]);
    over_blocks(group, group_end, [&](std::size_t block) {
      const auto [begin, end] = slots_of(block);
      std::size_t at = block_start[block];
      for (std::size_t i = begin; i < end; ++i) {
        if (kept(static_cast<TetId>(i))) copy_kept(i, out[at++]);
      }
      if (release && begin < end) tets.release_block_of(static_cast<TetId>(begin));
    });
  }
  return out;
}

}  // namespace dtlab::engine
