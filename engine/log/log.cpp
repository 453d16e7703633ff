// SPDX-License-Identifier: MIT
#include "cleave/log/log.h"

#include <cstdarg>
#include <cstdio>
#include <mutex>
#include <string>

namespace cleave::log {

namespace {

std::mutex& sinkMutex() {
  static std::mutex mutex;
  return mutex;
}

Sink& currentSink() {
  static Sink sink;
  return sink;
}

std::string formatted(const char* format, va_list args) {
  va_list copy;
  va_copy(copy, args);
  const int size = std::vsnprintf(nullptr, 0, format, copy);
  va_end(copy);
  if (size <= 0) return {};
  std::string text(size_t(size) + 1, '\0');
  std::vsnprintf(text.data(), text.size(), format, args);
  text.resize(size_t(size));
  return text;
}

}  // namespace

namespace {

void writeFormatted(Level level, std::string_view source, const char* format, va_list args) {
  write(level, source, formatted(format, args));
}

}  // namespace

const char* toString(Level level) {
  switch (level) {
    case Level::Info: return "info";
    case Level::Warning: return "warning";
    case Level::Error: return "error";
  }
  return "?";
}

Sink setSink(Sink sink) {
  std::lock_guard<std::mutex> lock(sinkMutex());
  Sink previous = std::move(currentSink());
  currentSink() = std::move(sink);
  return previous;
}

void write(Level level, std::string_view source, std::string_view message) {
  std::lock_guard<std::mutex> lock(sinkMutex());
  if (currentSink()) {
    currentSink()(level, source, message);
  } else {
    printToConsole(level, source, message);
  }
}

void printToConsole(Level level, std::string_view source, std::string_view message) {
  std::FILE* out = level == Level::Info ? stdout : stderr;
  if (source.empty()) {
    std::fprintf(out, "%.*s\n", int(message.size()), message.data());
  } else {
    std::fprintf(out, "%.*s: %.*s\n", int(source.size()), source.data(), int(message.size()), message.data());
  }
  std::fflush(out);
}

void info(std::string_view source, const char* format, ...) {
  va_list args;
  va_start(args, format);
  writeFormatted(Level::Info, source, format, args);
  va_end(args);
}

void warning(std::string_view source, const char* format, ...) {
  va_list args;
  va_start(args, format);
  writeFormatted(Level::Warning, source, format, args);
  va_end(args);
}

void error(std::string_view source, const char* format, ...) {
  va_list args;
  va_start(args, format);
  writeFormatted(Level::Error, source, format, args);
  va_end(args);
}

}  // namespace cleave::log
