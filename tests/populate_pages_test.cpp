// A test of the engine's internals: it includes headers from engine/src (dtlab_internal_test).
// populate_pages maps a fresh buffer's whole pages without changing what they hold, and
// populated_vector gives value-initialized items whatever the thread count.
#include <gtest/gtest.h>
#include <sys/mman.h>
#include <unistd.h>

#include <cerrno>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "dtlab/predicates/point.hpp"
#include "support/populate_pages.hpp"

namespace dtlab::test {
namespace {

// Pages of [memory, memory + bytes) the system has mapped (mincore).
std::size_t resident_pages(void* memory, std::size_t bytes) {
  const auto page = static_cast<std::size_t>(sysconf(_SC_PAGESIZE));
  std::vector<unsigned char> resident((bytes + page - 1) / page);
  EXPECT_EQ(mincore(memory, bytes, resident.data()), 0);
  std::size_t count = 0;
  for (const unsigned char r : resident) count += r & 1;
  return count;
}

TEST(PopulatePages, MapsTheWholePagesInsideTheRangeAndLeavesTheirContents) {
  const auto page = static_cast<std::size_t>(sysconf(_SC_PAGESIZE));
  const std::size_t pages = 1024;
  void* memory =
      mmap(nullptr, pages * page, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
  ASSERT_NE(memory, MAP_FAILED);
  // Pages of 4 KiB, counted one by one: a huge page would map 512 at the first write (where
  // transparent huge pages are "always", the kernel aligns a mapping this large for them).
  madvise(memory, pages * page, MADV_NOHUGEPAGE);
  auto* bytes = static_cast<unsigned char*>(memory);
  bytes[3 * page + 5] = 42;  // one page mapped, with something in it
  ASSERT_EQ(resident_pages(memory, pages * page), 1u);
  // One thread: nothing asked, nothing mapped.
  EXPECT_FALSE(engine::populate_pages(bytes + 10, pages * page - 20, 1));
  EXPECT_EQ(resident_pages(memory, pages * page), 1u);
  // The request itself, on the page already mapped: kernels before Linux 5.14 do not know it.
  // There populate_pages maps nothing (a hint: the writers fault the pages in as before), so
  // there is nothing here to count; the skip names why.
#ifdef MADV_POPULATE_WRITE
  if (madvise(bytes + 3 * page, page, MADV_POPULATE_WRITE) != 0 && errno == EINVAL) {
    munmap(memory, pages * page);
    GTEST_SKIP() << "this kernel has no MADV_POPULATE_WRITE (Linux 5.14)";
  }
#else
  // Built without the request: populate_pages compiles to "nothing mapped" (its own #ifdef).
  munmap(memory, pages * page);
  GTEST_SKIP() << "these system headers have no MADV_POPULATE_WRITE (Linux 5.14)";
#endif
  // A range from inside the first page to inside the last: the pages wholly inside it.
  EXPECT_TRUE(engine::populate_pages(bytes + 10, pages * page - 20, 2));
  // Not the first and the last, which the range holds in part (the one written lies inside).
  EXPECT_EQ(resident_pages(memory, pages * page), pages - 2);
  EXPECT_EQ(resident_pages(bytes + page, (pages - 2) * page), pages - 2);
  EXPECT_EQ(bytes[3 * page + 5], 42);
  for (std::size_t i = page; i < (pages - 1) * page; i += 97) {
    if (i != 3 * page + 5) {
      ASSERT_EQ(bytes[i], 0) << i;
    }
  }
  munmap(memory, pages * page);
}

TEST(PopulatePages, PopulatedVectorHoldsValueInitializedItems) {
  for (const int threads : {1, 2, 4}) {
    for (const std::size_t n :
         {std::size_t{0}, std::size_t{1}, std::size_t{1000}, std::size_t{1} << 20}) {
      const auto points = engine::populated_vector<predicates::Point3>(n, threads);
      ASSERT_EQ(points.size(), n);
      for (const predicates::Point3& p : points) {
        ASSERT_TRUE(p.x == 0 && p.y == 0 && p.z == 0);
      }
    }
  }
}

}  // namespace
}  // namespace dtlab::test
