// SPDX-License-Identifier: MIT
// Internal to engine/assets: the per-format readers behind mesh_io.h and the small helpers they share
// (one-line errors, a line scanner for text formats, locale-independent number parsing, the final
// validation every reader runs). Not part of the public interface.
#pragma once

#include <charconv>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "cleave/assets/mesh_io.h"
#include "cleave/geometry/cap_triangulator.h"

namespace cleave::assets::detail {

// Readers on bytes. `name` only appears in messages. `baseDir` (glTF text only) is the folder in
// which external buffers are looked up; nullopt refuses external buffers.
MeshReadResult readObj(std::span<const uint8_t> bytes, const std::string& name);
MeshReadResult readOff(std::span<const uint8_t> bytes, const std::string& name);
MeshReadResult readStl(std::span<const uint8_t> bytes, const std::string& name);
MeshReadResult readPly(std::span<const uint8_t> bytes, const std::string& name);
MeshReadResult readGltf(std::span<const uint8_t> bytes, const std::string& name, bool binary,
                        const std::optional<std::string>& baseDir);

MeshReadResult failure(const std::string& name, const std::string& reason);
MeshReadResult failureAt(const std::string& name, size_t line, const std::string& reason);

// Checks what every reader promises (at least one triangle, indices in range, finite attributes,
// per-vertex arrays of the right size, submeshes covering the indices), fills materialNames when
// empty and returns the result; on a violation returns a failure naming the file.
MeshReadResult finish(MeshReadResult result, const std::string& name);

// Parses a whole token as a number; false on anything else (trailing characters, empty, overflow).
bool parseFloat(std::string_view token, float& value);
bool parseDouble(std::string_view token, double& value);
bool parseInt64(std::string_view token, int64_t& value);

// Splits text into lines (LF, CRLF or CR) and lines into whitespace-separated tokens, counting lines
// from 1. `#` starts a comment to the end of the line when commentChar is '#'.
class LineScanner {
 public:
  LineScanner(std::string_view text, char commentChar) : text_(text), comment_(commentChar) {}

  // Advances to the next line; false at the end of the text.
  bool nextLine();
  // The next token of the current line, or an empty view at the end of the line.
  std::string_view nextToken();
  // The rest of the current line with leading whitespace removed.
  std::string_view rest();
  size_t lineNumber() const { return lineNumber_; }
  size_t offset() const { return pos_; }

 private:
  std::string_view text_;
  char comment_;
  size_t pos_ = 0;  // start of the next line
  std::string_view line_;
  size_t linePos_ = 0;
  size_t lineNumber_ = 0;
};

// Writers: validates a mesh and gives its submesh runs (one run of material 0 when it has none).
bool writableRuns(const geometry::MeshData& mesh, std::vector<geometry::SubMesh>& runs,
                  std::string& reason);
// Writes bytes to a file; on failure `error` names the file.
bool writeBytes(const std::string& path, const void* data, size_t size, std::string& error);
// The file half of a writer: when `serialised` is ok, writes `bytes` to `path`; every error of the
// result names the file.
MeshWriteResult saveSerialised(const std::string& path, MeshWriteResult serialised,
                               const std::vector<uint8_t>& bytes);

// Triangulates the polygon faces of a file. A convex face is fanned from its first corner; any
// other face is ear-clipped in its plane, because the fan of a concave face folds over itself and
// makes the mesh intersect itself (see geometry::CapTriangulator::triangulateFace). Scratch memory
// is kept between faces.
class PolygonTriangulator {
 public:
  // Appends the triangles of the face whose vertices are `polygon` to `indices`; corners[k] is the
  // position of polygon[k]. Without corners (a PLY file may list its faces before its vertices) the
  // face is fanned.
  void append(std::span<const uint32_t> polygon, std::span<const glm::vec3> corners,
              std::vector<uint32_t>& indices);

 private:
  geometry::CapTriangulator triangulator_;
  std::vector<uint32_t> triangles_;
};

// Short printable rendering of a token for messages ("..." when cut).
std::string quoted(std::string_view token);

}  // namespace cleave::assets::detail
