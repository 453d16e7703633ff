// SPDX-License-Identifier: MIT
#include "cleave/input/input_source.h"

#include <gtest/gtest.h>

namespace cleave::input {
namespace {

TEST(LiveQueue, NextDrainsPushedEventsInOrder) {
  LiveQueue queue;
  queue.push(KeyDown{Key::A});
  queue.push(MouseMove{1, 2, 1, 2});
  EXPECT_EQ(queue.pending(), 2u);
  InputFrame frame;
  EXPECT_TRUE(queue.next(7, frame));
  EXPECT_EQ(frame.tick, 7u);
  const std::vector<InputEvent> expected{KeyDown{Key::A}, MouseMove{1, 2, 1, 2}};
  EXPECT_EQ(frame.events, expected);
  EXPECT_EQ(queue.pending(), 0u);
  EXPECT_TRUE(queue.next(8, frame));
  EXPECT_TRUE(frame.events.empty());
}

Replay sampleReplay() {
  Replay replay;
  replay.scene = "arena";
  replay.seed = 1;
  replay.ticks = 6;
  replay.frames = {InputFrame{1, {KeyDown{Key::W}}}, InputFrame{3, {KeyUp{Key::W}}},
                   InputFrame{4, {Scroll{0, 1}}}};
  return replay;
}

TEST(ReplaySource, GivesRecordedEventsPerTickAndFinishesAtLength) {
  ReplaySource source(sampleReplay());
  EXPECT_EQ(source.length(), 6u);
  InputFrame frame;
  std::vector<size_t> counts;
  uint64_t tick = 0;
  while (source.next(tick, frame)) {
    EXPECT_EQ(frame.tick, tick);
    counts.push_back(frame.events.size());
    ++tick;
  }
  EXPECT_EQ(tick, 6u);
  EXPECT_TRUE(source.finished());
  EXPECT_TRUE(frame.events.empty());
  EXPECT_EQ(counts, (std::vector<size_t>{0, 1, 0, 1, 1, 0}));
  EXPECT_EQ(source.droppedFrames(), 0u);
}

TEST(ReplaySource, SkippedTicksDropTheirFrames) {
  ReplaySource source(sampleReplay());
  InputFrame frame;
  ASSERT_TRUE(source.next(4, frame));
  EXPECT_EQ(frame.events, (std::vector<InputEvent>{Scroll{0, 1}}));
  EXPECT_EQ(source.droppedFrames(), 2u);
  ASSERT_TRUE(source.next(4, frame));  // same tick again: no events the second time
  EXPECT_TRUE(frame.events.empty());
}

TEST(ReplaySource, LengthWithoutDeclaredTicksIsLastTickPlusOne) {
  Replay replay = sampleReplay();
  replay.ticks.reset();
  ReplaySource source(std::move(replay));
  EXPECT_EQ(source.length(), 5u);
  InputFrame frame;
  EXPECT_TRUE(source.next(4, frame));
  EXPECT_FALSE(source.next(5, frame));
  EXPECT_TRUE(source.finished());
}

TEST(ReplayRecorder, RecordsNonEmptyFramesAndTheFullLength) {
  ReplayRecorder recorder("demo", 9);
  recorder.record(InputFrame{0, {}});
  recorder.record(InputFrame{1, {KeyDown{Key::Space}}});
  recorder.record(InputFrame{1, {KeyUp{Key::Space}}});  // same tick: merged
  recorder.record(InputFrame{0, {KeyDown{Key::A}}});    // older tick: dropped
  recorder.record(InputFrame{9, {}});
  const Replay& replay = recorder.replay();
  EXPECT_EQ(replay.scene, "demo");
  EXPECT_EQ(replay.seed, 9u);
  EXPECT_EQ(replay.ticks, 10u);
  ASSERT_EQ(replay.frames.size(), 1u);
  EXPECT_EQ(replay.frames[0].events,
            (std::vector<InputEvent>{KeyDown{Key::Space}, KeyUp{Key::Space}}));
  EXPECT_EQ(recorder.droppedFrames(), 1u);
}

}  // namespace
}  // namespace cleave::input
