// SPDX-License-Identifier: MIT
// The range checks of index_range.h: the plain loops (what a processor without AVX2 runs) and the
// AVX2 ones give the same answers, on arrays that pass and on arrays with one wrong entry at every
// place of a vector and of the scalar tail.
#include "cleave/geometry/index_range.h"

#include <cstdint>
#include <numeric>
#include <vector>

#include <gtest/gtest.h>

namespace cleave::geometry::detail {
namespace {

#ifdef CLEAVE_AVX2_VARIANTS  // the AVX2 loops are built for x86-64 only
TEST(IndexRange, PlainAndAvx2LoopsAgree) {
  if (!runsAvx2()) GTEST_SKIP() << "this processor has no AVX2";
  for (size_t count : {size_t(0), size_t(1), size_t(7), size_t(8), size_t(33), size_t(1000)}) {
    std::vector<uint32_t> values(count);
    std::iota(values.begin(), values.end(), 5u);  // 5, 6, ...: ascending, all below count + 5
    const uint32_t limit = static_cast<uint32_t>(count) + 5;
    std::vector<uint32_t> a(count), b(count);
    EXPECT_EQ(loops::anyAtOrAbove(values.data(), count, limit), loops::anyAtOrAboveAvx2(values.data(), count, limit));
    EXPECT_FALSE(loops::anyAtOrAboveAvx2(values.data(), count, limit));
    EXPECT_TRUE(loops::copyBelowAvx2(values.data(), b.data(), count, limit));
    EXPECT_EQ(b, values);
    EXPECT_TRUE(loops::ascendingAvx2(values.data(), count));
    std::vector<uint32_t> back(count + 5);
    for (uint32_t k = 0; k < count; ++k) back[values[k]] = k;
    EXPECT_TRUE(loops::pointBackAvx2(values.data(), count, back.data()));
    for (size_t wrong = 0; wrong < count; ++wrong) {
      SCOPED_TRACE(testing::Message() << count << " values, entry " << wrong << " wrong");
      std::vector<uint32_t> over = values;
      over[wrong] = limit;
      EXPECT_TRUE(loops::anyAtOrAbove(over.data(), count, limit));
      EXPECT_TRUE(loops::anyAtOrAboveAvx2(over.data(), count, limit));
      EXPECT_FALSE(loops::copyBelow(over.data(), a.data(), count, limit));
      EXPECT_FALSE(loops::copyBelowAvx2(over.data(), b.data(), count, limit));
      EXPECT_EQ(a, over);
      EXPECT_EQ(b, over);
      std::vector<uint32_t> flat = values;
      flat[wrong] = wrong > 0 ? flat[wrong - 1] : 1u << 30;
      EXPECT_EQ(loops::ascending(flat.data(), count), count == 1);
      EXPECT_EQ(loops::ascendingAvx2(flat.data(), count), count == 1);
      std::vector<uint32_t> elsewhere = back;
      elsewhere[values[wrong]] ^= 1u << 20;
      EXPECT_FALSE(loops::pointBack(values.data(), count, elsewhere.data()));
      EXPECT_FALSE(loops::pointBackAvx2(values.data(), count, elsewhere.data()));
    }
  }
}
#endif

}  // namespace
}  // namespace cleave::geometry::detail
