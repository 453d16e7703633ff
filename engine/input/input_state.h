// SPDX-License-Identifier: MIT
// InputState: the events of each tick folded into "held", "pressed this tick", "released this
// tick", the mouse position and motion, scroll and window size. Gameplay reads this, not events.
//
//   state.begin(frame);                 // once per tick, before gameplay
//   if (state.pressed(Key::Space)) jump();
//   if (state.held(Key::W)) walk();
//
// Semantics per tick: pressed(k) is true if k went from up to down during the tick; released(k)
// if it went from down to up; held(k) is the state after the last event of the tick. A key pressed
// and released within one tick is pressed() and released() but not held(). A KeyDown for a key
// already held (auto-repeat) and a KeyUp for a key not held change nothing. Mouse buttons follow
// the same rules. mouseDelta() and scroll() are sums over the tick; mousePosition() is the last
// reported position (MouseMove, MouseDown or MouseUp). Out-of-range keys/buttons are ignored.
#pragma once

#include <bitset>
#include <cstdint>

#include <glm/vec2.hpp>

#include "cleave/input/input_event.h"
#include "cleave/input/key.h"

namespace cleave::input {

class InputState {
 public:
  // windowSize: the size before any Resize event (0 x 0 if unknown).
  explicit InputState(glm::ivec2 windowSize = {0, 0}) : windowSize_(windowSize) {}

  // Starts tick frame.tick: clears the per-tick edges and sums, then applies the events in order.
  void begin(const InputFrame& frame);

  // Releases everything (e.g. when the window loses focus); the edges of the current tick stay.
  void releaseAll();

  bool held(Key key) const { return test(keysHeld_, static_cast<size_t>(key)); }
  bool pressed(Key key) const { return test(keysPressed_, static_cast<size_t>(key)); }
  bool released(Key key) const { return test(keysReleased_, static_cast<size_t>(key)); }

  bool held(MouseButton button) const { return test(buttonsHeld_, static_cast<size_t>(button)); }
  bool pressed(MouseButton button) const {
    return test(buttonsPressed_, static_cast<size_t>(button));
  }
  bool released(MouseButton button) const {
    return test(buttonsReleased_, static_cast<size_t>(button));
  }

  glm::vec2 mousePosition() const { return mousePosition_; }  // window pixels
  glm::vec2 mouseDelta() const { return mouseDelta_; }        // pixels moved this tick
  glm::vec2 scroll() const { return scroll_; }                // wheel steps this tick
  glm::ivec2 windowSize() const { return windowSize_; }       // pixels
  bool resized() const { return resized_; }                   // a Resize event this tick
  uint64_t tick() const { return tick_; }                     // tick of the last begin()

 private:
  template <size_t N>
  static bool test(const std::bitset<N>& bits, size_t index) {
    return index < N && bits.test(index);
  }

  std::bitset<kKeyCount> keysHeld_, keysPressed_, keysReleased_;
  std::bitset<kMouseButtonCount> buttonsHeld_, buttonsPressed_, buttonsReleased_;
  glm::vec2 mousePosition_{0.0f};
  glm::vec2 mouseDelta_{0.0f};
  glm::vec2 scroll_{0.0f};
  glm::ivec2 windowSize_;
  bool resized_ = false;
  uint64_t tick_ = 0;
};

}  // namespace cleave::input
