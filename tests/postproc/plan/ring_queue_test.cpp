#include "postproc/plan/ring_queue.h"

#include <gtest/gtest.h>

#include <cstddef>

namespace vcpost::plan::detail {
namespace {

TEST(RingQueue, KeepsOrderWhenItGrowsWrappedAround) {
  RingQueue<int> q;
  for (int i = 0; i < 10; ++i) q.push_back(i);
  q.pop_front(6);                                // the front is now in the middle of the 16 slots
  for (int i = 10; i < 30; ++i) q.push_back(i);  // wraps, then outgrows the 16 slots
  ASSERT_EQ(q.size(), 24u);
  EXPECT_EQ(q.front(), 6);
  EXPECT_EQ(q.back(), 29);
  for (std::size_t i = 0; i < q.size(); ++i) EXPECT_EQ(q[i], static_cast<int>(6 + i)) << i;
  q.pop_back();
  q.pop_front();
  EXPECT_EQ(q.size(), 22u);
  EXPECT_EQ(q.front(), 7);
  EXPECT_EQ(q.back(), 28);
  q.clear();
  EXPECT_TRUE(q.empty());
}

TEST(RingQueue, EmplacedElementsStartFromTheirInitialisersNotFromAReusedSlot) {
  struct Item {
    int v = 7;
  };
  RingQueue<Item> q;
  for (int i = 0; i < 16; ++i) q.push_back(Item{100 + i});
  q.pop_front(16);
  Item& item = q.emplace_back();  // reuses a slot that held 100 + k
  EXPECT_EQ(item.v, 7);
  EXPECT_EQ(q.size(), 1u);
}

}  // namespace
}  // namespace vcpost::plan::detail
