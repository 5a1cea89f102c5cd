#include "comply/core/triple_buffer.hpp"

#include <gtest/gtest.h>

namespace comply {
namespace {

TEST(TripleBuffer, ReaderSeesTheInitialValueUntilAWrite) {
  TripleBuffer<int> buffer(7);
  EXPECT_FALSE(buffer.update());
  EXPECT_EQ(buffer.read(), 7);
}

TEST(TripleBuffer, ReaderGetsTheNewestOfSeveralWrites) {
  TripleBuffer<int> buffer(0);
  buffer.write(1);
  buffer.write(2);
  buffer.write(3);
  EXPECT_TRUE(buffer.update());
  EXPECT_EQ(buffer.read(), 3);
  // Nothing new: the value stays and update() says so.
  EXPECT_FALSE(buffer.update());
  EXPECT_EQ(buffer.read(), 3);
}

TEST(TripleBuffer, WritesAfterAReadArriveOnTheNextUpdate) {
  TripleBuffer<int> buffer(0);
  buffer.write(1);
  ASSERT_TRUE(buffer.update());
  buffer.write(2);
  EXPECT_EQ(buffer.read(), 1);  // not yet taken
  EXPECT_TRUE(buffer.update());
  EXPECT_EQ(buffer.read(), 2);
}

TEST(TripleBuffer, SoleWriterPublishesTheSameWay) {
  TripleBuffer<int> buffer(0);
  buffer.publishFromSoleWriter(5);
  buffer.publishFromSoleWriter(6);
  EXPECT_TRUE(buffer.update());
  EXPECT_EQ(buffer.read(), 6);
}

}  // namespace
}  // namespace comply
