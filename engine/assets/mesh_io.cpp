// SPDX-License-Identifier: MIT
// Dispatch by extension, file access, the helpers shared by the readers, and the OBJ writer.
#include "cleave/assets/mesh_io.h"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <system_error>

#include "cleave/assets/mesh_reader.h"

namespace cleave::assets {

namespace detail {

MeshReadResult failure(const std::string& name, const std::string& reason) {
  MeshReadResult result;
  result.setFailure(base::StatusCode::ParseError, name + ": " + reason);
  return result;
}

MeshReadResult failureAt(const std::string& name, size_t line, const std::string& reason) {
  MeshReadResult result;
  result.setFailure(base::StatusCode::ParseError, name + ":" + std::to_string(line) + ": " + reason);
  return result;
}

}  // namespace detail

const char* toString(MeshFormat format) {
  switch (format) {
    case MeshFormat::Obj: return "OBJ";
    case MeshFormat::Off: return "OFF";
    case MeshFormat::Stl: return "STL";
    case MeshFormat::Ply: return "PLY";
    case MeshFormat::Gltf: return "glTF";
    case MeshFormat::Glb: return "GLB";
    case MeshFormat::Unknown: break;
  }
  return "unknown";
}

MeshFormat formatFromPath(std::string_view path) {
  const size_t slash = path.find_last_of("/\\");
  const std::string_view file = slash == std::string_view::npos ? path : path.substr(slash + 1);
  const size_t dot = file.find_last_of('.');
  if (dot == std::string_view::npos) return MeshFormat::Unknown;
  std::string ext(file.substr(dot + 1));
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  if (ext == "obj") return MeshFormat::Obj;
  if (ext == "off") return MeshFormat::Off;
  if (ext == "stl") return MeshFormat::Stl;
  if (ext == "ply") return MeshFormat::Ply;
  if (ext == "gltf") return MeshFormat::Gltf;
  if (ext == "glb") return MeshFormat::Glb;
  return MeshFormat::Unknown;
}

namespace {

// Files above this size are refused rather than read into memory.
constexpr uint64_t kMaxFileBytes = uint64_t{1} << 31;

bool readWholeFile(const std::string& path, std::vector<uint8_t>& bytes, std::string& error) {
  std::error_code ec;
  const std::filesystem::file_status status = std::filesystem::status(path, ec);
  if (ec || !std::filesystem::exists(status)) {
    error = path + ": no such file";
    return false;
  }
  if (std::filesystem::is_directory(status)) {
    error = path + ": is a directory, not a mesh file";
    return false;
  }
  if (!std::filesystem::is_regular_file(status)) {
    error = path + ": not a regular file";
    return false;
  }
  const uintmax_t size = std::filesystem::file_size(path, ec);
  if (ec) {
    error = path + ": cannot read the file size (" + ec.message() + ")";
    return false;
  }
  if (size > kMaxFileBytes) {
    error = path + ": file too large (" + std::to_string(size) + " bytes)";
    return false;
  }
  std::FILE* file = std::fopen(path.c_str(), "rb");
  if (file == nullptr) {
    error = path + ": cannot open the file for reading";
    return false;
  }
  bytes.resize(static_cast<size_t>(size));
  const size_t got = size == 0 ? 0 : std::fread(bytes.data(), 1, bytes.size(), file);
  const bool readError = std::ferror(file) != 0;
  std::fclose(file);
  if (readError || got != bytes.size()) {
    error = path + ": read error";
    return false;
  }
  return true;
}

MeshReadResult dispatch(std::span<const uint8_t> bytes, MeshFormat format, const std::string& name,
                        const std::optional<std::string>& baseDir) {
  if (bytes.empty()) return detail::failure(name, "empty file");
  switch (format) {
    case MeshFormat::Obj: return detail::readObj(bytes, name);
    case MeshFormat::Off: return detail::readOff(bytes, name);
    case MeshFormat::Stl: return detail::readStl(bytes, name);
    case MeshFormat::Ply: return detail::readPly(bytes, name);
    case MeshFormat::Gltf: return detail::readGltf(bytes, name, false, baseDir);
    case MeshFormat::Glb: return detail::readGltf(bytes, name, true, baseDir);
    case MeshFormat::Unknown: break;
  }
  return detail::failure(name, "unknown mesh format");
}

}  // namespace

MeshReadResult readMeshFile(const std::string& path, MeshFormat format) {
  if (format == MeshFormat::Unknown) {
    return detail::failure(path, "unknown mesh format");
  }
  std::vector<uint8_t> bytes;
  std::string error;
  if (!readWholeFile(path, bytes, error)) {
    MeshReadResult result;
    result.setFailure(base::StatusCode::IoError, error);
    return result;
  }
  std::string baseDir = std::filesystem::path(path).parent_path().string();
  if (baseDir.empty()) baseDir.assign(1, '.');
  return dispatch(bytes, format, path, baseDir);
}

MeshReadResult loadMesh(const std::string& path) {
  const MeshFormat format = formatFromPath(path);
  if (format == MeshFormat::Unknown) {
    return detail::failure(path,
                           "unknown file extension (expected .obj, .off, .stl, .ply, .gltf or .glb)");
  }
  return readMeshFile(path, format);
}

MeshReadResult readMeshFromMemory(std::span<const uint8_t> bytes, MeshFormat format,
                                  const std::string& name) {
  return dispatch(bytes, format, name, std::nullopt);
}

// ---------------------------------------------------------------------------------------------
// OBJ writer

namespace {

// Length of the valid UTF-8 sequence starting at s[i], or 0 when it is not valid.
size_t utf8Length(const std::string& s, size_t i) {
  const unsigned char c = static_cast<unsigned char>(s[i]);
  size_t length = 0;
  uint32_t minimum = 0;
  uint32_t code = 0;
  if (c < 0x80) return 1;
  if ((c & 0xe0) == 0xc0) { length = 2; minimum = 0x80; code = c & 0x1f; }
  else if ((c & 0xf0) == 0xe0) { length = 3; minimum = 0x800; code = c & 0x0f; }
  else if ((c & 0xf8) == 0xf0) { length = 4; minimum = 0x10000; code = c & 0x07; }
  else return 0;
  if (i + length > s.size()) return 0;
  for (size_t k = 1; k < length; ++k) {
    const unsigned char d = static_cast<unsigned char>(s[i + k]);
    if ((d & 0xc0) != 0x80) return 0;
    code = (code << 6) | (d & 0x3f);
  }
  if (code < minimum || code > 0x10ffff || (code >= 0xd800 && code <= 0xdfff)) return 0;
  return length;
}

}  // namespace

std::string materialName(const MeshWriteOptions& options, uint32_t materialId) {
  if (materialId == options.capMaterialId) return "cap";
  if (materialId < options.materialNames.size() && !options.materialNames[materialId].empty()) {
    // Whitespace would end the name in a `usemtl` line, control characters and invalid UTF-8
    // cannot go into glTF's JSON: they become '_'.
    const std::string& raw = options.materialNames[materialId];
    std::string name;
    for (size_t i = 0; i < raw.size();) {
      const size_t length = utf8Length(raw, i);
      const unsigned char c = static_cast<unsigned char>(raw[i]);
      if (length == 0 || c <= 0x20 || c == 0x7f) {
        name += '_';
        i += length == 0 ? 1 : length;
      } else {
        name.append(raw, i, length);
        i += length;
      }
    }
    return name;
  }
  return "material_" + std::to_string(materialId);
}

namespace detail {

// Validates the mesh a writer gets and gives its submesh runs (a single run when it has none).
bool writableRuns(const geometry::MeshData& mesh, std::vector<geometry::SubMesh>& runs,
                  std::string& reason) {
  if (mesh.indices.size() % 3 != 0) {
    reason = "index count is not a multiple of 3";
    return false;
  }
  for (uint32_t index : mesh.indices) {
    if (index >= mesh.positions.size()) {
      reason = "index " + std::to_string(index) + " out of range";
      return false;
    }
  }
  if ((!mesh.normals.empty() && mesh.normals.size() != mesh.positions.size()) ||
      (!mesh.uv0.empty() && mesh.uv0.size() != mesh.positions.size())) {
    reason = "attribute count differs from the vertex count";
    return false;
  }
  if (mesh.submeshes.empty()) {
    runs = {geometry::SubMesh{0, static_cast<uint32_t>(mesh.indices.size()), 0}};
    return true;
  }
  uint64_t next = 0;
  for (const geometry::SubMesh& sub : mesh.submeshes) {
    if (sub.firstIndex != next || sub.indexCount % 3 != 0) {
      reason = "submeshes do not cover the indices in order";
      return false;
    }
    next += sub.indexCount;
  }
  if (next != mesh.indices.size()) {
    reason = "submeshes do not cover the indices in order";
    return false;
  }
  runs = mesh.submeshes;
  return true;
}

MeshWriteResult saveSerialised(const std::string& path, MeshWriteResult serialised,
                               const std::vector<uint8_t>& bytes) {
  if (!serialised.ok()) {
    serialised.message = path + ": " + serialised.message;
    return serialised;
  }
  std::string error;
  if (!writeBytes(path, bytes.data(), bytes.size(), error)) {
    serialised.setFailure(base::StatusCode::IoError, error);
  }
  return serialised;
}

bool writeBytes(const std::string& path, const void* data, size_t size, std::string& error) {
  std::FILE* file = std::fopen(path.c_str(), "wb");
  if (file == nullptr) {
    error = path + ": cannot open the file for writing";
    return false;
  }
  const size_t wrote = size == 0 ? 0 : std::fwrite(data, 1, size, file);
  const bool closeFailed = std::fclose(file) != 0;
  if (wrote != size || closeFailed) {
    error = path + ": write error";
    return false;
  }
  return true;
}

}  // namespace detail

namespace {

void appendFloat(std::string& out, float value) {
  char buffer[32];
  // Shortest representation that reads back to the same float.
  const auto [end, ec] = std::to_chars(buffer, buffer + sizeof(buffer), value);
  if (ec == std::errc()) out.append(buffer, end);
  else out += '0';
}

}  // namespace

MeshWriteResult writeObjToString(const geometry::MeshData& mesh, const MeshWriteOptions& options,
                                 std::string& out) {
  MeshWriteResult result;
  std::vector<geometry::SubMesh> runs;
  std::string reason;
  if (!detail::writableRuns(mesh, runs, reason)) {
    result.setFailure(base::StatusCode::InvalidArgument, "OBJ: " + reason);
    return result;
  }
  const bool uvs = options.writeUvs && !mesh.uv0.empty();
  const bool normals = options.writeNormals && !mesh.normals.empty();
  out.clear();
  out.reserve(mesh.positions.size() * 40 + mesh.indices.size() * 12);
  out += "# Cleave mesh: " + std::to_string(mesh.positions.size()) + " vertices, " +
         std::to_string(mesh.indices.size() / 3) + " triangles\n";
  for (const glm::vec3& p : mesh.positions) {
    out += "v ";
    appendFloat(out, p.x);
    out += ' ';
    appendFloat(out, p.y);
    out += ' ';
    appendFloat(out, p.z);
    out += '\n';
  }
  if (uvs) {
    for (const glm::vec2& t : mesh.uv0) {
      out += "vt ";
      appendFloat(out, t.x);
      out += ' ';
      appendFloat(out, t.y);
      out += '\n';
    }
  }
  if (normals) {
    for (const glm::vec3& n : mesh.normals) {
      out += "vn ";
      appendFloat(out, n.x);
      out += ' ';
      appendFloat(out, n.y);
      out += ' ';
      appendFloat(out, n.z);
      out += '\n';
    }
  }
  for (const geometry::SubMesh& run : runs) {
    if (run.indexCount == 0) continue;
    out += "usemtl " + materialName(options, run.materialId) + "\n";
    for (uint32_t i = run.firstIndex; i < run.firstIndex + run.indexCount; i += 3) {
      out += 'f';
      for (uint32_t k = 0; k < 3; ++k) {
        const std::string index = std::to_string(mesh.indices[i + k] + 1);
        out += ' ';
        out += index;
        if (uvs || normals) {
          out += '/';
          if (uvs) out += index;
          if (normals) {
            out += '/';
            out += index;
          }
        }
      }
      out += '\n';
    }
  }
  result.code = base::StatusCode::Ok;
  return result;
}

MeshWriteResult writeObj(const std::string& path, const geometry::MeshData& mesh,
                         const MeshWriteOptions& options) {
  std::string text;
  MeshWriteResult result = writeObjToString(mesh, options, text);
  if (!result.ok()) {
    result.message = path + ": " + result.message;
    return result;
  }
  std::string error;
  if (!detail::writeBytes(path, text.data(), text.size(), error)) {
    result.setFailure(base::StatusCode::IoError, error);
  }
  return result;
}

}  // namespace cleave::assets
