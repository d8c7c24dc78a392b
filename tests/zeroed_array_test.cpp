// util/zeroed_array.h: the film's and the image's storage — n values of all-zero bytes at the
// start, copies that equal their source and own their memory, moved-from arrays that are empty.

#include <gtest/gtest.h>

#include <utility>

#include "strahl/image/image.h"
#include "strahl/render/tile.h"
#include "strahl/util/zeroed_array.h"

namespace strahl::zeroed_array_test {
namespace {

TEST(ZeroedArray, StartsAtZeroAndCopiesAndMovesLikeAVector) {
  ZeroedArray<PixelStats> a(3 << 20);  // large enough for calloc to map fresh pages
  ASSERT_EQ(a.size(), std::size_t(3 << 20));
  for (const PixelStats& p : a) ASSERT_TRUE(p.sum == 0 && p.sum_sq == 0 && p.n == 0);
  a[7].sum = 2.5, a[7].n = 3;
  ZeroedArray<PixelStats> b(a);  // a copy: equal values, its own memory
  EXPECT_EQ(b.size(), a.size());
  EXPECT_NE(b.data(), a.data());
  EXPECT_EQ(b[7].sum, 2.5);
  EXPECT_EQ(b.at(7).n, 3u);
  b[7].n = 4;
  EXPECT_EQ(a[7].n, 3u);
  EXPECT_THROW((void)a.at(a.size()), std::out_of_range);

  ZeroedArray<PixelStats> c(std::move(a));  // a moved-from array is empty
  EXPECT_EQ(c.size(), std::size_t(3 << 20));
  EXPECT_EQ(c[7].n, 3u);
  EXPECT_TRUE(a.empty());  // NOLINT(bugprone-use-after-move): what a move leaves is the point here
  EXPECT_EQ(a.begin(), a.end());
  a = std::move(b);
  EXPECT_EQ(a.size(), c.size());
  EXPECT_TRUE(b.empty());  // NOLINT(bugprone-use-after-move)
  a = c;
  EXPECT_EQ(a.size(), c.size());
  EXPECT_EQ(a[7].n, 3u);
  EXPECT_TRUE(ZeroedArray<int>().empty());
}

TEST(ZeroedArray, ImagesCompareByTheirPixels) {
  Image a(4, 3), b(4, 3);
  EXPECT_TRUE(a == b);
  a.at(3, 2) = Rgb{0, 0, 1};
  EXPECT_FALSE(a == b);
  b.at(3, 2) = Rgb{0, 0, 1};
  EXPECT_TRUE(a == b);
  EXPECT_FALSE(a == Image(3, 4));
  const Image moved = std::move(a);
  EXPECT_TRUE(moved == b);
  EXPECT_TRUE(a.pixels().empty());  // NOLINT(bugprone-use-after-move)
}

}  // namespace
}  // namespace strahl::zeroed_array_test
