// SPDX-License-Identifier: MIT
// Positions in a scene's JSON text (scene_json.h).
#include "cleave/components/scene_json.h"

#include <algorithm>

namespace cleave::components::scene_json {

namespace {

// Lines of the source text. nlohmann::json keeps no positions, so a semantic error keeps the JSON
// pointer of the offending value and this scanner walks the (already valid) text along the pointer
// to the line where that value starts. Comments are skipped as the parser does.

class LineFinder {
 public:
  explicit LineFinder(const std::string& text) : s_(text) {}

  // Line of the value at `path`; the line of the deepest ancestor found if the path ends early.
  int lineOf(const std::vector<std::string>& path) {
    i_ = 0;
    line_ = 1;
    whitespace();
    for (const std::string& token : path) {
      const size_t saveI = i_;
      const int saveLine = line_;
      if (!descend(token)) {
        i_ = saveI;
        line_ = saveLine;
        break;
      }
    }
    return line_;
  }

 private:
  bool at(char c) const { return i_ < s_.size() && s_[i_] == c; }

  void whitespace() {
    while (i_ < s_.size()) {
      const char c = s_[i_];
      if (c == '\n') {
        ++line_;
        ++i_;
      } else if (c == ' ' || c == '\t' || c == '\r') {
        ++i_;
      } else if (c == '/' && i_ + 1 < s_.size() && s_[i_ + 1] == '/') {
        while (i_ < s_.size() && s_[i_] != '\n') ++i_;
      } else if (c == '/' && i_ + 1 < s_.size() && s_[i_ + 1] == '*') {
        i_ += 2;
        while (i_ + 1 < s_.size() && !(s_[i_] == '*' && s_[i_ + 1] == '/')) {
          if (s_[i_] == '\n') ++line_;
          ++i_;
        }
        i_ += 2;
      } else {
        break;
      }
    }
  }

  // At a '"': the string's characters with simple escapes resolved (enough to compare keys).
  std::string string() {
    std::string out;
    ++i_;
    while (i_ < s_.size() && s_[i_] != '"') {
      if (s_[i_] == '\\' && i_ + 1 < s_.size()) {
        ++i_;
        switch (s_[i_]) {
          case 'n': out += '\n'; break;
          case 't': out += '\t'; break;
          case 'r': out += '\r'; break;
          case 'b': out += '\b'; break;
          case 'f': out += '\f'; break;
          default: out += s_[i_]; break;
        }
      } else {
        out += s_[i_];
      }
      ++i_;
    }
    ++i_;
    return out;
  }

  void skipValue() {
    whitespace();
    if (at('"')) {
      string();
      return;
    }
    if (at('{') || at('[')) {
      int depth = 0;
      while (i_ < s_.size()) {
        whitespace();
        if (i_ >= s_.size()) return;
        const char c = s_[i_];
        if (c == '"') {
          string();
          continue;
        }
        ++i_;
        if (c == '{' || c == '[') ++depth;
        if (c == '}' || c == ']') {
          if (--depth == 0) return;
        }
      }
      return;
    }
    while (i_ < s_.size() && std::string_view(",]} \t\r\n/").find(s_[i_]) == std::string_view::npos) ++i_;
  }

  bool descend(const std::string& token) {
    whitespace();
    if (at('{')) {
      ++i_;
      while (true) {
        whitespace();
        if (!at('"')) return false;
        const std::string key = string();
        whitespace();
        if (!at(':')) return false;
        ++i_;
        whitespace();
        if (key == token) return true;
        skipValue();
        whitespace();
        if (!at(',')) return false;
        ++i_;
      }
    }
    if (at('[')) {
      size_t index = 0;
      for (char c : token) {
        if (c < '0' || c > '9') return false;
        index = index * 10 + size_t(c - '0');
      }
      ++i_;
      for (size_t k = 0;; ++k) {
        whitespace();
        if (at(']')) return false;
        if (k == index) return true;
        skipValue();
        whitespace();
        if (!at(',')) return false;
        ++i_;
      }
    }
    return false;
  }

  const std::string& s_;
  size_t i_ = 0;
  int line_ = 1;
};

}  // namespace

int jsonLineOf(const std::string& text, const std::vector<std::string>& path) { return LineFinder(text).lineOf(path); }

// The last object key that starts before `end` (for syntax errors, which have no pointer).
std::string lastKeyBefore(const std::string& s, size_t end) {
  std::string last;
  size_t i = 0;
  end = std::min(end, s.size());
  while (i < end) {
    if (s[i] == '"') {
      std::string str;
      ++i;
      while (i < end && s[i] != '"') {
        if (s[i] == '\\' && i + 1 < end) ++i;
        str += s[i++];
      }
      ++i;
      size_t j = i;
      while (j < end && (s[j] == ' ' || s[j] == '\t' || s[j] == '\r' || s[j] == '\n')) ++j;
      if (j < end && s[j] == ':') last = str;
      continue;
    }
    ++i;
  }
  return last;
}

std::string pointerOf(const std::vector<std::string>& path) {
  if (path.empty()) return "/";
  std::string out;
  for (const std::string& token : path) {
    out += '/';
    for (char c : token) {
      if (c == '~') out += "~0";
      else if (c == '/') out += "~1";
      else out += c;
    }
  }
  return out;
}

const char* typeName(const json& j) {
  switch (j.type()) {
    case json::value_t::null: return "null";
    case json::value_t::object: return "an object";
    case json::value_t::array: return "an array";
    case json::value_t::string: return "a string";
    case json::value_t::boolean: return "a boolean";
    case json::value_t::number_integer:
    case json::value_t::number_unsigned: return "an integer";
    case json::value_t::number_float: return "a number";
    default: return "an unknown value";
  }
}

std::string joinNames(std::span<const char* const> names) {
  std::string out;
  for (const char* n : names) {
    if (!out.empty()) out += ", ";
    out += n;
  }
  return out;
}

std::string joinNames(std::initializer_list<const char*> names) {
  return joinNames(std::span<const char* const>(names.begin(), names.size()));
}

}  // namespace cleave::components::scene_json
