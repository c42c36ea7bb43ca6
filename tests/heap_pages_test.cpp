// app/heap_pages.cpp: the heap's growth is reserved and advised for 2 MiB pages, and the blocks a
// run makes afterwards (small ones and up to 32 MiB) are in that advised range.
#include "app/heap_pages.hpp"

#include <gtest/gtest.h>

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

namespace {

/// The mapping of /proc/self/smaps holding `address`: its header line and VmFlags.
struct Mapping {
  std::string header;
  std::string flags;
};

Mapping mapping_of(const void* address) {
  const auto a = reinterpret_cast<std::uintptr_t>(address);
  std::ifstream smaps("/proc/self/smaps");
  std::string line;
  Mapping found;
  bool inside = false;
  while (std::getline(smaps, line)) {
    unsigned long lo = 0, hi = 0;
    if (std::sscanf(line.c_str(), "%lx-%lx ", &lo, &hi) == 2 && line.find(':') > line.find(' ')) {
      inside = lo <= a && a < hi;
      if (inside) found.header = line;
    } else if (inside && line.rfind("VmFlags:", 0) == 0) {
      found.flags = line;
    }
  }
  return found;
}

bool advised(const Mapping& m) {
  std::istringstream words(m.flags);
  std::string w;
  while (words >> w)
    if (w == "hg") return true;
  return false;
}

TEST(HeapPages, BlocksMadeAfterwardsLieInTheAdvisedHeap) {
  const std::size_t bytes = rtsim::app::use_huge_heap_pages();
  ASSERT_GE(bytes, rtsim::app::kHeapReserve / 2) << "the heap's growth was not advised";
  // A run's kinds of block: many small ones, and a large one glibc would have mapped apart.
  std::vector<std::unique_ptr<char[]>> small;
  for (int i = 0; i < 1000; ++i) small.emplace_back(new char[200]);
  std::unique_ptr<char[]> large(new char[std::size_t{8} << 20]);
  for (const void* p :
       {static_cast<const void*>(small.back().get()), static_cast<const void*>(large.get())}) {
    const Mapping m = mapping_of(p);
    std::printf("block %p: %s\n  %s\n", p, m.header.c_str(), m.flags.c_str());
    EXPECT_NE(m.header.find("[heap]"), std::string::npos) << "not in the heap";
    EXPECT_TRUE(advised(m)) << "its mapping is not advised for huge pages (VmFlags hg)";
  }
}

}  // namespace
