// SPDX-License-Identifier: MIT
// Mesh files to and from the plain MeshData of the split core.
//
// Readers: OBJ, OFF, STL (ascii and binary), PLY (ascii, binary little and big endian) and glTF 2.0
// (.gltf and .glb, static meshes of the default scene). Writers: OBJ and GLB.
//
// Units: whatever the file uses (the engine reads them as metres); no rescaling, no axis change.
// Winding: files are read as counter-clockwise seen from outside (the convention of all five formats)
// and written the same way. Polygons with more than three corners are fan-triangulated from their
// first corner when convex, ear-clipped in their plane otherwise (a concave face's fan folds over
// itself and leaves the mesh self-intersecting).
//
// Ownership: every result owns its mesh; nothing points into the input bytes or the file.
//
// Failure: no function throws and no input crashes, hangs or allocates far beyond the size of the
// input (every declared count is checked against the bytes that remain). On failure `ok` is false,
// the mesh is empty and `error` is one line "<file>: <reason>" or, for text formats,
// "<file>:<line>: <reason>". A file without a single triangle is an error, as is a non-finite
// coordinate or an index out of range.
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "cleave/base/status.h"
#include "cleave/assets/material.h"
#include "cleave/geometry/mesh_data.h"

namespace cleave::assets {

enum class MeshFormat : uint8_t { Unknown, Obj, Off, Stl, Ply, Gltf, Glb };

const char* toString(MeshFormat format);

// The format named by the extension of `path`, case-insensitive (".obj", ".off", ".stl", ".ply",
// ".gltf", ".glb"); Unknown otherwise.
MeshFormat formatFromPath(std::string_view path);

// A Status (code, and a message of one line naming the file and the reason; empty when ok) with
// what the read gives.
struct MeshReadResult : base::Status {
  geometry::MeshData mesh;
  std::vector<std::string> warnings;       // non-fatal remarks (tinygltf warnings, dropped normals)
  // Material names indexed by SubMesh::materialId: OBJ `usemtl` names in order of first use
  // ("default" for faces before any usemtl), glTF material names ("material_<i>" when unnamed,
  // "default" for primitives without material). Formats without materials give {"default"}.
  std::vector<std::string> materialNames;
};

// Reads a mesh file, choosing the reader by the extension (case-insensitive). An unknown extension,
// a missing or unreadable file or a directory is an error naming the file.
MeshReadResult loadMesh(const std::string& path);

// Reads one format from a file, whatever its extension.
MeshReadResult readMeshFile(const std::string& path, MeshFormat format);

// Reads one format from bytes in memory; `name` is used in messages only. A .gltf read from memory
// may only use data: URIs (external buffers are refused, since there is no folder to look in).
MeshReadResult readMeshFromMemory(std::span<const uint8_t> bytes, MeshFormat format,
                                  const std::string& name);

// Ok, or the code with one line naming the file and the reason.
using MeshWriteResult = base::Status;

struct MeshWriteOptions {
  // Material id of the cap submesh: it is written as the material named "cap".
  uint32_t capMaterialId = 1;
  // Names by material id for the other submeshes; an id without a name is written "material_<id>".
  std::vector<std::string> materialNames;
  // Linear RGBA base colours by material id (skinned GLB writer); an id without one gets none.
  std::vector<glm::vec4> materialColors;
  // GLB writers: the materials to copy by material id (for the ids it has, except the cap's, in
  // place of materialColors): base colour and metallic-roughness factors, doubleSided, and the
  // base colour and normal textures with their texCoord (and the normal scale), each with its
  // sampler and its image embedded as a buffer view holding the source's encoded bytes with its
  // mime type. Only what the written materials use is written, in order of first use. A texture
  // is left out of the material when its image has no encoded PNG or JPEG bytes or when it reads
  // a texture coordinate set the file does not get (TEXCOORD_0 is the only one written). Views:
  // the caller keeps the arrays alive during the write (Model::materialSource()).
  MaterialSource materials;
  bool writeNormals = true;  // when the mesh has normals
  bool writeUvs = true;      // when the mesh has uv0
};

// The name a submesh of material `materialId` is written with (see MeshWriteOptions).
std::string materialName(const MeshWriteOptions& options, uint32_t materialId);

// Wavefront OBJ text: `v`, `vt` (uv0), `vn` (normals), one `usemtl` per submesh and `f v/t/n`
// faces. No .mtl file is written. An invalid mesh (ragged index list, index out of range,
// submeshes not covering the indices) is an error.
MeshWriteResult writeObjToString(const geometry::MeshData& mesh, const MeshWriteOptions& options,
                                 std::string& out);
MeshWriteResult writeObj(const std::string& path, const geometry::MeshData& mesh,
                         const MeshWriteOptions& options);

// Binary glTF 2.0: one mesh, one node, positions (with bounds), normals, uv0 and uint32 indices,
// one primitive per submesh with its own material (named as above, copied from
// MeshWriteOptions::materials when it has the id).
MeshWriteResult writeGlbToMemory(const geometry::MeshData& mesh, const MeshWriteOptions& options,
                                 std::vector<uint8_t>& out);
MeshWriteResult writeGlb(const std::string& path, const geometry::MeshData& mesh,
                         const MeshWriteOptions& options);

}  // namespace cleave::assets
