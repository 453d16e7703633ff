// SPDX-License-Identifier: MIT
// Internal to engine/assets: the vertex attributes that the glTF readers (gltf_io.cpp, the model
// loader) read and the GLB writers write, as one table: the glTF attribute name, the accessor type
// and the component types it may have, the component type written, and the MeshData field it
// fills. Also the parts of a primitive both readers share: its mode, its corner list and its
// triangles in the mesh's winding. Needs <tiny_gltf.h> (through gltf_access.h).
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "cleave/assets/gltf_access.h"

namespace cleave::assets::detail {

// The MeshData field an attribute fills (positions, normals, uv0, joints, weights).
enum class VertexField : uint8_t { Positions, Normals, Uv0, Joints, Weights };

struct GltfAttribute {
  const char* name;  // glTF attribute name
  VertexField field;
  int type;        // accessor type (TINYGLTF_TYPE_VEC2 ...)
  int components;  // components of that type
  // Component types read: float, normalized unsigned byte or short, (plain) unsigned byte or short.
  bool readsFloat;
  bool readsNormalized;
  bool readsUnsigned;
  int writtenComponentType;  // what the GLB writers write
  // The message (after "mesh M primitive P: ") for an accessor the attribute does not accept.
  const char* requirement;
};

// POSITION, NORMAL, TEXCOORD_0, JOINTS_0, WEIGHTS_0, in that order (the order the model loader
// reads them in).
extern const GltfAttribute kGltfAttributes[5];
const GltfAttribute& gltfAttribute(VertexField field);

// Whether `view` is what `attribute` accepts: its type and a component type it reads, and (but for
// POSITION, which sets it) `vertexCount` elements.
bool attributeFits(const GltfAttribute& attribute, const AccessorView& view, size_t vertexCount);

// The primitive's accessor of `attribute`: false with viewAccessor's reason when it cannot be read;
// `accessor` is -1 (and true) when the primitive has no such attribute.
bool viewAttribute(const tinygltf::Model& model, const tinygltf::Primitive& primitive,
                   const GltfAttribute& attribute, AccessorView& view, int& accessor,
                   std::string& reason);

// The primitive's mode when it gives triangles (TRIANGLES, TRIANGLE_STRIP or TRIANGLE_FAN; the
// default is TRIANGLES); false for points and lines. usesDraco: whether it is Draco-compressed,
// which neither reader supports.
bool triangleMode(const tinygltf::Primitive& primitive, int& mode);
bool usesDraco(const tinygltf::Primitive& primitive);

// Why a primitive's corner list could not be read.
struct CornerFailure {
  enum Kind { View, Type, Range, TooManyVertices } kind = View;
  std::string reason;  // View: viewAccessor's reason
  uint64_t index = 0;  // Range: the index and where it is
  size_t position = 0;
};
// The corners of a primitive of `vertexCount` vertices: its indices (unsigned byte, short or int
// scalars, each below vertexCount) or 0..vertexCount-1 without them.
bool primitiveCorners(const tinygltf::Model& model, const tinygltf::Primitive& primitive,
                      size_t vertexCount, std::vector<uint32_t>& corners, CornerFailure& failure);

// Appends `triangles` (corner triples of a primitive whose first vertex is `base`) to `indices`,
// reversing each when the primitive's transform mirrors, so that all keep their outward winding.
void appendTriangles(std::span<const uint32_t> triangles, size_t base, bool mirrored,
                     std::vector<uint32_t>& indices);

}  // namespace cleave::assets::detail
