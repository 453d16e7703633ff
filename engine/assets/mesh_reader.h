// SPDX-License-Identifier: MIT
// Internal to engine/assets: the per-format readers behind mesh_io.h, their one-line errors and the
// writers' shared checks. The readers' tokenizer is line_scanner.h, their face triangulation
// polygon_triangulator.h and their common tail (normals, validation) mesh_finish.h. Not part of the
// public interface.
#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "cleave/assets/mesh_io.h"

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

// Writers: validates a mesh and gives its submesh runs (one run of material 0 when it has none).
bool writableRuns(const geometry::MeshData& mesh, std::vector<geometry::SubMesh>& runs,
                  std::string& reason);
// Writes bytes to a file; on failure `error` names the file.
bool writeBytes(const std::string& path, const void* data, size_t size, std::string& error);
// The file half of a writer: when `serialised` is ok, writes `bytes` to `path`; every error of the
// result names the file.
MeshWriteResult saveSerialised(const std::string& path, MeshWriteResult serialised,
                               const std::vector<uint8_t>& bytes);

}  // namespace cleave::assets::detail
