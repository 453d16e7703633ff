// SPDX-License-Identifier: MIT
#include "cleave/input/replay.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <fstream>
#include <system_error>
#include <type_traits>
#include <utility>

namespace cleave::input {
namespace {

// ---------------------------------------------------------------------------------------------
// Small parsing helpers. All take string_views and return nullopt instead of throwing.

bool isSpace(char c) { return c == ' ' || c == '\t'; }

std::vector<std::string_view> splitWords(std::string_view line) {
  std::vector<std::string_view> words;
  size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && isSpace(line[i])) ++i;
    const size_t start = i;
    while (i < line.size() && !isSpace(line[i])) ++i;
    if (i > start) words.push_back(line.substr(start, i - start));
  }
  return words;
}

std::optional<uint64_t> parseU64(std::string_view text) {
  if (text.empty()) return std::nullopt;
  for (char c : text)
    if (c < '0' || c > '9') return std::nullopt;
  uint64_t value = 0;
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (error != std::errc() || end != text.data() + text.size()) return std::nullopt;
  return value;
}

std::optional<float> parseFloat(std::string_view text) {
  if (text.empty()) return std::nullopt;
  float value = 0.0f;
  const auto [end, error] =
      std::from_chars(text.data(), text.data() + text.size(), value, std::chars_format::general);
  if (error != std::errc() || end != text.data() + text.size()) return std::nullopt;
  return value;
}

std::string formatFloat(float value) {
  char buffer[64];
  // Shortest representation that reads back to the same float: this is what makes the writer an
  // exact inverse of the parser.
  const auto [end, error] = std::to_chars(buffer, buffer + sizeof(buffer), value);
  if (error != std::errc()) return "0";
  return std::string(buffer, end);
}

// Splits "a,b,c" at commas; nullopt unless there are minCount..maxCount parts.
std::optional<std::vector<std::string_view>> splitCommas(std::string_view text, size_t minCount,
                                                         size_t maxCount) {
  std::vector<std::string_view> parts;
  size_t start = 0;
  while (true) {
    const size_t comma = text.find(',', start);
    const size_t length = comma == std::string_view::npos ? text.npos : comma - start;
    parts.push_back(text.substr(start, length));
    if (parts.size() > maxCount) return std::nullopt;
    if (comma == std::string_view::npos) break;
    start = comma + 1;
  }
  if (parts.size() < minCount) return std::nullopt;
  return parts;
}

bool validSceneName(std::string_view name) {
  if (name.empty() || name.size() > kMaxSceneNameLength) return false;
  for (char c : name)
    if (c <= ' ' || c > '~' || c == '#') return false;
  return true;
}

// ---------------------------------------------------------------------------------------------
// Event syntax.

struct EventParse {
  std::optional<InputEvent> event;
  std::string error;
};

EventParse eventError(std::string reason) { return EventParse{std::nullopt, std::move(reason)}; }

std::string quoted(std::string_view text) {
  std::string result = "'";
  result += text;
  result += "'";
  return result;
}

// Parses a list of floats with the given bound; fills `error` on failure.
bool parseFloats(const std::vector<std::string_view>& parts, float bound, std::string_view word,
                 float* out, std::string& error) {
  for (size_t i = 0; i < parts.size(); ++i) {
    const std::optional<float> value = parseFloat(parts[i]);
    if (!value || !std::isfinite(*value)) {
      error = "bad number " + quoted(parts[i]) + " in " + quoted(word);
      return false;
    }
    if (std::fabs(*value) > bound) {
      error = "absurd value " + quoted(parts[i]) + " in " + quoted(word) + " (limit " +
              formatFloat(bound) + ")";
      return false;
    }
    out[i] = *value;
  }
  return true;
}

