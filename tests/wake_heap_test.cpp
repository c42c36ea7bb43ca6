// The WakeQueue's 4-ary heap (modules/wake_heap.hpp): on random streams of pushes and pops, with
// many equal times, its entries leave in the order of (time, sequence number), as they left
// std::priority_queue before it; the client number packed beside the sequence number comes back.
#include "modules/wake_heap.hpp"

#include <gtest/gtest.h>

#include <cstdint>
#include <functional>
#include <queue>
#include <random>
#include <tuple>
#include <vector>

namespace {

using rtsim::modules::WakeHeap;
using Reference = std::tuple<std::uint64_t, std::uint64_t, std::uint32_t>;  // t, seq, client

TEST(WakeHeap, LeavesInTheOrderOfABinaryHeapOnRandomStreams) {
  for (const std::uint64_t spread : {std::uint64_t{1}, std::uint64_t{4}, std::uint64_t{1000}}) {
    std::mt19937_64 rng(spread);
    WakeHeap heap;
    std::priority_queue<Reference, std::vector<Reference>, std::greater<>> reference;
    std::uint64_t seq = 0;
    std::uint64_t now = 0;
    std::size_t popped = 0;
    for (int step = 0; step < 200000; ++step) {
      // Pushes outnumber pops early, then the heap drains: sizes from 0 to a few thousand.
      const bool push = reference.empty() || rng() % 100 < (step < 100000 ? 55u : 45u);
      if (push) {
        const std::uint64_t t = now + rng() % spread;  // never before the last pop's time
        const auto client = static_cast<std::uint32_t>(rng() % WakeHeap::kMaxClients);
        heap.push(t, seq, client);
        reference.emplace(t, seq, client);
        ++seq;
      } else {
        ASSERT_FALSE(heap.empty());
        const auto [t, s, client] = reference.top();
        ASSERT_EQ(heap.top().t, t) << "pop " << popped;
        ASSERT_EQ(heap.top().seq(), s) << "pop " << popped;
        ASSERT_EQ(heap.top().client(), client) << "pop " << popped;
        heap.pop();
        reference.pop();
        now = t;
        ++popped;
      }
      ASSERT_EQ(heap.size(), reference.size());
    }
    EXPECT_GT(popped, 50000u);
  }
}

TEST(WakeHeap, EqualTimesLeaveFirstPushedFirst) {
  WakeHeap heap;
  for (std::uint32_t k = 0; k < 40; ++k) heap.push(7, k, 39 - k);
  heap.push(3, 40, 99);
  EXPECT_EQ(heap.top().client(), 99u);
  heap.pop();
  for (std::uint32_t k = 0; k < 40; ++k) {
    ASSERT_EQ(heap.top().seq(), k);
    EXPECT_EQ(heap.top().client(), 39 - k);
    heap.pop();
  }
  EXPECT_TRUE(heap.empty());
}

}  // namespace
