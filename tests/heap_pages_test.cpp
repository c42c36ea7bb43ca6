// app/heap_pages.cpp: the heap's growth is reserved and advised for 2 MiB pages, and the blocks a
// run makes afterwards (small ones and up to 32 MiB) are in that advised range.
#include "app/heap_pages.hpp"

#include <gtest/gtest.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

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
  if (rtsim::app::address_space_limited())
    GTEST_SKIP() << "this process runs under a limit on its address space: nothing is reserved";
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

TEST(HeapPages, UnderAnAddressSpaceLimitNothingIsReserved) {
  // The reserve would count whole against the limit and leave too little for threads' stacks
  // and the image module (tests/bad_input_runs_test.cpp runs rtsim under ulimit -v): a child
  // under a limit of 4 GiB reserves nothing and its heap grows as glibc's does.
  const pid_t child = fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    const rlimit limit{std::uint64_t{4} << 30, std::uint64_t{4} << 30};
    if (setrlimit(RLIMIT_AS, &limit) != 0) _exit(3);
    if (!rtsim::app::address_space_limited()) _exit(4);
    _exit(rtsim::app::use_huge_heap_pages() == 0 ? 0 : 5);
  }
  int status = 0;
  ASSERT_EQ(waitpid(child, &status, 0), child);
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 0) << "3: setrlimit failed, 4: the limit not seen, 5: reserved";
}

}  // namespace
