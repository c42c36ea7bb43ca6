// The kit's first-in first-out buffer (modules/ring_buffer.hpp), which holds every machine's
// queued messages: items come out in the order they went in while it wraps round and grows, and
// a taken item's resources are released at once.
#include "modules/ring_buffer.hpp"

#include <gtest/gtest.h>

#include <memory>
#include <string>

namespace {

using rtsim::modules::RingBuffer;

TEST(RingBuffer, ItemsLeaveInTheOrderTheyCameWhileItWrapsAndGrows) {
  RingBuffer<int> q;
  int next_in = 0, next_out = 0;
  // Uneven puts and takes: the front moves round the array, and it grows with the front
  // anywhere in it (4, 8, 16, 32 slots).
  for (int round = 0; round < 40; ++round) {
    for (int k = 0; k < 3 + round % 5; ++k) q.push_back(next_in++);
    for (int k = 0; k < 2 + round % 3 && !q.empty(); ++k) {
      ASSERT_EQ(q.front(), next_out) << "round " << round;
      q.pop_front();
      ++next_out;
    }
    ASSERT_EQ(q.size(), static_cast<std::size_t>(next_in - next_out));
  }
  while (!q.empty()) {
    ASSERT_EQ(q.front(), next_out++);
    q.pop_front();
  }
  EXPECT_EQ(next_out, next_in);
}

TEST(RingBuffer, AppendFillsTheNewBackSlotInPlace) {
  RingBuffer<std::string> q;
  q.push_back(std::string(3, 'a'));
  q.append().assign(2, 'b');
  EXPECT_EQ(q.front(), std::string(3, 'a'));
  q.pop_front();
  EXPECT_EQ(q.front(), std::string(2, 'b'));
  EXPECT_EQ(q.size(), 1u);
}

TEST(RingBuffer, ATakenItemIsReleasedAtOnce) {
  RingBuffer<std::shared_ptr<int>> q;
  const auto item = std::make_shared<int>(7);
  q.push_back(item);
  EXPECT_EQ(item.use_count(), 2);
  q.pop_front();
  EXPECT_EQ(item.use_count(), 1) << "the slot still holds what was taken from it";
}

}  // namespace
