// SPDX-License-Identifier: MIT
// The glTF vertex attribute table and the primitive parts both readers share (see
// gltf_attributes.h).
#include "cleave/assets/gltf_attributes.h"

namespace cleave::assets::detail {

const GltfAttribute kGltfAttributes[5] = {
    {"POSITION", VertexField::Positions, TINYGLTF_TYPE_VEC3, 3, true, false, false,
     TINYGLTF_COMPONENT_TYPE_FLOAT, "POSITION must be a float VEC3"},
    {"NORMAL", VertexField::Normals, TINYGLTF_TYPE_VEC3, 3, true, false, false,
     TINYGLTF_COMPONENT_TYPE_FLOAT, "NORMAL must be a float VEC3 with one entry per vertex"},
    {"TEXCOORD_0", VertexField::Uv0, TINYGLTF_TYPE_VEC2, 2, true, true, false,
     TINYGLTF_COMPONENT_TYPE_FLOAT,
     "TEXCOORD_0 must be a VEC2 (float or normalized unsigned) per vertex"},
    {"JOINTS_0", VertexField::Joints, TINYGLTF_TYPE_VEC4, 4, false, false, true,
     TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT,
     "JOINTS_0 must be an unsigned byte or short VEC4 per vertex"},
    {"WEIGHTS_0", VertexField::Weights, TINYGLTF_TYPE_VEC4, 4, true, true, false,
     TINYGLTF_COMPONENT_TYPE_FLOAT,
     "WEIGHTS_0 must be a float or normalized unsigned VEC4 per vertex"},
};

const GltfAttribute& gltfAttribute(VertexField field) {
  return kGltfAttributes[static_cast<size_t>(field)];
}

bool attributeFits(const GltfAttribute& attribute, const AccessorView& view, size_t vertexCount) {
  const bool smallUnsigned = view.componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE ||
                             view.componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT;
  const bool typeOk =
      (attribute.readsFloat && view.componentType == TINYGLTF_COMPONENT_TYPE_FLOAT) ||
      (attribute.readsNormalized && view.normalized && smallUnsigned) ||
      (attribute.readsUnsigned && smallUnsigned);
  const bool countOk = attribute.field == VertexField::Positions || view.count == vertexCount;
  return view.components == attribute.components && typeOk && countOk;
}

bool viewAttribute(const tinygltf::Model& model, const tinygltf::Primitive& primitive,
                   const GltfAttribute& attribute, AccessorView& view, int& accessor,
                   std::string& reason) {
  accessor = -1;
  const auto it = primitive.attributes.find(attribute.name);
  if (it == primitive.attributes.end()) return true;
  if (!viewAccessor(model, it->second, view, reason)) return false;
  accessor = it->second;
  return true;
}

bool usesDraco(const tinygltf::Primitive& primitive) {
  return primitive.extensions.count("KHR_draco_mesh_compression") != 0;
}

bool triangleMode(const tinygltf::Primitive& primitive, int& mode) {
  mode = primitive.mode < 0 ? TINYGLTF_MODE_TRIANGLES : primitive.mode;
  return mode == TINYGLTF_MODE_TRIANGLES || mode == TINYGLTF_MODE_TRIANGLE_STRIP ||
         mode == TINYGLTF_MODE_TRIANGLE_FAN;
}

bool primitiveCorners(const tinygltf::Model& model, const tinygltf::Primitive& primitive,
                      size_t vertexCount, std::vector<uint32_t>& corners, CornerFailure& failure) {
  if (primitive.indices < 0) {
    if (vertexCount > UINT32_MAX) {
      failure.kind = CornerFailure::TooManyVertices;
      return false;
    }
    corners.resize(vertexCount);
    for (size_t i = 0; i < vertexCount; ++i) corners[i] = static_cast<uint32_t>(i);
    return true;
  }
  AccessorView view;
  if (!viewAccessor(model, primitive.indices, view, failure.reason)) {
    failure.kind = CornerFailure::View;
    return false;
  }
  if (view.components != 1 || (view.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE &&
                               view.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT &&
                               view.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT)) {
    failure.kind = CornerFailure::Type;
    return false;
  }
  corners.resize(view.count);
  for (size_t i = 0; i < view.count; ++i) {
    const double value = component(view, i, 0);
    if (value >= static_cast<double>(vertexCount)) {
      failure = {CornerFailure::Range, {}, static_cast<uint64_t>(value), i};
      return false;
    }
    corners[i] = static_cast<uint32_t>(value);
  }
  return true;
}

void appendTriangles(std::span<const uint32_t> triangles, size_t base, bool mirrored,
                     std::vector<uint32_t>& indices) {
  for (size_t t = 0; t + 2 < triangles.size(); t += 3) {
    const uint32_t a = static_cast<uint32_t>(base) + triangles[t];
    const uint32_t b = static_cast<uint32_t>(base) + triangles[t + 1];
    const uint32_t c = static_cast<uint32_t>(base) + triangles[t + 2];
    indices.insert(indices.end(), {a, mirrored ? c : b, mirrored ? b : c});
  }
}

}  // namespace cleave::assets::detail
