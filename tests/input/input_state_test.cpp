// SPDX-License-Identifier: MIT
#include "cleave/input/input_state.h"

#include <gtest/gtest.h>

namespace cleave::input {
namespace {

InputFrame frame(uint64_t tick, std::vector<InputEvent> events) {
  return InputFrame{tick, std::move(events)};
}

TEST(InputState, PressedOnlyOnTheTickOfTheKeyDown) {
  InputState state;
  state.begin(frame(0, {KeyDown{Key::W}}));
  EXPECT_TRUE(state.pressed(Key::W));
  EXPECT_TRUE(state.held(Key::W));
  EXPECT_FALSE(state.released(Key::W));
  state.begin(frame(1, {}));
  EXPECT_FALSE(state.pressed(Key::W));
  EXPECT_TRUE(state.held(Key::W));
  state.begin(frame(2, {KeyUp{Key::W}}));
  EXPECT_FALSE(state.held(Key::W));
  EXPECT_TRUE(state.released(Key::W));
  EXPECT_FALSE(state.pressed(Key::W));
  state.begin(frame(3, {}));
  EXPECT_FALSE(state.released(Key::W));
  EXPECT_FALSE(state.held(Key::W));
}

TEST(InputState, TapWithinOneTickIsPressedAndReleasedButNotHeld) {
  InputState state;
  state.begin(frame(0, {KeyDown{Key::Space}, KeyUp{Key::Space}}));
  EXPECT_TRUE(state.pressed(Key::Space));
  EXPECT_TRUE(state.released(Key::Space));
  EXPECT_FALSE(state.held(Key::Space));
}

TEST(InputState, ReleaseAndPressAgainWithinOneTickStaysHeld) {
  InputState state;
  state.begin(frame(0, {KeyDown{Key::E}}));
  state.begin(frame(1, {KeyUp{Key::E}, KeyDown{Key::E}}));
  EXPECT_TRUE(state.pressed(Key::E));
  EXPECT_TRUE(state.released(Key::E));
  EXPECT_TRUE(state.held(Key::E));
}

TEST(InputState, RepeatedKeyDownIsNotANewPress) {
  InputState state;
  state.begin(frame(0, {KeyDown{Key::Q}}));
  state.begin(frame(1, {KeyDown{Key::Q}}));
  EXPECT_FALSE(state.pressed(Key::Q));
  EXPECT_TRUE(state.held(Key::Q));
  state.begin(frame(2, {KeyUp{Key::A}}));  // never pressed
  EXPECT_FALSE(state.released(Key::A));
}

TEST(InputState, KeysAreIndependent) {
  InputState state;
  state.begin(frame(0, {KeyDown{Key::LeftShift}, KeyDown{Key::F12}}));
  state.begin(frame(1, {KeyUp{Key::LeftShift}}));
  EXPECT_FALSE(state.held(Key::LeftShift));
  EXPECT_TRUE(state.held(Key::F12));
  EXPECT_FALSE(state.held(Key::A));
}

TEST(InputState, MouseButtonsFollowKeySemantics) {
  InputState state;
  state.begin(frame(0, {MouseDown{MouseButton::Left, 10, 20}}));
  EXPECT_TRUE(state.pressed(MouseButton::Left));
  EXPECT_TRUE(state.held(MouseButton::Left));
  EXPECT_FALSE(state.held(MouseButton::Right));
  EXPECT_EQ(state.mousePosition(), glm::vec2(10, 20));
  state.begin(frame(1, {MouseUp{MouseButton::Left, 30, 40}}));
  EXPECT_TRUE(state.released(MouseButton::Left));
  EXPECT_FALSE(state.held(MouseButton::Left));
  EXPECT_EQ(state.mousePosition(), glm::vec2(30, 40));
}

TEST(InputState, MouseDeltaAndScrollAreSummedPerTick) {
  InputState state;
  state.begin(frame(0, {MouseMove{101, 50, 1, 0}, MouseMove{103, 49, 2, -1}, Scroll{0, 1},
                        Scroll{0, 2}}));
  EXPECT_EQ(state.mousePosition(), glm::vec2(103, 49));
  EXPECT_EQ(state.mouseDelta(), glm::vec2(3, -1));
  EXPECT_EQ(state.scroll(), glm::vec2(0, 3));
  state.begin(frame(1, {}));
  EXPECT_EQ(state.mouseDelta(), glm::vec2(0, 0));
  EXPECT_EQ(state.scroll(), glm::vec2(0, 0));
  EXPECT_EQ(state.mousePosition(), glm::vec2(103, 49));
}

TEST(InputState, ResizeUpdatesWindowSizeAndFlagsTheTick) {
  InputState state({800, 600});
  EXPECT_EQ(state.windowSize(), glm::ivec2(800, 600));
  state.begin(frame(5, {Resize{1280, 720}}));
  EXPECT_TRUE(state.resized());
  EXPECT_EQ(state.windowSize(), glm::ivec2(1280, 720));
  EXPECT_EQ(state.tick(), 5u);
  state.begin(frame(6, {}));
  EXPECT_FALSE(state.resized());
  EXPECT_EQ(state.windowSize(), glm::ivec2(1280, 720));
}

TEST(InputState, ReleaseAllReleasesHeldKeysAndButtons) {
  InputState state;
  state.begin(frame(0, {KeyDown{Key::D}, MouseDown{MouseButton::Middle, 0, 0}}));
  state.releaseAll();
  EXPECT_FALSE(state.held(Key::D));
  EXPECT_TRUE(state.released(Key::D));
  EXPECT_FALSE(state.held(MouseButton::Middle));
  EXPECT_TRUE(state.released(MouseButton::Middle));
}

TEST(InputState, OutOfRangeKeyIsIgnored) {
  InputState state;
  state.begin(frame(0, {KeyDown{Key::Count}}));
  EXPECT_FALSE(state.held(Key::Count));
  EXPECT_FALSE(state.pressed(Key::Count));
}

}  // namespace
}  // namespace cleave::input
