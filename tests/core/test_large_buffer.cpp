#include "refx/core/large_buffer.h"

#include <cstdint>

#include <gtest/gtest.h>

namespace refx {
namespace {

// A 1920x1080 float depth buffer: 8,294,400 bytes, over the 2 MiB threshold, so it
// starts on a 2 MiB boundary (2^21) and its mapping is rounded up to 4 huge pages.
TEST(LargeBuffer, LargeAllocationsStartOnAHugePage) {
  LargeBuffer<float> depth(size_t(1920) * 1080, 1.0f);
  EXPECT_EQ(reinterpret_cast<uintptr_t>(depth.data()) % (uintptr_t(1) << 21), 0u);
  EXPECT_EQ(detail::roundToHugePages(depth.size() * sizeof(float)), size_t(4) << 21);
  EXPECT_EQ(depth.front(), 1.0f);
  EXPECT_EQ(depth.back(), 1.0f);
  depth[1920 * 1079 + 1919] = 0.25f;
  EXPECT_EQ(depth.back(), 0.25f);
}

// Exactly 2 MiB takes the mapped path, one byte less the ordinary heap; both hold what
// they are given, and a copy into a larger buffer (a reallocation) keeps it.
TEST(LargeBuffer, BothSidesOfTheThresholdKeepTheirContents) {
  LargeBuffer<uint8_t> small((size_t(1) << 21) - 1, 7), exact(size_t(1) << 21, 9);
  EXPECT_EQ(reinterpret_cast<uintptr_t>(exact.data()) % (uintptr_t(1) << 21), 0u);
  EXPECT_EQ(small.back(), 7);
  EXPECT_EQ(exact.back(), 9);
  small.push_back(3);  // now 2 MiB: moved into a mapping
  EXPECT_EQ(small.size(), size_t(1) << 21);
  EXPECT_EQ(small.front(), 7);
  EXPECT_EQ(small[(size_t(1) << 21) - 2], 7);
  EXPECT_EQ(small.back(), 3);
  EXPECT_EQ(detail::roundToHugePages(1), size_t(1) << 21);
  EXPECT_EQ(detail::roundToHugePages((size_t(1) << 21) + 1), size_t(2) << 21);
}

}  // namespace
}  // namespace refx
