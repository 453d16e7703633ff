// SPDX-License-Identifier: MIT
// The text formats' tokenizer (engine/assets/line_scanner.h) and the PLY body read with it.
#include "cleave/assets/line_scanner.h"

#include <gtest/gtest.h>

#include <span>
#include <string>
#include <vector>

#include "cleave/assets/mesh_io.h"

namespace cleave::assets {
namespace {

using detail::LineScanner;

std::vector<std::string> tokensOfLine(LineScanner& scanner) {
  std::vector<std::string> tokens;
  for (std::string_view t = scanner.nextToken(); !t.empty(); t = scanner.nextToken())
    tokens.emplace_back(t);
  return tokens;
}

TEST(LineScanner, SplitsLinesAndTokensAndCountsLines) {
  LineScanner scanner("v 1 2\r\n\tf  3\t4 # note\rlast\n", '#');
  ASSERT_TRUE(scanner.nextLine());
  EXPECT_EQ(tokensOfLine(scanner), (std::vector<std::string>{"v", "1", "2"}));
  ASSERT_TRUE(scanner.nextLine());  // CRLF is one line end
  EXPECT_EQ(scanner.lineNumber(), 2u);
  EXPECT_EQ(tokensOfLine(scanner), (std::vector<std::string>{"f", "3", "4"}));  // comment cut
  ASSERT_TRUE(scanner.nextLine());  // a lone CR ends a line too
  EXPECT_EQ(scanner.lineNumber(), 3u);
  EXPECT_EQ(scanner.rest(), "last");
  EXPECT_FALSE(scanner.nextLine());
  EXPECT_EQ(scanner.lineNumber(), 3u);
}

TEST(LineScanner, TokensAcrossLinesSkipEmptyAndCommentLines) {
  LineScanner scanner("OFF\n\n# counts\n  3 1 0\n", '#');
  ASSERT_TRUE(scanner.nextLine());
  std::vector<std::string> tokens;
  std::vector<size_t> lines;
  for (std::string_view t = scanner.nextTokenAnyLine(); !t.empty();
       t = scanner.nextTokenAnyLine()) {
    tokens.emplace_back(t);
    lines.push_back(scanner.lineNumber());
  }
  EXPECT_EQ(tokens, (std::vector<std::string>{"OFF", "3", "1", "0"}));
  EXPECT_EQ(lines, (std::vector<size_t>{1, 4, 4, 4}));

  LineScanner data("\n# only a comment\n\nx\n", '#');
  ASSERT_TRUE(data.nextDataLine());
  EXPECT_EQ(data.lineNumber(), 4u);
  EXPECT_EQ(data.rest(), "x");
  EXPECT_FALSE(data.nextDataLine());
}

TEST(LineScanner, NumbersAreWholeTokensInAnyLocale) {
  float f = 0.f;
  double d = 0.0;
  int64_t i = 0;
  EXPECT_TRUE(detail::parseFloat("+1.5e2", f));
  EXPECT_EQ(f, 150.f);
  EXPECT_TRUE(detail::parseDouble("-0.25", d));
  EXPECT_EQ(d, -0.25);
  EXPECT_TRUE(detail::parseInt64("-42", i));
  EXPECT_EQ(i, -42);
  EXPECT_FALSE(detail::parseFloat("1,5", f));
  EXPECT_FALSE(detail::parseFloat("1.5x", f));
  EXPECT_FALSE(detail::parseFloat("+", f));
  EXPECT_FALSE(detail::parseInt64("1.0", i));
  EXPECT_FALSE(detail::parseInt64("99999999999999999999", i));

  LineScanner scanner("0.5 2 oops 4\n", '\0');
  ASSERT_TRUE(scanner.nextLine());
  float values[4] = {};
  std::string_view bad;
  EXPECT_FALSE(scanner.nextFloats(values, bad));
  EXPECT_EQ(bad, "oops");
  EXPECT_EQ(values[0], 0.5f);
  EXPECT_EQ(values[1], 2.f);
  EXPECT_EQ(scanner.position(), 10u);  // just after "oops"
  LineScanner shortLine("1 2\n", '\0');
  ASSERT_TRUE(shortLine.nextLine());
  bad = "unset";
  EXPECT_FALSE(shortLine.nextFloats(std::span<float>(values, 3), bad));
  EXPECT_TRUE(bad.empty());  // the line ended
}

TEST(LineScanner, NulSeparatesTokensUnlessToldNot) {
  const std::string text("1\0002 3", 5);
  LineScanner separating(text, '\0');
  ASSERT_TRUE(separating.nextLine());
  EXPECT_EQ(tokensOfLine(separating), (std::vector<std::string>{"1", "2", "3"}));
  LineScanner joining(text, '\0', /*nulSeparates=*/false);
  ASSERT_TRUE(joining.nextLine());
  EXPECT_EQ(tokensOfLine(joining), (std::vector<std::string>{std::string("1\0002", 3), "3"}));
}

// An ascii PLY body counts its lines by LF (a lone CR in the data is blank space there), and a NUL
// byte inside a number makes it a bad number rather than two numbers.
TEST(LineScanner, AsciiPlyBodyLinesAndNulBytes) {
  const std::string header =
      "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
      "property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n";
  auto read = [](const std::string& text) {
    const std::vector<uint8_t> bytes(text.begin(), text.end());
    return readMeshFromMemory(bytes, MeshFormat::Ply, "t.ply");
  };
  MeshReadResult result = read(header + "0 0 0\r1 0 0\n0 1 0\n3 0 1 x\n");
  EXPECT_FALSE(result.ok());
  EXPECT_EQ(result.message, "t.ply:12: in face 0: bad number 'x'");
  result = read(header + "0 0 0\n1 0 0\n0 1 0\n3 0 1\n");
  EXPECT_EQ(result.message, "t.ply:14: in face 0: file ends inside the data");
  result = read(header + "0 0 0\n1 0" + std::string(1, '\0') + "5 0\n0 1 0\n3 0 1 2\n");
  EXPECT_EQ(result.message, "t.ply:11: in vertex 1: bad number '0?5'");
  result = read(header + "0 0 0\r1 0 0\n0 1 0\n3 0 1 2\n");
  EXPECT_TRUE(result.ok()) << result.message;
  EXPECT_EQ(result.mesh.indices, (std::vector<uint32_t>{0, 1, 2}));
}

}  // namespace
}  // namespace cleave::assets
