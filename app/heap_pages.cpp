#include "app/heap_pages.hpp"

#include <malloc.h>
#include <sys/mman.h>
#include <sys/resource.h>
#include <unistd.h>

#include <climits>
#include <cstdint>
#include <cstdlib>
#include <initializer_list>

namespace rtsim::app {

namespace {
/// glibc's default top pad, trim and mmap thresholds (128 KiB).
constexpr int kGlibcDefault = 128 * 1024;
}  // namespace

bool address_space_limited() {
  for (const int resource : {RLIMIT_AS, RLIMIT_DATA}) {
    rlimit limit{};
    if (getrlimit(resource, &limit) != 0 || limit.rlim_cur != RLIM_INFINITY) return true;
  }
  return false;
}

std::size_t use_huge_heap_pages() {
  // Under a limit on address space or data (ulimit -v, ulimit -d) the reserve would count
  // against it whole, untouched as it is, and leave too little for the rest: threads' stacks,
  // the image module's libraries. The heap stays as glibc makes it.
  if (address_space_limited()) return 0;
  // Where anything is refused, the heap goes back to glibc's defaults: a heap that asked for the
  // reserve at every growth and never got it could not grow at all.
  const auto back_to_defaults = [] {
    mallopt(M_TOP_PAD, kGlibcDefault);
    mallopt(M_TRIM_THRESHOLD, kGlibcDefault);
    mallopt(M_MMAP_THRESHOLD, kGlibcDefault);
    return std::size_t{0};
  };
  const auto kPage = static_cast<std::uintptr_t>(sysconf(_SC_PAGESIZE));
  // Blocks up to glibc's largest mmap threshold come from the (advised) heap; the reserve is
  // never handed back (trimming and growing again would fault it in anew).
  if (mallopt(M_MMAP_THRESHOLD, 32 << 20) == 0 || mallopt(M_TRIM_THRESHOLD, INT_MAX) == 0 ||
      mallopt(M_TOP_PAD, static_cast<int>(kHeapReserve)) == 0)
    return back_to_defaults();
  // The heap so far (its blocks of static initialisers) and its free top, from which the next
  // blocks come, are advised with the growth: one mapping.
  const auto before = reinterpret_cast<std::uintptr_t>(sbrk(0));
  const std::uintptr_t from = (before - mallinfo2().arena) & ~(kPage - 1);
  // A block larger than the heap's free top makes it grow now, by the reserve; freed, the block
  // is the top again. volatile: a block that is never used could be optimised away.
  void* volatile block = std::malloc(mallinfo2().keepcost + (std::size_t{1} << 16));
  std::free(block);
  const auto after = reinterpret_cast<std::uintptr_t>(sbrk(0));
  if (after <= before) return back_to_defaults();  // no room for the reserve
  if (madvise(reinterpret_cast<void*>(from), after - from, MADV_HUGEPAGE) != 0) return 0;
  return after - from;
}

}  // namespace rtsim::app
