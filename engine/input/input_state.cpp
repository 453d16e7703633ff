// SPDX-License-Identifier: MIT
#include "cleave/input/input_state.h"

#include <type_traits>

namespace cleave::input {
namespace {

// Applies one down/up transition to a held set and records the edge.
template <size_t N>
void press(std::bitset<N>& held, std::bitset<N>& pressed, size_t index) {
  if (index >= N || held.test(index)) return;  // out of range, or auto-repeat
  held.set(index);
  pressed.set(index);
}

template <size_t N>
void release(std::bitset<N>& held, std::bitset<N>& released, size_t index) {
  if (index >= N || !held.test(index)) return;
  held.reset(index);
  released.set(index);
}

}  // namespace

void InputState::begin(const InputFrame& frame) {
  tick_ = frame.tick;
  keysPressed_.reset();
  keysReleased_.reset();
  buttonsPressed_.reset();
  buttonsReleased_.reset();
  mouseDelta_ = glm::vec2(0.0f);
  scroll_ = glm::vec2(0.0f);
  resized_ = false;

  for (const InputEvent& event : frame.events) {
    std::visit(
        [this](const auto& e) {
          using E = std::decay_t<decltype(e)>;
          if constexpr (std::is_same_v<E, KeyDown>) {
            press(keysHeld_, keysPressed_, static_cast<size_t>(e.key));
          } else if constexpr (std::is_same_v<E, KeyUp>) {
            release(keysHeld_, keysReleased_, static_cast<size_t>(e.key));
          } else if constexpr (std::is_same_v<E, MouseMove>) {
            mousePosition_ = {e.x, e.y};
            mouseDelta_ += glm::vec2(e.dx, e.dy);
          } else if constexpr (std::is_same_v<E, MouseDown>) {
            mousePosition_ = {e.x, e.y};
            press(buttonsHeld_, buttonsPressed_, static_cast<size_t>(e.button));
          } else if constexpr (std::is_same_v<E, MouseUp>) {
            mousePosition_ = {e.x, e.y};
            release(buttonsHeld_, buttonsReleased_, static_cast<size_t>(e.button));
          } else if constexpr (std::is_same_v<E, Scroll>) {
            scroll_ += glm::vec2(e.dx, e.dy);
          } else if constexpr (std::is_same_v<E, Resize>) {
            windowSize_ = {e.width, e.height};
            resized_ = true;
          } else {
            static_assert(sizeof(E) == 0, "unhandled input event type");
          }
        },
        event);
  }
}

void InputState::releaseAll() {
  keysReleased_ |= keysHeld_;
  buttonsReleased_ |= buttonsHeld_;
  keysHeld_.reset();
  buttonsHeld_.reset();
}

}  // namespace cleave::input
