// SPDX-License-Identifier: MIT
// Replays: the input events of a run, per tick, in a versioned line-based text format.
//
// The format is specified in docs/replay-format.md. In short:
//
//   cleave-replay 1
//   scene arena
//   seed 42
//   ticks 600
//   12 kd:w mm:640,360,0,0
//   30 ku:w md:left@640,360
//
// parseReplay/loadReplay never throw and never crash: any input, including binary garbage, gives
// either a Replay or an error naming the file, the line and the reason. writeReplay is the exact
// inverse of parseReplay for every valid Replay (parse(write(r)) == r).
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "cleave/base/status.h"
#include "cleave/input/input_event.h"

namespace cleave::input {

inline constexpr int kReplayVersion = 1;

// Limits above which a value is rejected as absurd (a corrupt or hostile file).
inline constexpr uint64_t kMaxReplayTick = 1'000'000'000;  // about 193 days at 60 Hz
inline constexpr float kMaxMouseCoordinate = 1.0e7f;        // |x|, |y|, |dx|, |dy| in pixels
inline constexpr float kMaxScroll = 1.0e4f;                 // |dx|, |dy| in wheel steps
inline constexpr int32_t kMaxWindowSize = 65536;            // width, height in pixels
inline constexpr size_t kMaxReplayLineLength = 65536;       // characters, without the newline
inline constexpr size_t kMaxSceneNameLength = 256;
inline constexpr uint64_t kMaxReplayFileBytes = 256ull << 20;

struct Replay {
  std::string scene;  // scene to load: one word of printable ASCII, no '#'
  uint64_t seed = 0;  // seed of the run's RNG
  // Declared length in ticks; when set, every frame's tick is below it.
  std::optional<uint64_t> ticks;
  // Only ticks that have events, ticks strictly increasing, every frame non-empty.
  std::vector<InputFrame> frames;

  // Number of ticks to run: `ticks` if declared, else the last frame's tick + 1 (0 if no frames).
  uint64_t length() const;

  bool operator==(const Replay&) const = default;
};

// A Status (message "<file>:<line>: <reason>" or "<file>: <reason>", empty when ok) with the replay.
struct ReplayParseResult : base::Status {
  Replay replay;      // valid only when ok
  size_t line = 0;    // 1-based line of the error; 0 for file-level errors or when ok
};

// Parses replay text. fileName is only used in error messages.
ReplayParseResult parseReplay(std::string_view text, std::string_view fileName);

// Reads and parses a file; also reports missing, unreadable, directory and oversized files.
ReplayParseResult loadReplay(const std::string& path);

// Empty if the replay can be written and read back unchanged; otherwise the first problem
// (scene name, tick order, empty frame, absurd or non-finite value, unknown key/button).
std::string validateReplay(const Replay& replay);

// Text of a replay in the format above, ending with a newline. Precondition: validateReplay(replay)
// is empty (otherwise the text is still produced but parseReplay will reject it).
std::string writeReplay(const Replay& replay);

// Ok, or the code with "<path>: <reason>".
using ReplaySaveResult = base::Status;

// Validates and writes a replay file (replacing an existing file).
ReplaySaveResult saveReplay(const std::string& path, const Replay& replay);

// One event in the replay syntax, e.g. "kd:w", "mm:640,360,1.5,-2"; "" for an invalid key/button.
std::string formatEvent(const InputEvent& event);

// Records the frames of a run as they are played, for writeReplay/saveReplay.
class ReplayRecorder {
 public:
  ReplayRecorder(std::string scene, uint64_t seed);

  // Appends the frame's events. Every call, even with no events, extends the recorded length to
  // frame.tick + 1. Events of a tick equal to the last recorded one are appended to that frame;
  // a frame with an older tick is dropped (counted in droppedFrames()).
  void record(const InputFrame& frame);

  const Replay& replay() const { return replay_; }
  size_t droppedFrames() const { return dropped_; }

 private:
  Replay replay_;
  size_t dropped_ = 0;
};

}  // namespace cleave::input