// `lastMouse` is the last cursor position seen in this replay, for "mm:x,y" without deltas.
EventParse parseEvent(std::string_view word, float lastMouse[2]) {
  const size_t colon = word.find(':');
  if (colon == std::string_view::npos)
    return eventError("unknown event " + quoted(word) +
                      " (expected kind:arguments, e.g. kd:w, mm:640,360,0,0)");
  const std::string_view kind = word.substr(0, colon);
  const std::string_view args = word.substr(colon + 1);
  std::string error;

  if (kind == "kd" || kind == "ku") {
    const std::optional<Key> key = keyFromName(args);
    if (!key) return eventError("unknown key name " + quoted(args) + " in " + quoted(word));
    if (kind == "kd") return EventParse{KeyDown{*key}, {}};
    return EventParse{KeyUp{*key}, {}};
  }
  if (kind == "mm") {
    const auto parts = splitCommas(args, 2, 4);
    if (!parts || parts->size() == 3)
      return eventError("bad mouse move " + quoted(word) + " (expected mm:x,y or mm:x,y,dx,dy)");
    float values[4] = {0, 0, 0, 0};
    if (!parseFloats(*parts, kMaxMouseCoordinate, word, values, error)) return eventError(error);
    if (parts->size() == 2) {
      values[2] = values[0] - lastMouse[0];
      values[3] = values[1] - lastMouse[1];
    }
    lastMouse[0] = values[0];
    lastMouse[1] = values[1];
    return EventParse{MouseMove{values[0], values[1], values[2], values[3]}, {}};
  }
  if (kind == "md" || kind == "mu") {
    const size_t at = args.find('@');
    if (at == std::string_view::npos)
      return eventError("bad mouse button event " + quoted(word) +
                        " (expected md:button@x,y, e.g. md:left@640,360)");
    const std::string_view name = args.substr(0, at);
    const std::optional<MouseButton> button = mouseButtonFromName(name);
    if (!button)
      return eventError("unknown mouse button " + quoted(name) + " in " + quoted(word) +
                        " (expected left, right or middle)");
    const auto parts = splitCommas(args.substr(at + 1), 2, 2);
    if (!parts)
      return eventError("bad mouse button event " + quoted(word) + " (expected md:button@x,y)");
    float values[2] = {0, 0};
    if (!parseFloats(*parts, kMaxMouseCoordinate, word, values, error)) return eventError(error);
    lastMouse[0] = values[0];
    lastMouse[1] = values[1];
    if (kind == "md") return EventParse{MouseDown{*button, values[0], values[1]}, {}};
    return EventParse{MouseUp{*button, values[0], values[1]}, {}};
  }
  if (kind == "sc") {
    const auto parts = splitCommas(args, 2, 2);
    if (!parts) return eventError("bad scroll " + quoted(word) + " (expected sc:dx,dy)");
    float values[2] = {0, 0};
    if (!parseFloats(*parts, kMaxScroll, word, values, error)) return eventError(error);
    return EventParse{Scroll{values[0], values[1]}, {}};
  }
  if (kind == "rs") {
    const auto parts = splitCommas(args, 2, 2);
    if (!parts) return eventError("bad resize " + quoted(word) + " (expected rs:width,height)");
    int32_t size[2] = {0, 0};
    for (size_t i = 0; i < 2; ++i) {
      const std::optional<uint64_t> value = parseU64((*parts)[i]);
      if (!value) return eventError("bad number " + quoted((*parts)[i]) + " in " + quoted(word));
      if (*value > static_cast<uint64_t>(kMaxWindowSize))
        return eventError("absurd window size " + quoted((*parts)[i]) + " in " + quoted(word) +
                          " (limit " + std::to_string(kMaxWindowSize) + ")");
      size[i] = static_cast<int32_t>(*value);
    }
    return EventParse{Resize{size[0], size[1]}, {}};
  }
  return eventError("unknown event " + quoted(word) + " (expected kd, ku, mm, md, mu, sc or rs)");
}

// ---------------------------------------------------------------------------------------------
// The parser proper: one pass over the lines.

class Parser {
 public:
  Parser(std::string_view text, std::string_view fileName) : text_(text), fileName_(fileName) {}

