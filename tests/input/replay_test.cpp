// SPDX-License-Identifier: MIT
#include "cleave/input/replay.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <random>
#include <string>

namespace cleave::input {
namespace {

constexpr const char* kValid =
    "cleave-replay 1\n"
    "# a comment line\n"
    "scene arena\n"
    "seed 42\n"
    "ticks 600\n"
    "\n"
    "12 kd:w mm:640,360,0,0\n"
    "13 mm:641.5,358,1.5,-2  # trailing comment\n"
    "30 ku:w md:left@640,360 mu:left@700,380\n"
    "31 sc:0,-1 rs:1280,720 kd:left_shift kd:f12\n";

Replay richReplay() {
  Replay replay;
  replay.scene = "scenes/tech_demo.json";
  replay.seed = 18446744073709551615ull;
  replay.ticks = 1000;
  for (uint64_t tick = 0; tick < 900; tick += 7) {
    InputFrame frame{tick, {}};
    frame.events.push_back(KeyDown{static_cast<Key>(tick % kKeyCount)});
    frame.events.push_back(MouseMove{0.1f * static_cast<float>(tick), -1.0f / 3.0f,
                                     1e-7f * static_cast<float>(tick), -123456.78f});
    frame.events.push_back(MouseDown{static_cast<MouseButton>(tick % 3), 1.25f, 1e6f});
    frame.events.push_back(MouseUp{MouseButton::Right, -0.0f, 3.0f});
    frame.events.push_back(Scroll{0.5f, -2.0f});
    frame.events.push_back(Resize{static_cast<int32_t>(tick), 720});
    frame.events.push_back(KeyUp{static_cast<Key>((tick * 5) % kKeyCount)});
    replay.frames.push_back(frame);
  }
  return replay;
}

TEST(ReplayParser, ParsesTheDocumentedExample) {
  const ReplayParseResult result = parseReplay(kValid, "example.replay");
  ASSERT_TRUE(result.ok()) << result.message;
  const Replay& replay = result.replay;
  EXPECT_EQ(replay.scene, "arena");
  EXPECT_EQ(replay.seed, 42u);
  EXPECT_EQ(replay.ticks, 600u);
  EXPECT_EQ(replay.length(), 600u);
  ASSERT_EQ(replay.frames.size(), 4u);
  EXPECT_EQ(replay.frames[0].tick, 12u);
  EXPECT_EQ(replay.frames[0].events, (std::vector<InputEvent>{KeyDown{Key::W},
                                                               MouseMove{640, 360, 0, 0}}));
  EXPECT_EQ(replay.frames[1].events,
            (std::vector<InputEvent>{MouseMove{641.5f, 358, 1.5f, -2}}));
  EXPECT_EQ(replay.frames[2].events,
            (std::vector<InputEvent>{KeyUp{Key::W}, MouseDown{MouseButton::Left, 640, 360},
                                     MouseUp{MouseButton::Left, 700, 380}}));
  EXPECT_EQ(replay.frames[3].events,
            (std::vector<InputEvent>{Scroll{0, -1}, Resize{1280, 720}, KeyDown{Key::LeftShift},
                                     KeyDown{Key::F12}}));
}

TEST(ReplayParser, MouseMoveWithoutDeltasUsesThePreviousPosition) {
  const ReplayParseResult result = parseReplay(
      "cleave-replay 1\nscene s\nseed 1\n0 mm:10,20\n1 md:left@15,25\n2 mm:12,30\n", "m.replay");
  ASSERT_TRUE(result.ok()) << result.message;
  EXPECT_EQ(result.replay.frames[0].events[0], InputEvent(MouseMove{10, 20, 10, 20}));
  EXPECT_EQ(result.replay.frames[2].events[0], InputEvent(MouseMove{12, 30, -3, 5}));
  EXPECT_FALSE(result.replay.ticks.has_value());
  EXPECT_EQ(result.replay.length(), 3u);
}

TEST(ReplayParser, AcceptsCrLfLineEndsAndTabs) {
  const ReplayParseResult result =
      parseReplay("cleave-replay 1\r\nscene s\r\nseed\t7\r\n3\tkd:a\r\n", "crlf.replay");
  ASSERT_TRUE(result.ok()) << result.message;
  EXPECT_EQ(result.replay.seed, 7u);
  EXPECT_EQ(result.replay.frames[0].events[0], InputEvent(KeyDown{Key::A}));
}

TEST(ReplayWriter, RoundTripsThroughTheParserExactly) {
  const Replay original = richReplay();
  ASSERT_EQ(validateReplay(original), "");
  const std::string text = writeReplay(original);
  const ReplayParseResult parsed = parseReplay(text, "rich.replay");
  ASSERT_TRUE(parsed.ok()) << parsed.message;
  EXPECT_EQ(parsed.replay, original);
  EXPECT_EQ(writeReplay(parsed.replay), text);
}

TEST(ReplayWriter, RoundTripsTheDocumentedExample) {
  const ReplayParseResult first = parseReplay(kValid, "example.replay");
  ASSERT_TRUE(first.ok());
  const ReplayParseResult second = parseReplay(writeReplay(first.replay), "again.replay");
  ASSERT_TRUE(second.ok()) << second.message;
  EXPECT_EQ(second.replay, first.replay);
}

TEST(ReplayWriter, WritesTheDocumentedSyntax) {
  Replay replay;
  replay.scene = "arena";
  replay.seed = 42;
  replay.frames = {InputFrame{12, {KeyDown{Key::W}, MouseMove{640, 360, 0.5f, -1}}},
                   InputFrame{30, {MouseDown{MouseButton::Left, 640, 360}, Scroll{0, -1},
                                   Resize{1280, 720}}}};
  EXPECT_EQ(writeReplay(replay),
            "cleave-replay 1\nscene arena\nseed 42\n"
            "12 kd:w mm:640,360,0.5,-1\n"
            "30 md:left@640,360 sc:0,-1 rs:1280,720\n");
}

TEST(ReplayWriter, ValidateRejectsWhatCannotRoundTrip) {
  Replay replay = richReplay();
  replay.scene = "two words";
  EXPECT_NE(validateReplay(replay), "");
  replay = richReplay();
  replay.frames.push_back(InputFrame{5, {KeyDown{Key::A}}});  // tick goes back
  EXPECT_NE(validateReplay(replay), "");
  replay = richReplay();
  replay.frames.push_back(InputFrame{950, {}});  // empty frame
  EXPECT_NE(validateReplay(replay), "");
  replay = richReplay();
  replay.frames.push_back(InputFrame{950, {Scroll{std::nanf(""), 0}}});
  EXPECT_NE(validateReplay(replay), "");
}

struct CorruptCase {
  const char* name;
  std::string text;
  size_t line;
  const char* reasonPart;
};

std::vector<CorruptCase> corruptCases() {
  const std::string head = "cleave-replay 1\nscene arena\nseed 42\n";
  return {
      {"empty file", "", 1, "empty"},
      {"missing header", "scene arena\nseed 1\n", 1, "missing header"},
      {"only comments", "# nothing\n\n", 2, "missing header"},
      {"wrong version", "cleave-replay 2\nscene a\nseed 1\n", 1, "version 2"},
      {"bad version", "cleave-replay one\n", 1, "bad version"},
      {"missing scene", "cleave-replay 1\nseed 1\n5 kd:w\n", 3, "scene"},
      {"missing seed at end", "cleave-replay 1\nscene a\n", 2, "seed"},
      {"duplicate seed", head + "seed 3\n", 4, "duplicate"},
      {"bad seed", "cleave-replay 1\nscene a\nseed -4\n", 3, "bad number"},
      {"seed overflow", "cleave-replay 1\nscene a\nseed 18446744073709551616\n", 3, "bad number"},
      {"unknown event", head + "1 kd:w zz:3\n", 4, "unknown event"},
      {"event without colon", head + "1 w\n", 4, "unknown event"},
      {"unknown key name", head + "1 kd:W\n", 4, "unknown key name"},
      {"unknown button", head + "1 md:back@1,2\n", 4, "unknown mouse button"},
      {"bad number", head + "1 mm:1,x\n", 4, "bad number"},
      {"nan", head + "1 sc:nan,0\n", 4, "bad number"},
      {"infinity", head + "1 mm:inf,0\n", 4, "bad number"},
      {"three mouse numbers", head + "1 mm:1,2,3\n", 4, "bad mouse move"},
      {"tick not increasing", head + "5 kd:w\n5 ku:w\n", 5, "strictly increasing"},
      {"tick going back", head + "5 kd:w\n# c\n3 ku:w\n", 6, "strictly increasing"},
      {"bad tick", head + "5x kd:w\n", 4, "bad tick"},
      {"tick without events", head + "5\n", 4, "no events"},
      {"truncated last line", head + "5 kd:w\n6 ku:", 5, "truncated"},
      {"truncated header", "cleave-replay 1\nscene ar", 2, "truncated"},
      {"binary bytes", head + std::string("5 kd:w\x00\x01\n", 9), 4, "unexpected byte 0x00"},
      {"high bytes", head + "5 kd:\xc3\xa9\n", 4, "unexpected byte 0xc3"},
      {"absurd tick", head + "99999999999 kd:w\n", 4, "absurd tick"},
      {"absurd coordinate", head + "1 mm:1e30,0\n", 4, "absurd value"},
      {"absurd scroll", head + "1 sc:0,1e9\n", 4, "absurd value"},
      {"absurd window", head + "1 rs:100000,720\n", 4, "absurd window size"},
      {"negative window", head + "1 rs:-1,720\n", 4, "bad number"},
      {"absurd length", head + "ticks 99999999999999\n", 4, "absurd length"},
      {"tick beyond length", head + "ticks 10\n10 kd:w\n", 5, "declared length"},
      {"header after events", head + "1 kd:w\nscene b\n", 5, "after the first tick"},
      {"unknown line", head + "hello world\n", 4, "unknown line"},
      {"scene with two words", "cleave-replay 1\nscene a b\n", 2, "exactly one value"},
      {"very long line", head + "1 " + std::string(70000, 'x') + "\n", 4, "longer than"},
  };
}

TEST(ReplayParser, EveryCorruptCaseNamesFileLineAndReason) {
  for (const CorruptCase& c : corruptCases()) {
    const ReplayParseResult result = parseReplay(c.text, "bad.replay");
    EXPECT_FALSE(result.ok()) << c.name;
    EXPECT_EQ(result.line, c.line) << c.name << ": " << result.message;
    const std::string prefix = "bad.replay:" + std::to_string(c.line) + ": ";
    EXPECT_EQ(result.message.rfind(prefix, 0), 0u) << c.name << ": " << result.message;
    EXPECT_NE(result.message.find(c.reasonPart), std::string::npos)
        << c.name << ": " << result.message;
  }
}

TEST(ReplayLoader, ReportsMissingFilesAndDirectories) {
  const std::string missing = std::string(CLEAVE_BINARY_DIR) + "/no_such_dir/none.replay";
  const ReplayParseResult result = loadReplay(missing);
  EXPECT_FALSE(result.ok());
  EXPECT_NE(result.message.find(missing), std::string::npos) << result.message;
  EXPECT_NE(result.message.find("no such file"), std::string::npos) << result.message;

  const ReplayParseResult directory = loadReplay(CLEAVE_BINARY_DIR);
  EXPECT_FALSE(directory.ok());
  EXPECT_NE(directory.message.find("directory"), std::string::npos) << directory.message;
}

TEST(ReplayLoader, SaveThenLoadRoundTrips) {
  const std::string path = std::string(CLEAVE_BINARY_DIR) + "/input_test_roundtrip.replay";
  const Replay original = richReplay();
  const ReplaySaveResult saved = saveReplay(path, original);
  ASSERT_TRUE(saved.ok()) << saved.message;
  const ReplayParseResult loaded = loadReplay(path);
  ASSERT_TRUE(loaded.ok()) << loaded.message;
  EXPECT_EQ(loaded.replay, original);
  std::filesystem::remove(path);
}

TEST(ReplayLoader, ParseErrorsNameThePath) {
  const std::string path = std::string(CLEAVE_BINARY_DIR) + "/input_test_bad.replay";
  {
    std::ofstream file(path, std::ios::binary);
    file << "cleave-replay 1\nscene a\nseed 1\n4 kd:nope\n";
  }
  const ReplayParseResult loaded = loadReplay(path);
  EXPECT_FALSE(loaded.ok());
  EXPECT_EQ(loaded.message.rfind(path + ":4: ", 0), 0u) << loaded.message;
  std::filesystem::remove(path);
}

TEST(ReplayLoader, SaveRefusesAnInvalidReplay) {
  Replay replay;
  replay.scene = "";
  const ReplaySaveResult saved =
      saveReplay(std::string(CLEAVE_BINARY_DIR) + "/input_test_never.replay", replay);
  EXPECT_FALSE(saved.ok());
  EXPECT_NE(saved.message.find("scene"), std::string::npos) << saved.message;
}

// Mutations of a valid replay must either parse into something that validates and round-trips,
// or fail with a located error; never crash, never throw.
TEST(ReplayParser, RandomMutationsNeverCrash) {
  const std::string base = writeReplay(richReplay()).substr(0, 2000) + "\n" + kValid;
  std::mt19937 rng(2024);
  int parsedCount = 0;
  int errorCount = 0;
  for (int iteration = 0; iteration < 4000; ++iteration) {
    std::string text = base;
    const int edits = 1 + static_cast<int>(rng() % 4);
    for (int e = 0; e < edits && !text.empty(); ++e) {
      const size_t at = rng() % text.size();
      switch (rng() % 5) {
        case 0:  // bit flip
          text[at] = static_cast<char>(text[at] ^ (1 << (rng() % 8)));
          break;
        case 1:  // truncation
          text.resize(at);
          break;
        case 2:  // random byte inserted
          text.insert(text.begin() + static_cast<std::ptrdiff_t>(at),
                      static_cast<char>(rng() % 256));
          break;
        case 3:  // delete a run
          text.erase(at, 1 + rng() % 8);
          break;
        default: {  // duplicate a chunk elsewhere
          const std::string chunk = text.substr(at, 1 + rng() % 20);
          text.insert(rng() % (text.size() + 1), chunk);
          break;
        }
      }
    }
    const ReplayParseResult result = parseReplay(text, "fuzz.replay");
    if (result.ok()) {
      ++parsedCount;
      ASSERT_EQ(validateReplay(result.replay), "") << text;
      const ReplayParseResult again = parseReplay(writeReplay(result.replay), "fuzz2.replay");
      ASSERT_TRUE(again.ok()) << again.message;
      ASSERT_EQ(again.replay, result.replay);
    } else {
      ++errorCount;
      ASSERT_EQ(result.message.rfind("fuzz.replay:", 0), 0u) << result.message;
      ASSERT_GE(result.line, 1u);
    }
  }
  EXPECT_GT(parsedCount, 0);
  EXPECT_GT(errorCount, 0);
}

}  // namespace
}  // namespace cleave::input
