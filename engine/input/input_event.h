// SPDX-License-Identifier: MIT
// Input events of one simulation tick, as produced by the window layer or read from a replay.
//
// Coordinates are window pixels with the origin at the top-left corner and y pointing down (the
// GLFW convention), as floats. Scroll offsets are wheel steps (GLFW offsets; y > 0 scrolls up /
// away from the user). Sizes are window pixels. Events are plain values compared member-wise.
#pragma once

#include <cstdint>
#include <variant>
#include <vector>

#include "cleave/input/key.h"

namespace cleave::input {

struct KeyDown {
  Key key = Key::Space;
  bool operator==(const KeyDown&) const = default;
};

struct KeyUp {
  Key key = Key::Space;
  bool operator==(const KeyUp&) const = default;
};

// Cursor moved to (x, y); (dx, dy) is the motion since the previous MouseMove. With a captured
// cursor (first-person camera) the position is virtual and unbounded; use the deltas.
struct MouseMove {
  float x = 0.0f;
  float y = 0.0f;
  float dx = 0.0f;
  float dy = 0.0f;
  bool operator==(const MouseMove&) const = default;
};

// Button pressed / released with the cursor at (x, y).
struct MouseDown {
  MouseButton button = MouseButton::Left;
  float x = 0.0f;
  float y = 0.0f;
  bool operator==(const MouseDown&) const = default;
};

struct MouseUp {
  MouseButton button = MouseButton::Left;
  float x = 0.0f;
  float y = 0.0f;
  bool operator==(const MouseUp&) const = default;
};

struct Scroll {
  float dx = 0.0f;
  float dy = 0.0f;
  bool operator==(const Scroll&) const = default;
};

// The window's client area now measures width x height pixels (0 x 0 when minimised).
struct Resize {
  int32_t width = 0;
  int32_t height = 0;
  bool operator==(const Resize&) const = default;
};

using InputEvent = std::variant<KeyDown, KeyUp, MouseMove, MouseDown, MouseUp, Scroll, Resize>;

// The events of one tick, in the order they happened.
struct InputFrame {
  uint64_t tick = 0;
  std::vector<InputEvent> events;
  bool operator==(const InputFrame&) const = default;
};

}  // namespace cleave::input