  ReplayParseResult run() {
    size_t position = 0;
    while (position < text_.size()) {
      ++lineNumber_;
      const size_t newline = text_.find('\n', position);
      const bool terminated = newline != std::string_view::npos;
      std::string_view line =
          text_.substr(position, terminated ? newline - position : std::string_view::npos);
      position = terminated ? newline + 1 : text_.size();

      if (!terminated)
        return fail("truncated last line (the file does not end with a newline)");
      if (line.size() > kMaxReplayLineLength)
        return fail("line longer than " + std::to_string(kMaxReplayLineLength) + " characters");
      if (!line.empty() && line.back() == '\r') line.remove_suffix(1);  // CRLF line ends
      if (!checkBytes(line)) return result_;
      if (const size_t hash = line.find('#'); hash != std::string_view::npos)
        line = line.substr(0, hash);
      const std::vector<std::string_view> words = splitWords(line);
      if (words.empty()) continue;
      if (!handle(words)) return result_;
    }
    if (lineNumber_ == 0 || !sawVersion_) {
      lineNumber_ = std::max<size_t>(lineNumber_, 1);
      return fail(text_.empty() ? "missing header: the file is empty"
                                : "missing header line 'cleave-replay 1'");
    }
    if (!checkHeaderComplete()) return result_;
    result_.code = base::StatusCode::Ok;
    result_.line = 0;
    result_.message.clear();
    return std::move(result_);
  }

 private:
  ReplayParseResult fail(std::string reason) {
    result_.line = lineNumber_;
    result_.setFailure(base::StatusCode::ParseError,
                       std::string(fileName_) + ":" + std::to_string(lineNumber_) + ": " + reason);
    result_.replay = Replay{};
    return result_;
  }

  // Printable ASCII and tabs only; bytes >= 0x80 are tolerated inside comments (UTF-8 prose).
  bool checkBytes(std::string_view line) {
    bool inComment = false;
    for (size_t i = 0; i < line.size(); ++i) {
      const auto byte = static_cast<unsigned char>(line[i]);
      if (byte == '#') inComment = true;
      const bool printable = (byte >= 0x20 && byte < 0x7f) || byte == '\t';
      if (printable || (inComment && byte >= 0x80)) continue;
      char hex[8];
      std::snprintf(hex, sizeof(hex), "0x%02x", byte);
      fail(std::string("unexpected byte ") + hex + " at column " + std::to_string(i + 1) +
           " (binary data or non-ASCII text; a replay is plain ASCII)");
      return false;
    }
    return true;
  }

  bool handle(const std::vector<std::string_view>& words) {
    const std::string_view key = words[0];
    if (!sawVersion_) {
      if (key != "cleave-replay") {
        fail("missing header line 'cleave-replay 1' (found " + quoted(key) + ")");
        return false;
      }
      if (words.size() != 2) {
        fail("the header line must be 'cleave-replay <version>'");
        return false;
      }
      const std::optional<uint64_t> version = parseU64(words[1]);
      if (!version) {
        fail("bad version number " + quoted(words[1]));
        return false;
      }
      if (*version != static_cast<uint64_t>(kReplayVersion)) {
        fail("unsupported replay version " + std::string(words[1]) + " (this build reads version " +
             std::to_string(kReplayVersion) + ")");
        return false;
      }
      sawVersion_ = true;
      return true;
    }
    if (key == "cleave-replay") {
      fail("duplicate 'cleave-replay' header line");
      return false;
    }
    if (key == "scene" || key == "seed" || key == "ticks") return handleHeader(words);
    if (key[0] >= '0' && key[0] <= '9') return handleTick(words);
    fail("unknown line starting with " + quoted(key) +
         " (expected a header line scene/seed/ticks or '<tick> <event>...')");
    return false;
  }

