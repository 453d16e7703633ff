// SPDX-License-Identifier: MIT
// Internal to engine/assets: the tokenizer of the text mesh formats (OBJ, OFF, PLY, ascii STL).
// Splits text into lines and lines into whitespace-separated tokens, keeps the line number for
// messages, and parses numbers with std::from_chars (locale-independent, whole token or nothing).
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <string_view>

namespace cleave::assets::detail {

// Parses a whole token as a number (an optional leading '+' is allowed); false on anything else
// (trailing characters, empty, overflow). `value` is unspecified on failure.
bool parseFloat(std::string_view token, float& value);
bool parseDouble(std::string_view token, double& value);
bool parseInt64(std::string_view token, int64_t& value);

// Short printable rendering of a token for messages, in single quotes ("..." when cut).
std::string quoted(std::string_view token);

// Splits text into lines (LF, CRLF or CR) and lines into tokens separated by spaces, tabs, form
// feeds, vertical tabs or (unless told otherwise) NUL bytes, counting lines from 1. When
// commentChar is not '\0' it starts a comment to the end of the line. The scanner views `text`,
// which must outlive it.
class LineScanner {
 public:
  // `nulSeparates` false makes a NUL byte part of a token (a PLY body, where it is garbage that
  // must fail as a bad number rather than split one).
  LineScanner(std::string_view text, char commentChar, bool nulSeparates = true)
      : text_(text), comment_(commentChar), nulSeparates_(nulSeparates) {}

  // Advances to the next line; false at the end of the text.
  bool nextLine();
  // Advances to the next line that holds a token (skipping empty and comment-only lines); false at
  // the end of the text.
  bool nextDataLine();
  // The next token of the current line, or an empty view at the end of the line.
  std::string_view nextToken();
  // The next token, moving over line ends, empty lines and comments; empty at the end of the text.
  std::string_view nextTokenAnyLine();
  // Reads values.size() numbers from the current line. On a missing or bad token returns false and
  // sets `bad` to it (empty when the line ended).
  bool nextFloats(std::span<float> values, std::string_view& bad);
  // The rest of the current line with leading and trailing whitespace removed.
  std::string_view rest();
  size_t lineNumber() const { return lineNumber_; }
  // Byte offset of the start of the next line in the text.
  size_t offset() const { return pos_; }
  // Byte offset in the text just after the last token read (the end of the text past the last
  // line).
  size_t position() const { return lineStart_ + linePos_; }

 private:
  std::string_view text_;
  char comment_;
  bool nulSeparates_;
  size_t pos_ = 0;        // start of the next line
  size_t lineStart_ = 0;  // start of the current line
  std::string_view line_;
  size_t linePos_ = 0;
  size_t lineNumber_ = 0;
};

}  // namespace cleave::assets::detail
