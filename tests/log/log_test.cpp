// SPDX-License-Identifier: MIT
// The message sink (engine/log/log.h): messages reach the sink the host sets, formatted, with their
// level and source; an empty sink restores the default; ScopedSink puts the previous one back;
// writes from several threads arrive whole, one at a time.
#include <gtest/gtest.h>

#include <string>
#include <thread>
#include <vector>

#include "cleave/log/log.h"

namespace cleave::log {
namespace {

struct Captured {
  Level level;
  std::string source;
  std::string message;
};

TEST(Log, MessagesReachTheHostsSinkFormattedWithLevelAndSource) {
  std::vector<Captured> got;
  {
    ScopedSink scope([&](Level level, std::string_view source, std::string_view message) {
      got.push_back({level, std::string(source), std::string(message)});
    });
    warning("cleave", "split of %s (entity %u) kept whole: %s", "crate", 7u, "open section");
    info("", "state-hash: %016llx", 0xabcull);
    error("glfw", "error 0x%x", 0x10008);
    write(Level::Info, "tool", "plain text, no format: 100%");
  }
  ASSERT_EQ(got.size(), 4u);
  EXPECT_EQ(got[0].level, Level::Warning);
  EXPECT_EQ(got[0].source, "cleave");
  EXPECT_EQ(got[0].message, "split of crate (entity 7) kept whole: open section");
  EXPECT_EQ(got[1].message, "state-hash: 0000000000000abc");
  EXPECT_EQ(got[2].level, Level::Error);
  EXPECT_EQ(got[2].message, "error 0x10008");
  EXPECT_EQ(got[3].message, "plain text, no format: 100%");
  EXPECT_STREQ(toString(Level::Warning), "warning");
}

TEST(Log, ScopedSinksNestAndTheDefaultComesBack) {
  int outer = 0, inner = 0;
  {
    ScopedSink a([&](Level, std::string_view, std::string_view) { ++outer; });
    info("t", "one");
    {
      ScopedSink b([&](Level, std::string_view, std::string_view) { ++inner; });
      info("t", "two");
    }
    info("t", "three");
  }
  EXPECT_EQ(outer, 2);
  EXPECT_EQ(inner, 1);
  // Back to the default: setSink returns an empty sink for it.
  EXPECT_FALSE(setSink({}));
}

TEST(Log, WritesFromManyThreadsArriveWholeAndOneAtATime) {
  std::vector<std::string> got;
  int inside = 0, overlaps = 0;
  ScopedSink scope([&](Level, std::string_view, std::string_view message) {
    if (++inside > 1) ++overlaps;
    got.emplace_back(message);
    --inside;
  });
  std::vector<std::thread> threads;
  for (int t = 0; t < 4; ++t)
    threads.emplace_back([t] {
      for (int k = 0; k < 250; ++k) info("worker", "thread %d message %d", t, k);
    });
  for (std::thread& thread : threads) thread.join();
  EXPECT_EQ(got.size(), 1000u);
  EXPECT_EQ(overlaps, 0);
  for (const std::string& m : got) EXPECT_EQ(m.rfind("thread ", 0), 0u) << m;
}

}  // namespace
}  // namespace cleave::log
