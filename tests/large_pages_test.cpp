// util/large_pages.h: large zeroed blocks mapped on their own, aligned to 2 MiB and advised for
// transparent huge pages (Linux, not under sanitizers); small ones from calloc. Every block reads
// as zeros and holds what is written to it. util/large_array.h: vectors whose blocks of 32 MiB
// or more are mapped so, and smaller ones come from operator new, aligned as their type asks.

#include <gtest/gtest.h>

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>

#include "strahl/util/large_array.h"
#include "strahl/util/large_pages.h"
#include "strahl/util/zeroed_array.h"

namespace strahl::large_pages_test {
namespace {

// /proc/self/smaps' "THPeligible" of the mapping that holds address p: 1 when the kernel may back
// it with huge pages (the advice was taken), 0 when not, −1 when there is no such line.
int thp_eligible(const void* p) {
  std::ifstream smaps("/proc/self/smaps");
  const auto a = reinterpret_cast<std::uintptr_t>(p);
  std::string line;
  bool inside = false;
  while (std::getline(smaps, line)) {
    unsigned long lo = 0, hi = 0;
    if (std::sscanf(line.c_str(), "%lx-%lx ", &lo, &hi) == 2 && line.find('-') < line.find(' ')) {
      inside = a >= lo && a < hi;
      continue;
    }
    if (inside && line.rfind("THPeligible:", 0) == 0) return std::stoi(line.substr(12));
  }
  return -1;
}

// The system's transparent-huge-page mode: "always", "madvise" or "never" ("" when unknown).
std::string thp_mode() {
  std::ifstream in("/sys/kernel/mm/transparent_hugepage/enabled");
  std::string all;
  std::getline(in, all);
  const auto open = all.find('['), close = all.find(']');
  return open == std::string::npos || close == std::string::npos ? "" : all.substr(open + 1, close - open - 1);
}

TEST(LargePages, BlocksReadAsZerosAndHoldWhatIsWritten) {
  for (const std::size_t bytes : {std::size_t(1), std::size_t(4096), kLargeBlock - 1, kLargeBlock, kLargePage - 1,
                                  kLargePage, kLargePage + 1, 5 * kLargePage + 12345}) {
    auto* p = static_cast<unsigned char*>(allocate_zeroed_bytes(bytes));
    ASSERT_NE(p, nullptr);
    std::size_t nonzero = 0;
    for (std::size_t i = 0; i < bytes; ++i) nonzero += p[i] != 0;
    EXPECT_EQ(nonzero, 0u) << bytes << " bytes";
    p[0] = 1, p[bytes - 1] = 2;  // the first and the last byte are the block's
    EXPECT_EQ(p[0], bytes == 1 ? 2 : 1);
    EXPECT_EQ(p[bytes - 1], 2);
    free_zeroed_bytes(p, bytes);
  }
  free_zeroed_bytes(nullptr, 0);
}

TEST(LargePages, LargeBlocksAreAlignedAndAdvisedForHugePages) {
  EXPECT_FALSE(maps_large_pages(kLargeBlock - 1));
  if (!maps_large_pages(kLargeBlock)) GTEST_SKIP() << "calloc's memory here (not Linux, a sanitizer, or STRAHL_LARGE_PAGES=0)";
  ZeroedArray<double> sums(3 * kLargePage / sizeof(double) + 7);  // a film's sums: 3 large pages and a bit
  EXPECT_EQ(reinterpret_cast<std::uintptr_t>(sums.data()) % kLargePage, 0u);
  sums[sums.size() - 1] = 1;
  ZeroedArray<std::uint32_t> counts(kLargeBlock / sizeof(std::uint32_t));  // half a large page
  EXPECT_EQ(reinterpret_cast<std::uintptr_t>(counts.data()) % kLargePage, 0u);
  const std::string mode = thp_mode();
  if (mode != "always" && mode != "madvise") GTEST_SKIP() << "transparent huge pages are " << mode;
  const int eligible = thp_eligible(sums.data());
  if (eligible < 0) GTEST_SKIP() << "no THPeligible in /proc/self/smaps";
  EXPECT_EQ(eligible, 1);
  // A small array from calloc: in "madvise" mode the heap is not advised.
  if (mode == "madvise") {
    ZeroedArray<double> small(1000);
    EXPECT_EQ(thp_eligible(small.data()), 0);
  }
}

// A BVH node's alignment (64 bytes), which both kinds of block must honour.
struct alignas(64) Node {
  double value[3];
};

TEST(LargeArray, HoldsWhatIsWrittenAlignedAsItsTypeAsks) {
  // Small (operator new) and large (mapped when large pages are on) arrays, grown past their first
  // block: every element keeps its value, every block is aligned to 64 bytes.
  const std::size_t big = kLargeBlock / sizeof(Node) + 1;
  for (const std::size_t n : {std::size_t(1), std::size_t(1000), big}) {
    LargeArray<Node> a;
    a.resize(n);
    EXPECT_EQ(reinterpret_cast<std::uintptr_t>(a.data()) % 64, 0u) << n;
    for (std::size_t i = 0; i < n; ++i) a[i].value[0] = double(i);
    a.push_back(Node{{-1, 0, 0}});  // grows: a new block, the elements moved into it
    EXPECT_EQ(reinterpret_cast<std::uintptr_t>(a.data()) % 64, 0u) << n;
    std::size_t wrong = 0;
    for (std::size_t i = 0; i < n; ++i) wrong += a[i].value[0] != double(i);
    EXPECT_EQ(wrong, 0u) << n;
    EXPECT_EQ(a.back().value[0], -1);
    const LargeArray<Node> copy = a;
    EXPECT_EQ(copy[n / 2].value[0], double(n / 2));
  }
}

TEST(LargeArray, BlocksFromOneMiBAreInHugePagesSmallerOnesAreNot) {
  if (!maps_large_pages(kLargeBlock)) GTEST_SKIP() << "no large pages here (not Linux, a sanitizer, or STRAHL_LARGE_PAGES=0)";
  LargeArray<double> large(kLargeBlock / sizeof(double));
  EXPECT_EQ(reinterpret_cast<std::uintptr_t>(large.data()) % kLargePage, 0u);
  large.back() = 1;
  const std::string mode = thp_mode();
  if (mode != "madvise") GTEST_SKIP() << "transparent huge pages are " << mode << " (the test needs madvise)";
  const int eligible = thp_eligible(large.data());
  if (eligible < 0) GTEST_SKIP() << "no THPeligible in /proc/self/smaps";
  EXPECT_EQ(eligible, 1);
  // Just below: malloc's block (which it maps afresh, unadvised, or takes from its heap).
  LargeArray<double> below(kLargeBlock / sizeof(double) - 1);
  below.back() = 1;
  EXPECT_EQ(thp_eligible(below.data()), 0);
}

// STRAHL_LARGE_PAGES=0 or off: no block in large pages; any other value: as without it. The
// variable is read once per process, so each case runs in a child of its own (a death test's
// "threadsafe" style starts the test binary afresh).
TEST(LargePagesDeathTest, TheEnvironmentTurnsThemOff) {
  // (Not maps_large_pages here: it would read the variable before the child sets it.)
  if (!large_pages_supported()) GTEST_SKIP() << "calloc's memory on this build (not Linux, or a sanitizer)";
  GTEST_FLAG_SET(death_test_style, "threadsafe");
  const auto exit_code_with = [](const char* value) {  // 1: large pages, 0: none
    ::setenv("STRAHL_LARGE_PAGES", value, 1);
    std::exit(maps_large_pages(kLargeBlock) ? 1 : 0);
  };
  EXPECT_EXIT(exit_code_with("0"), ::testing::ExitedWithCode(0), "");
  EXPECT_EXIT(exit_code_with("off"), ::testing::ExitedWithCode(0), "");
  EXPECT_EXIT(exit_code_with("1"), ::testing::ExitedWithCode(1), "");
  EXPECT_EXIT(exit_code_with(""), ::testing::ExitedWithCode(1), "");
}

}  // namespace
}  // namespace strahl::large_pages_test
