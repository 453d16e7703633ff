// SPDX-License-Identifier: MIT
// Keyboard keys and mouse buttons of the input layer, with stable text names.
//
// The names are the GLFW key names lower-cased without the GLFW_KEY_ prefix ("w", "space",
// "left_shift", "f1", "0"). They are part of the replay format (docs/replay-format.md): never
// rename one; add new keys before Key::Count. The window layer maps GLFW codes to these values
// and drops keys that have no Key.
#pragma once

#include <cstdint>
#include <optional>
#include <string_view>

namespace cleave::input {

enum class Key : uint8_t {
  // clang-format off
  A, B, C, D, E, F, G, H, I, J, K, L, M, N, O, P, Q, R, S, T, U, V, W, X, Y, Z,
  Num0, Num1, Num2, Num3, Num4, Num5, Num6, Num7, Num8, Num9,
  Space, Escape, Enter, Tab, Backspace, Insert, Delete,
  Right, Left, Down, Up, PageUp, PageDown, Home, End,
  F1, F2, F3, F4, F5, F6, F7, F8, F9, F10, F11, F12,
  LeftShift, LeftControl, LeftAlt, RightShift, RightControl, RightAlt,
  Minus, Equal, Comma, Period, Slash, Semicolon, Apostrophe,
  LeftBracket, RightBracket, Backslash, GraveAccent, CapsLock,
  // clang-format on
  Count  // not a key: the number of keys
};

inline constexpr int kKeyCount = static_cast<int>(Key::Count);

enum class MouseButton : uint8_t { Left, Right, Middle, Count };

inline constexpr int kMouseButtonCount = static_cast<int>(MouseButton::Count);

// Stable name of a key or button; "?" for Count or an out-of-range value.
std::string_view keyName(Key key);
std::string_view mouseButtonName(MouseButton button);

// Inverse of keyName / mouseButtonName (exact, case-sensitive); nullopt for an unknown name.
std::optional<Key> keyFromName(std::string_view name);
std::optional<MouseButton> mouseButtonFromName(std::string_view name);

}  // namespace cleave::input