  bool handleHeader(const std::vector<std::string_view>& words) {
    const std::string_view key = words[0];
    if (sawTick_) {
      fail("header line " + quoted(key) + " after the first tick line");
      return false;
    }
    if (words.size() != 2) {
      fail("header line " + quoted(key) + " needs exactly one value");
      return false;
    }
    const std::string_view value = words[1];
    if (key == "scene") {
      if (sawScene_) return failBool("duplicate 'scene' header line");
      if (!validSceneName(value))
        return failBool("bad scene name " + quoted(value) +
                        " (one word of printable ASCII, at most " +
                        std::to_string(kMaxSceneNameLength) + " characters, no '#')");
      result_.replay.scene = std::string(value);
      sawScene_ = true;
      return true;
    }
    if (key == "seed") {
      if (sawSeed_) return failBool("duplicate 'seed' header line");
      const std::optional<uint64_t> seed = parseU64(value);
      if (!seed)
        return failBool("bad number " + quoted(value) +
                        " for the seed (an unsigned 64-bit integer)");
      result_.replay.seed = *seed;
      sawSeed_ = true;
      return true;
    }
    // ticks
    if (result_.replay.ticks) return failBool("duplicate 'ticks' header line");
    const std::optional<uint64_t> ticks = parseU64(value);
    if (!ticks) return failBool("bad number " + quoted(value) + " for the length in ticks");
    if (*ticks > kMaxReplayTick + 1)
      return failBool("absurd length of " + std::string(value) + " ticks (limit " +
                      std::to_string(kMaxReplayTick + 1) + ")");
    result_.replay.ticks = *ticks;
    return true;
  }

  bool handleTick(const std::vector<std::string_view>& words) {
    if (!sawTick_ && !checkHeaderComplete()) return false;
    sawTick_ = true;
    const std::optional<uint64_t> tick = parseU64(words[0]);
    if (!tick) return failBool("bad tick number " + quoted(words[0]));
    if (*tick > kMaxReplayTick)
      return failBool("absurd tick " + std::string(words[0]) + " (limit " +
                      std::to_string(kMaxReplayTick) + ")");
    if (result_.replay.ticks && *tick >= *result_.replay.ticks)
      return failBool("tick " + std::string(words[0]) + " is not below the declared length of " +
                      std::to_string(*result_.replay.ticks) + " ticks");
    if (!result_.replay.frames.empty() && *tick <= result_.replay.frames.back().tick)
      return failBool("tick " + std::string(words[0]) + " is not after the previous tick " +
                      std::to_string(result_.replay.frames.back().tick) +
                      " (ticks must be strictly increasing)");
    if (words.size() < 2) return failBool("tick " + std::string(words[0]) + " has no events");
    InputFrame frame;
    frame.tick = *tick;
    frame.events.reserve(words.size() - 1);
    for (size_t i = 1; i < words.size(); ++i) {
      EventParse parsed = parseEvent(words[i], lastMouse_);
      if (!parsed.event) return failBool(parsed.error);
      frame.events.push_back(*parsed.event);
    }
    result_.replay.frames.push_back(std::move(frame));
    return true;
  }

  bool checkHeaderComplete() {
    if (!sawScene_) return failBool("missing 'scene <name>' header line before the events");
    if (!sawSeed_) return failBool("missing 'seed <number>' header line before the events");
    return true;
  }

  bool failBool(std::string reason) {
    fail(std::move(reason));
    return false;
  }

  std::string_view text_;
  std::string_view fileName_;
  size_t lineNumber_ = 0;
  bool sawVersion_ = false;
  bool sawScene_ = false;
  bool sawSeed_ = false;
  bool sawTick_ = false;
  float lastMouse_[2] = {0.0f, 0.0f};
  ReplayParseResult result_;
};

