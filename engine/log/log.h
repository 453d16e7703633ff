// SPDX-License-Identifier: MIT
// The engine's messages: engine and component code never print; they hand each message to one sink
// the host sets (a game, a tool, a test, an editor's console). The default sink prints: Info to
// standard output, Warning and Error to standard error, as "<source>: <message>" (the message alone
// when the source is empty). Depends on the standard library only.
//
// Thread safety: setSink and write may be called from any thread; the sink is called with a lock
// held, one message at a time, on the thread that wrote it (keep it short; do not write from it).
#pragma once

#include <functional>
#include <string_view>

namespace cleave::log {

enum class Level { Info, Warning, Error };

const char* toString(Level level);  // "info", "warning", "error"

using Sink = std::function<void(Level level, std::string_view source, std::string_view message)>;

// Replaces the sink; an empty Sink restores the default. Returns the sink it replaced (empty when
// that was the default), so a scope can put it back.
Sink setSink(Sink sink);

// Hands one message to the sink. `source` names the part that speaks ("cleave", "glfw", ...).
void write(Level level, std::string_view source, std::string_view message);

// printf-style forms of write (the message is formatted into a string first).
[[gnu::format(printf, 2, 3)]] void info(std::string_view source, const char* format, ...);
[[gnu::format(printf, 2, 3)]] void warning(std::string_view source, const char* format, ...);
[[gnu::format(printf, 2, 3)]] void error(std::string_view source, const char* format, ...);

// The default sink.
void printToConsole(Level level, std::string_view source, std::string_view message);

// Sets a sink for the lifetime of the object and restores the previous one after (tests).
class ScopedSink {
 public:
  explicit ScopedSink(Sink sink) : previous_(setSink(std::move(sink))) {}
  ~ScopedSink() { setSink(std::move(previous_)); }
  ScopedSink(const ScopedSink&) = delete;
  ScopedSink& operator=(const ScopedSink&) = delete;

 private:
  Sink previous_;
};

}  // namespace cleave::log
