#include "mesh/shared_mesh.hpp"

#include <algorithm>
#include <span>

#include "support/parallel_ranges.hpp"
#include "support/populate_pages.hpp"

namespace dtlab::engine {
namespace {

// Blocks appended to the output after one mapping of its pages (a block's kept tetrahedra take
// about 1 MiB of output in a walk-mode run).
constexpr std::size_t kOutputGroup = 2;

}  // namespace

// Each thread takes a contiguous share of the store's blocks; a block's tetrahedra go after those
// of every lower block. Releasing, the blocks are packed in place, then appended and let go one at
// a time. Not releasing (the store is read again), per-block counts come first, and the copy goes
// a group of `threads` blocks at a time into the output, grown (and zeroed, by the calling
// thread) a group at a time. Either way the output and the whole store never coexist.
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
    // Each thread packs its share of the blocks in place (TetStore::pack_quads); then one thread
    // appends them block by block, each let go once appended. An append constructs the copies
    // from the packed ones: a resize would first zero the output on this thread alone (that and
    // the blocks' copy groups made the step slower on two threads than on one).
    std::vector<std::span<const Quad>> packed(blocks);
    over_blocks(0, blocks, [&](std::size_t block) {
      const auto [begin, end] = slots_of(block);
      packed[block] = tets.pack_quads(block, end - begin, kept, [&](VertexId v) {
        return representative.empty() ? v : representative[v];
      });
    });
    std::size_t total = 0;
    for (const auto& quads : packed) total += quads.size();
    std::vector<Tetrahedron> out;
    out.reserve(total);
    // A group of blocks at a time: the output's pages for the group mapped by the threads at once
    // (populate_pages), then the group appended, each block let go once appended. Mapping the
    // whole output first would make it coexist with the whole store (107 bytes a point more at
    // the run's peak); a group's pages at a time keep it growing as the store shrinks.
    for (std::size_t group = 0; group < blocks; group += kOutputGroup) {
      const std::size_t group_end = std::min(blocks, group + kOutputGroup);
      std::size_t count = 0;
      for (std::size_t block = group; block < group_end; ++block) count += packed[block].size();
      populate_pages(out.data() + out.size(), count * sizeof(Tetrahedron), parts);
      for (std::size_t block = group; block < group_end; ++block) {
        out.insert(out.end(), packed[block].begin(), packed[block].end());
        const auto [begin, end] = slots_of(block);
        if (begin < end) tets.release_block_of(static_cast<TetId>(begin));
      }
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