std::string validateEvent(const InputEvent& event) {
  auto coordinateOk = [](float v) {
    return std::isfinite(v) && std::fabs(v) <= kMaxMouseCoordinate;
  };
  return std::visit(
      [&](const auto& e) -> std::string {
        using E = std::decay_t<decltype(e)>;
        if constexpr (std::is_same_v<E, KeyDown> || std::is_same_v<E, KeyUp>) {
          if (static_cast<int>(e.key) >= kKeyCount) return "unknown key";
        } else if constexpr (std::is_same_v<E, MouseMove>) {
          if (!coordinateOk(e.x) || !coordinateOk(e.y) || !coordinateOk(e.dx) ||
              !coordinateOk(e.dy))
            return "mouse move value out of range or not finite";
        } else if constexpr (std::is_same_v<E, MouseDown> || std::is_same_v<E, MouseUp>) {
          if (static_cast<int>(e.button) >= kMouseButtonCount) return "unknown mouse button";
          if (!coordinateOk(e.x) || !coordinateOk(e.y))
            return "mouse button position out of range or not finite";
        } else if constexpr (std::is_same_v<E, Scroll>) {
          if (!std::isfinite(e.dx) || !std::isfinite(e.dy) || std::fabs(e.dx) > kMaxScroll ||
              std::fabs(e.dy) > kMaxScroll)
            return "scroll value out of range or not finite";
        } else if constexpr (std::is_same_v<E, Resize>) {
          if (e.width < 0 || e.height < 0 || e.width > kMaxWindowSize || e.height > kMaxWindowSize)
            return "window size out of range";
        }
        return {};
      },
      event);
}

}  // namespace

uint64_t Replay::length() const {
  if (ticks) return *ticks;
  return frames.empty() ? 0 : frames.back().tick + 1;
}

ReplayParseResult parseReplay(std::string_view text, std::string_view fileName) {
  try {
    return Parser(text, fileName).run();
  } catch (const std::exception& e) {
    // Only allocation failure can get here; report it instead of letting it cross the layer.
    ReplayParseResult result;
    result.setFailure(base::StatusCode::ParseError, std::string(fileName) + ": cannot parse replay: " + e.what());
    return result;
  }
}

ReplayParseResult loadReplay(const std::string& path) {
  ReplayParseResult result;
  try {
    std::error_code error;
    const std::filesystem::file_status status = std::filesystem::status(path, error);
    if (error || !std::filesystem::exists(status)) {
      result.setFailure(base::StatusCode::NotFound, path + ": cannot open replay file: no such file");
      return result;
    }
    if (std::filesystem::is_directory(status)) {
      result.setFailure(base::StatusCode::IoError, path + ": cannot open replay file: it is a directory");
      return result;
    }
    std::ifstream file(path, std::ios::binary);
    if (!file) {
      result.setFailure(base::StatusCode::IoError,
                        path + ": cannot open replay file (permission denied or unreadable)");
      return result;
    }
    std::string text;
    char buffer[1 << 16];
    while (file.read(buffer, sizeof(buffer)) || file.gcount() > 0) {
      text.append(buffer, static_cast<size_t>(file.gcount()));
      if (text.size() > kMaxReplayFileBytes) {
        result.setFailure(base::StatusCode::IoError, path + ": replay file larger than " +
                       std::to_string(kMaxReplayFileBytes >> 20) + " MiB");
        return result;
      }
    }
    if (file.bad()) {
      result.setFailure(base::StatusCode::IoError, path + ": read error");
      return result;
    }
    return parseReplay(text, path);
  } catch (const std::exception& e) {
    result.setFailure(base::StatusCode::IoError, path + ": cannot read replay file: " + e.what());
    return result;
  }
}

std::string formatEvent(const InputEvent& event) {
  return std::visit(
      [](const auto& e) -> std::string {
        using E = std::decay_t<decltype(e)>;
        if constexpr (std::is_same_v<E, KeyDown> || std::is_same_v<E, KeyUp>) {
          if (static_cast<int>(e.key) >= kKeyCount) return {};
          return std::string(std::is_same_v<E, KeyDown> ? "kd:" : "ku:") +
                 std::string(keyName(e.key));
        } else if constexpr (std::is_same_v<E, MouseMove>) {
          return "mm:" + formatFloat(e.x) + "," + formatFloat(e.y) + "," + formatFloat(e.dx) + "," +
                 formatFloat(e.dy);
        } else if constexpr (std::is_same_v<E, MouseDown> || std::is_same_v<E, MouseUp>) {
          if (static_cast<int>(e.button) >= kMouseButtonCount) return {};
          return std::string(std::is_same_v<E, MouseDown> ? "md:" : "mu:") +
                 std::string(mouseButtonName(e.button)) + "@" + formatFloat(e.x) + "," +
                 formatFloat(e.y);
        } else if constexpr (std::is_same_v<E, Scroll>) {
          return "sc:" + formatFloat(e.dx) + "," + formatFloat(e.dy);
        } else if constexpr (std::is_same_v<E, Resize>) {
          return "rs:" + std::to_string(e.width) + "," + std::to_string(e.height);
        } else {
          static_assert(sizeof(E) == 0, "unhandled input event type");
        }
      },
      event);
}

