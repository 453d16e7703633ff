// SPDX-License-Identifier: MIT
#include "cleave/input/key.h"

#include <array>

namespace cleave::input {
namespace {

// Indexed by Key; order must match the enum.
constexpr std::array<std::string_view, kKeyCount> kKeyNames = {
    "a", "b", "c", "d", "e", "f", "g", "h", "i", "j", "k", "l", "m",
    "n", "o", "p", "q", "r", "s", "t", "u", "v", "w", "x", "y", "z",
    "0", "1", "2", "3", "4", "5", "6", "7", "8", "9",
    "space", "escape", "enter", "tab", "backspace", "insert", "delete",
    "right", "left", "down", "up", "page_up", "page_down", "home", "end",
    "f1", "f2", "f3", "f4", "f5", "f6", "f7", "f8", "f9", "f10", "f11", "f12",
    "left_shift", "left_control", "left_alt", "right_shift", "right_control", "right_alt",
    "minus", "equal", "comma", "period", "slash", "semicolon", "apostrophe",
    "left_bracket", "right_bracket", "backslash", "grave_accent", "caps_lock",
};

constexpr std::array<std::string_view, kMouseButtonCount> kButtonNames = {"left", "right",
                                                                          "middle"};

}  // namespace

std::string_view keyName(Key key) {
  const auto index = static_cast<size_t>(key);
  return index < kKeyNames.size() ? kKeyNames[index] : std::string_view("?");
}

std::string_view mouseButtonName(MouseButton button) {
  const auto index = static_cast<size_t>(button);
  return index < kButtonNames.size() ? kButtonNames[index] : std::string_view("?");
}

std::optional<Key> keyFromName(std::string_view name) {
  // Linear search over ~80 names: replays are small and this keeps one table as the truth.
  for (size_t i = 0; i < kKeyNames.size(); ++i)
    if (kKeyNames[i] == name) return static_cast<Key>(i);
  return std::nullopt;
}

std::optional<MouseButton> mouseButtonFromName(std::string_view name) {
  for (size_t i = 0; i < kButtonNames.size(); ++i)
    if (kButtonNames[i] == name) return static_cast<MouseButton>(i);
  return std::nullopt;
}

}  // namespace cleave::input
