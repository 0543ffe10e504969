#include "mesh/shared_mesh.hpp"

#include <unistd.h>

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <new>
#include <span>
#include <type_traits>

#include "support/move_pages.hpp"
#include "support/parallel_ranges.hpp"

namespace dtlab::engine {

// Each thread takes a contiguous share of the store's blocks; a block's tetrahedra go after those
// of every lower block. Releasing, the blocks are packed in place, then moved into the output and
// let go one at a time. Not releasing (the store is read again), per-block counts come first, and
// the copy goes a group of `threads` blocks at a time into the output, grown (and zeroed, by the
// calling thread) a group at a time. Either way the output and the whole store never coexist.
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
  if (release) {
    // Each thread packs its share of the blocks in place (TetStore::pack_quads) and shifts each
    // block's quads to the offset within a page of their place in the output; then one thread
    // moves them there block by block (move_by_pages: their whole pages change places, the
    // partial pages at either end are copied; the moves take the process's memory map one at a
    // time anyway) and lets each block go. Only the partial pages at the blocks' ends (two a
    // block at most) are faulted in, and no store page that moved is freed: at 1M points on two
    // threads the old step (the output's pages mapped by both threads, each block copied into them,
    // then unmapped) took 80-90 ms of it (performance-log.md, thirteenth session).
    std::vector<std::span<Quad>> packed(blocks);
    over_blocks(0, blocks, [&](std::size_t block) {
      const auto [begin, end] = slots_of(block);
      packed[block] = tets.pack_quads(block, end - begin, kept, [&](VertexId v) {
        return representative.empty() ? v : representative[v];
      });
    });
    std::vector<std::size_t> block_start(blocks + 1, 0);
    for (std::size_t b = 0; b < blocks; ++b) {
      block_start[b + 1] = block_start[b] + packed[b].size();
    }
    const std::size_t total = block_start[blocks];
    std::vector<Tetrahedron> out;
    out.reserve(total);
    char* const output = reinterpret_cast<char*>(out.data());
    const auto page = static_cast<std::uintptr_t>(sysconf(_SC_PAGESIZE));
    // Room for the shift (less than a page): a block's quads take at most half of it (16 bytes a
    // slot of 32 or more), and the other half (1 MiB) holds a page of up to 64 KiB.
    static_assert(2 * sizeof(Quad) <= sizeof(Tet) &&
                  TetStore::kBlockSize * sizeof(Quad) >= std::size_t{1} << 16);
    over_blocks(0, blocks, [&](std::size_t block) {
      if (packed[block].empty()) return;
      char* const at = reinterpret_cast<char*>(packed[block].data());
      const std::uintptr_t shift =
          reinterpret_cast<std::uintptr_t>(output + block_start[block] * sizeof(Quad)) % page;
      std::memmove(at + shift, at, packed[block].size_bytes());
      packed[block] = {std::launder(reinterpret_cast<Quad*>(at + shift)), packed[block].size()};
    });
    for (std::size_t block = 0; block < blocks; ++block) {
      move_by_pages(reinterpret_cast<char*>(packed[block].data()),
                    output + block_start[block] * sizeof(Quad), packed[block].size_bytes());
      const auto [begin, end] = slots_of(block);
      if (begin < end) tets.release_block_of(static_cast<TetId>(begin));
    }
    // The quads are in the output's reserved room; inserted over themselves (a memmove onto the
    // same bytes) they become the vector's items without a write of other values.
    static_assert(std::is_same_v<Tetrahedron, Quad> && std::is_trivially_copyable_v<Quad>);
    const Tetrahedron* const moved = std::launder(reinterpret_cast<const Tetrahedron*>(output));
    out.insert(out.end(), moved, moved + total);
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
