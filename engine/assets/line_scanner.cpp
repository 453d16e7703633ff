// SPDX-License-Identifier: MIT
// The text formats' tokenizer (see line_scanner.h).
#include "cleave/assets/line_scanner.h"

#include <charconv>
#include <system_error>

namespace cleave::assets::detail {

namespace {

bool isSpace(char c, bool nulSeparates) {
  return c == ' ' || c == '\t' || c == '\f' || c == '\v' || (c == '\0' && nulSeparates);
}

// std::from_chars on the whole token, after an optional '+' (which from_chars does not take).
template <typename T>
bool parseWhole(std::string_view token, T& value) {
  if (!token.empty() && token.front() == '+') token.remove_prefix(1);
  if (token.empty()) return false;
  const auto [end, ec] = std::from_chars(token.data(), token.data() + token.size(), value);
  return ec == std::errc() && end == token.data() + token.size();
}

}  // namespace

bool parseFloat(std::string_view token, float& value) { return parseWhole(token, value); }
bool parseDouble(std::string_view token, double& value) { return parseWhole(token, value); }
bool parseInt64(std::string_view token, int64_t& value) { return parseWhole(token, value); }

std::string quoted(std::string_view token) {
  constexpr size_t kMax = 32;
  std::string out = "'";
  for (size_t i = 0; i < token.size() && i < kMax; ++i) {
    const unsigned char c = static_cast<unsigned char>(token[i]);
    out += (c >= 0x20 && c < 0x7f) ? static_cast<char>(c) : '?';
  }
  if (token.size() > kMax) out += "...";
  out += "'";
  return out;
}

bool LineScanner::nextLine() {
  if (pos_ >= text_.size()) {
    line_ = {};
    linePos_ = 0;
    lineStart_ = text_.size();
    return false;
  }
  size_t end = pos_;
  while (end < text_.size() && text_[end] != '\n' && text_[end] != '\r') ++end;
  line_ = text_.substr(pos_, end - pos_);
  lineStart_ = pos_;
  if (comment_ != '\0') {
    const size_t hash = line_.find(comment_);
    if (hash != std::string_view::npos) line_ = line_.substr(0, hash);
  }
  linePos_ = 0;
  ++lineNumber_;
  if (end < text_.size() && text_[end] == '\r' && end + 1 < text_.size() &&
      text_[end + 1] == '\n') {
    ++end;
  }
  pos_ = end + 1;
  return true;
}

bool LineScanner::nextDataLine() {
  while (nextLine()) {
    if (!rest().empty()) return true;
  }
  return false;
}

std::string_view LineScanner::nextToken() {
  while (linePos_ < line_.size() && isSpace(line_[linePos_], nulSeparates_)) ++linePos_;
  const size_t start = linePos_;
  while (linePos_ < line_.size() && !isSpace(line_[linePos_], nulSeparates_)) ++linePos_;
  return line_.substr(start, linePos_ - start);
}

std::string_view LineScanner::nextTokenAnyLine() {
  for (;;) {
    const std::string_view token = nextToken();
    if (!token.empty()) return token;
    if (!nextLine()) return {};
  }
}

bool LineScanner::nextFloats(std::span<float> values, std::string_view& bad) {
  for (float& value : values) {
    const std::string_view token = nextToken();
    if (!parseFloat(token, value)) {
      bad = token;
      return false;
    }
  }
  return true;
}

std::string_view LineScanner::rest() {
  while (linePos_ < line_.size() && isSpace(line_[linePos_], nulSeparates_)) ++linePos_;
  std::string_view r = line_.substr(linePos_);
  while (!r.empty() && isSpace(r.back(), nulSeparates_)) r.remove_suffix(1);
  return r;
}

}  // namespace cleave::assets::detail
