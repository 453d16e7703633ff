// SPDX-License-Identifier: MIT
#include "cleave/input/key.h"

#include <gtest/gtest.h>

#include <set>
#include <string>

namespace cleave::input {
namespace {

TEST(Key, EveryKeyNameRoundTripsAndIsUnique) {
  std::set<std::string> names;
  for (int i = 0; i < kKeyCount; ++i) {
    const Key key = static_cast<Key>(i);
    const std::string_view name = keyName(key);
    ASSERT_NE(name, "?") << i;
    EXPECT_TRUE(names.insert(std::string(name)).second) << name;
    EXPECT_EQ(keyFromName(name), key) << name;
  }
}

TEST(Key, NamesAreTheStableLowerCaseGlfwNames) {
  EXPECT_EQ(keyName(Key::W), "w");
  EXPECT_EQ(keyName(Key::Num0), "0");
  EXPECT_EQ(keyName(Key::Space), "space");
  EXPECT_EQ(keyName(Key::LeftShift), "left_shift");
  EXPECT_EQ(keyName(Key::LeftControl), "left_control");
  EXPECT_EQ(keyName(Key::Escape), "escape");
  EXPECT_EQ(keyName(Key::F12), "f12");
  EXPECT_EQ(keyName(Key::Up), "up");
  EXPECT_EQ(keyName(Key::CapsLock), "caps_lock");
  EXPECT_EQ(keyName(Key::Count), "?");
}

TEST(Key, UnknownNamesAreRejected) {
  EXPECT_FALSE(keyFromName("W").has_value());
  EXPECT_FALSE(keyFromName("").has_value());
  EXPECT_FALSE(keyFromName("f13").has_value());
  EXPECT_FALSE(keyFromName("?").has_value());
}

TEST(MouseButton, NamesRoundTrip) {
  for (int i = 0; i < kMouseButtonCount; ++i) {
    const auto button = static_cast<MouseButton>(i);
    EXPECT_EQ(mouseButtonFromName(mouseButtonName(button)), button);
  }
  EXPECT_EQ(mouseButtonName(MouseButton::Middle), "middle");
  EXPECT_FALSE(mouseButtonFromName("back").has_value());
}

}  // namespace
}  // namespace cleave::input
