// A test of the engine's internals: it includes headers from engine/src (dtlab_internal_test).
// move_by_pages moves the whole pages of a range where the source and the destination share their
// offset within a page, copies the partial pages at either end, and copies everything otherwise:
// the destination holds the source's bytes either way.
#include <gtest/gtest.h>
#include <sys/mman.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <new>
#include <vector>

#include "support/move_pages.hpp"

namespace dtlab::test {
namespace {

struct Mapping {
  explicit Mapping(std::size_t size) : bytes(size) {
    void* m = mmap(nullptr, bytes, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
    memory = m == MAP_FAILED ? nullptr : static_cast<char*>(m);
  }
  ~Mapping() {
    if (memory != nullptr) munmap(memory, bytes);
  }
  Mapping(const Mapping&) = delete;
  Mapping& operator=(const Mapping&) = delete;
  std::size_t bytes;
  char* memory;
};

// Whether this system moves pages at all (mremap to a fixed place, Linux since 2.4; a sandbox
// may refuse it): where not, move_by_pages copies everything, and the tests that count moved
// bytes say why they skip.
bool system_moves_pages() {
  const auto page = static_cast<std::size_t>(sysconf(_SC_PAGESIZE));
  Mapping from(page);
  Mapping to(page);
  if (from.memory == nullptr || to.memory == nullptr) return false;
  from.memory[0] = 1;
  if (mremap(from.memory, page, page, MREMAP_MAYMOVE | MREMAP_FIXED, to.memory) == MAP_FAILED) {
    return false;
  }
  from.memory = nullptr;  // moved: its mapping is gone
  return to.memory[0] == 1;
}

// The destination's bytes outside the moved range must stay as they were: a guard value.
constexpr char kGuard = 0x5a;

void fill(char* at, std::size_t bytes) {
  for (std::size_t i = 0; i < bytes; ++i) at[i] = static_cast<char>((i * 131 + 7) % 251);
}

TEST(MoveByPages, SameOffsetWithinAPageMovesTheWholePagesAndCopiesTheEnds) {
  if (!system_moves_pages()) GTEST_SKIP() << "this system refuses mremap to a fixed place";
  const auto page = static_cast<std::size_t>(sysconf(_SC_PAGESIZE));
  for (const std::size_t offset : {std::size_t{0}, std::size_t{16}, page - 16}) {
    for (const std::size_t bytes : {5 * page, 5 * page + 48, 3 * page - offset}) {
      Mapping source(8 * page);
      Mapping target(8 * page);
      ASSERT_NE(source.memory, nullptr);
      ASSERT_NE(target.memory, nullptr);
      std::fill(target.memory, target.memory + target.bytes, kGuard);
      fill(source.memory + offset, bytes);
      const std::vector<char> expected(source.memory + offset, source.memory + offset + bytes);
      // The destination one page in, at the same offset within its page.
      char* const to = target.memory + page + offset;
      const std::size_t moved = engine::move_by_pages(source.memory + offset, to, bytes);
      const std::size_t first = (offset + page - 1) / page * page;  // from the page's start
      const std::size_t last = (offset + bytes) / page * page;
      EXPECT_EQ(moved, last > first ? last - first : 0) << offset << " " << bytes;
      EXPECT_EQ(std::vector<char>(to, to + bytes), expected) << offset << " " << bytes;
      for (char* c = target.memory; c < to; ++c) ASSERT_EQ(*c, kGuard);
      for (char* c = to + bytes; c < target.memory + target.bytes; ++c) ASSERT_EQ(*c, kGuard);
    }
  }
}

// As the output step uses it: quads moved into a vector's reserved room at the offset within a
// page of their place there, then inserted over themselves to become the vector's items.
TEST(MoveByPages, IntoAVectorsReservedRoomThenInsertedOverThemselves) {
  if (!system_moves_pages()) GTEST_SKIP() << "this system refuses mremap to a fixed place";
  using Quad = std::array<std::uint32_t, 4>;
  const auto page = static_cast<std::size_t>(sysconf(_SC_PAGESIZE));
  const std::size_t count = 3 * page / sizeof(Quad) + 5;  // three pages and a bit
  std::vector<Quad> out;
  out.reserve(count);
  char* const to = reinterpret_cast<char*>(out.data());
  const std::size_t offset = reinterpret_cast<std::uintptr_t>(to) % page;
  Mapping source(8 * page);
  ASSERT_NE(source.memory, nullptr);
  std::vector<Quad> expected(count);
  for (std::size_t i = 0; i < count; ++i) {
    const auto k = static_cast<std::uint32_t>(4 * i);
    expected[i] = {k, k + 1, k + 2, k + 3};
  }
  std::memcpy(source.memory + offset, expected.data(), count * sizeof(Quad));
  EXPECT_GE(engine::move_by_pages(source.memory + offset, to, count * sizeof(Quad)), 2 * page);
  const Quad* const moved = std::launder(reinterpret_cast<const Quad*>(to));
  out.insert(out.end(), moved, moved + count);
  EXPECT_EQ(out, expected);
  EXPECT_EQ(engine::move_by_pages(source.memory, to, 0), 0u);  // nothing to move
}

TEST(MoveByPages, OtherOffsetsWithinAPageAreCopied) {
  const auto page = static_cast<std::size_t>(sysconf(_SC_PAGESIZE));
  Mapping source(8 * page);
  Mapping target(8 * page);
  ASSERT_NE(source.memory, nullptr);
  ASSERT_NE(target.memory, nullptr);
  const std::size_t bytes = 5 * page + 100;
  fill(source.memory + 16, bytes);
  const std::vector<char> expected(source.memory + 16, source.memory + 16 + bytes);
  EXPECT_EQ(engine::move_by_pages(source.memory + 16, target.memory + 32, bytes), 0u);
  EXPECT_EQ(std::vector<char>(target.memory + 32, target.memory + 32 + bytes), expected);
  // Copied, not moved: the source still holds its bytes.
  EXPECT_EQ(std::vector<char>(source.memory + 16, source.memory + 16 + bytes), expected);
}

}  // namespace
}  // namespace dtlab::test