std::string validateReplay(const Replay& replay) {
  if (!validSceneName(replay.scene)) return "bad scene name '" + replay.scene + "'";
  if (replay.ticks && *replay.ticks > kMaxReplayTick + 1) return "length in ticks out of range";
  for (size_t i = 0; i < replay.frames.size(); ++i) {
    const InputFrame& frame = replay.frames[i];
    const std::string where = "frame of tick " + std::to_string(frame.tick) + ": ";
    if (frame.tick > kMaxReplayTick) return where + "tick out of range";
    if (i > 0 && frame.tick <= replay.frames[i - 1].tick) return where + "ticks not increasing";
    if (replay.ticks && frame.tick >= *replay.ticks) return where + "tick not below the length";
    if (frame.events.empty()) return where + "no events";
    for (const InputEvent& event : frame.events) {
      if (std::string problem = validateEvent(event); !problem.empty()) return where + problem;
    }
  }
  return {};
}

std::string writeReplay(const Replay& replay) {
  std::string text = "cleave-replay " + std::to_string(kReplayVersion) + "\n";
  text += "scene " + replay.scene + "\n";
  text += "seed " + std::to_string(replay.seed) + "\n";
  if (replay.ticks) text += "ticks " + std::to_string(*replay.ticks) + "\n";
  for (const InputFrame& frame : replay.frames) {
    text += std::to_string(frame.tick);
    for (const InputEvent& event : frame.events) {
      text += ' ';
      text += formatEvent(event);
    }
    text += '\n';
  }
  return text;
}

ReplaySaveResult saveReplay(const std::string& path, const Replay& replay) {
  ReplaySaveResult result;
  try {
    if (std::string problem = validateReplay(replay); !problem.empty()) {
      result.setFailure(base::StatusCode::ParseError, path + ": replay not saved: " + problem);
      return result;
    }
    const std::string text = writeReplay(replay);
    std::ofstream file(path, std::ios::binary | std::ios::trunc);
    if (!file) {
      result.setFailure(base::StatusCode::IoError, path + ": cannot open for writing");
      return result;
    }
    file.write(text.data(), static_cast<std::streamsize>(text.size()));
    file.close();
    if (!file) {
      result.setFailure(base::StatusCode::IoError, path + ": write error");
      return result;
    }
    result.code = base::StatusCode::Ok;
  } catch (const std::exception& e) {
    result.setFailure(base::StatusCode::IoError, path + ": cannot write replay: " + e.what());
  }
  return result;
}

ReplayRecorder::ReplayRecorder(std::string scene, uint64_t seed) {
  replay_.scene = std::move(scene);
  replay_.seed = seed;
}

void ReplayRecorder::record(const InputFrame& frame) {
  // Saturating: a tick of UINT64_MAX (never valid in a file anyway) must not wrap the length to 0.
  const uint64_t length = frame.tick == UINT64_MAX ? UINT64_MAX : frame.tick + 1;
  if (!replay_.ticks || *replay_.ticks < length) replay_.ticks = length;
  if (frame.events.empty()) return;
  std::vector<InputFrame>& frames = replay_.frames;
  if (!frames.empty() && frame.tick < frames.back().tick) {
    ++dropped_;
    return;
  }
  if (!frames.empty() && frame.tick == frames.back().tick) {
    frames.back().events.insert(frames.back().events.end(), frame.events.begin(),
                                frame.events.end());
    return;
  }
  frames.push_back(frame);
}

}  // namespace cleave::input
