#pragma once
// Bytes moved to another place in this process's memory by moving the pages that hold them
// (mremap, Linux) where both places have the same offset within a page: the system relinks page
// table entries, where a copy would fault each fresh destination page in (3 to 4.6 us a page on
// the development VM, 1.8 us with two threads mapping) and the source's pages would be freed one
// by one afterwards. The partial pages at either end are copied.
#include <cerrno>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <new>

#ifdef __linux__
#include <sys/mman.h>
#include <unistd.h>
#endif

namespace dtlab::engine {

// Moves [from, from + bytes) to [to, to + bytes); the ranges do not overlap. Every whole page of
// the destination range must be private anonymous memory of the caller's alone (a buffer it
// allocated and has not handed out), and every whole page of the source range memory that nobody
// reads again: where pages move, the source's are unmapped and the destination's replaced. Where
// they cannot move (other offsets within a page, another system, a refusal) the bytes are
// copied. Returns the bytes moved by pages (the rest were copied). Each move leaves the
// destination's mapping split where the moved pages begin and end (two more mappings a move,
// against the system's limit of some 65,000 a process; past it the moves are refused before they
// change anything, and copied).
inline std::size_t move_by_pages(char* from, char* to, std::size_t bytes) {
  if (bytes == 0) return 0;
#ifdef __linux__
  const auto page = static_cast<std::uintptr_t>(sysconf(_SC_PAGESIZE));
  const auto source = reinterpret_cast<std::uintptr_t>(from);
  const auto target = reinterpret_cast<std::uintptr_t>(to);
  const std::uintptr_t first = (target + page - 1) / page * page;  // the first whole page
  const std::uintptr_t last = (target + bytes) / page * page;      // past the last whole page
  if ((source - target) % page == 0 && last > first) {
    const std::size_t head = first - target;
    const std::size_t middle = last - first;
    if (mremap(from + head, middle, middle, MREMAP_MAYMOVE | MREMAP_FIXED, to + head) !=
        MAP_FAILED) {
      std::memcpy(to, from, head);
      std::memcpy(to + head + middle, from + head + middle, bytes - head - middle);
      return middle;
    }
    // The system may have unmapped the destination's pages before it refused (Linux unmaps
    // them first, then can still fail for memory; a refusal at the mappings' limit comes before):
    // then fresh pages go there before the copy. mincore fails with ENOMEM on an unmapped page.
    unsigned char resident = 0;
    if (mincore(to + head, page, &resident) != 0 && errno == ENOMEM &&
        mmap(to + head, middle, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS | MAP_FIXED, -1,
             0) == MAP_FAILED) {
      throw std::bad_alloc();
    }
  }
#endif
  std::memcpy(to, from, bytes);
  return 0;
}

}  // namespace dtlab::engine
