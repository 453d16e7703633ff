// SPDX-License-Identifier: MIT
// OffsetList: a list placed past the start of its storage reads from its first item, grows by
// moving its items (and only its items) to the start of new storage, and keeps them through resize
// and truncate.
#include "cleave/geometry/offset_list.h"

#include <algorithm>
#include <cstdint>
#include <vector>

#include <gtest/gtest.h>

namespace cleave::geometry::detail {
namespace {

std::vector<uint32_t> items(const OffsetList<uint32_t>& list) { return {list.begin(), list.end()}; }

TEST(OffsetList, AListAdoptedPastTheStartReadsFromItsFirstItem) {
  OffsetList<uint32_t> list;
  uint32_t* storage = list.place(16);
  for (uint32_t k = 0; k < 16; ++k) storage[k] = 100 + k;
  list.adopt(5, 4);
  EXPECT_EQ(items(list), (std::vector<uint32_t>{105, 106, 107, 108}));
  EXPECT_EQ(list[0], 105u);
  EXPECT_EQ(list.data(), storage + 5);
  // Room after the list: push_back writes in place.
  for (uint32_t k = 0; k < 7; ++k) list.push_back(k);
  EXPECT_EQ(list.size(), 11u);
  EXPECT_EQ(list.data(), storage + 5);
  EXPECT_EQ(items(list), (std::vector<uint32_t>{105, 106, 107, 108, 0, 1, 2, 3, 4, 5, 6}));
}

TEST(OffsetList, GrowingMovesOnlyTheListToTheStartOfNewStorage) {
  OffsetList<uint32_t> list;
  uint32_t* storage = list.place(8);
  for (uint32_t k = 0; k < 8; ++k) storage[k] = k;
  list.adopt(6, 2);  // the last two places of the storage
  const uintptr_t old = reinterpret_cast<uintptr_t>(storage);
  list.push_back(8);  // no room after the list: new storage
  EXPECT_EQ(items(list), (std::vector<uint32_t>{6, 7, 8}));
  EXPECT_NE(reinterpret_cast<uintptr_t>(list.data()), old + 6 * sizeof(uint32_t));
  list.resize(40);  // grows again; the first three stay
  EXPECT_EQ(list.size(), 40u);
  EXPECT_EQ(std::vector<uint32_t>(list.begin(), list.begin() + 3), (std::vector<uint32_t>{6, 7, 8}));
}

TEST(OffsetList, TruncateDropsTheTailAndPlaceKeepsBigEnoughStorage) {
  OffsetList<uint32_t> list;
  uint32_t* storage = list.place(32);
  for (uint32_t k = 0; k < 32; ++k) storage[k] = k % 4;
  list.adopt(10, 12);
  list.truncate(std::remove(list.begin(), list.end(), 3u));
  EXPECT_EQ(items(list), (std::vector<uint32_t>{2, 0, 1, 2, 0, 1, 2, 0, 1}));
  EXPECT_EQ(list.place(32), storage);  // big enough: kept, and the list is empty
  EXPECT_TRUE(list.empty());
  list.clear();
  list.push_back(9);
  EXPECT_EQ(items(list), (std::vector<uint32_t>{9}));
  EXPECT_EQ(list.data(), storage);
}

}  // namespace
}  // namespace cleave::geometry::detail
