#pragma once
// The process's heap in 2 MiB pages where the kernel allows it (transparent huge pages on
// request, `madvise`, this machine's setting).
//
// A large machine is hundreds of thousands of small objects made and grown over the whole run:
// at 32 x 32 ullner-array's processors, ports, queues and busy timelines touch about 230 MB of
// heap a 4 KiB page at a time, 57,600 page faults that cost this virtual machine's kernel about
// 0.45 s, a quarter of the run (docs/benchmarks.md, "stop 71"). With the heap in 2 MiB pages the
// whole process faults 11,700 times (the rest: its libraries, the statistics thread's own
// arena, the image), and the processors' state, spread over the heap, misses the TLB less.
//
// glibc extends its main heap with brk and cannot be asked to advise the growth (its tunable
// glibc.malloc.hugetlb is read from the environment at start-up only), so this reserves the
// address space once: the heap's next growth is kHeapReserve at a time (M_TOP_PAD), that range
// is advised MADV_HUGEPAGE, never trimmed back, and blocks up to 32 MiB come from it rather than
// from mmap (M_MMAP_THRESHOLD, glibc's maximum). Reserved address space costs no memory until
// it is touched. Beyond the reserve (a run of more than 1 GiB of heap) the heap grows as before,
// in small pages. Under a limit on address space or data (ulimit -v, -d), which the reserve
// would count against whole, nothing is reserved (address_space_limited).
//
// Call it first thing in main(), before any thread starts. It changes where blocks are, never
// what a program computes.
#include <cstddef>

namespace rtsim::app {

/// Address space the heap reserves for large pages.
inline constexpr std::size_t kHeapReserve = std::size_t{1} << 30;

/// Whether the process runs under a finite limit on its address space or data (RLIMIT_AS,
/// RLIMIT_DATA).
bool address_space_limited();

/// Reserves and advises the heap (see above). Returns the bytes advised: 0 under a limit, or
/// where the allocator or the kernel refused, which leaves the heap as it was.
std::size_t use_huge_heap_pages();

}  // namespace rtsim::app
