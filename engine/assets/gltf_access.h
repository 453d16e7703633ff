// SPDX-License-Identifier: MIT
// Internal to engine/assets: checked access to glTF accessors and nodes through tinygltf, shared by
// the static mesh reader (gltf_io.cpp) and the model loader (gltf_model.cpp). Not installed for
// users' code in any other way than as a header of the assets layer; it needs <tiny_gltf.h>.
#pragma once

#include <tiny_gltf.h>

#include <cstdint>
#include <glm/glm.hpp>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "cleave/base/status.h"

namespace cleave::assets::detail {

// One accessor's elements in its buffer, after every offset, stride and count was checked.
struct AccessorView {
  const uint8_t* data = nullptr;
  size_t count = 0;
  size_t stride = 0;
  int componentType = 0;
  int components = 0;
  bool normalized = false;
};

// Fills `view` for accessor `index`; false with a reason (naming the accessor) when it cannot be
// read.
bool viewAccessor(const tinygltf::Model& model, int index, AccessorView& view, std::string& reason);
// Component c of element i as a double (normalized integers mapped to [0, 1] or [-1, 1]).
double component(const AccessorView& view, size_t i, int c);
// A node's local matrix (matrix, or T * R * S); a zero-length rotation gives NaNs.
glm::dmat4 localMatrix(const tinygltf::Node& node);
// The triangle list of a primitive's corners for mode TRIANGLES, TRIANGLE_STRIP (every other
// triangle reversed, so all keep the strip's winding) or TRIANGLE_FAN (around the first corner).
// A list whose length is not a multiple of 3 loses its last partial triangle: false then, so the
// caller can warn.
bool trianglesOfPrimitive(int mode, std::span<const uint32_t> corners, std::vector<uint32_t>& triangles);
// One line out of tinygltf's multi-line messages.
std::string oneLine(const std::string& text);
// Extensions that only change materials or textures: geometry can be read without them.
bool geometryNeutral(const std::string& extension);

// tinygltf's parse of a .gltf or .glb held in memory. With no base directory, external files are
// refused. `imageUserData` is handed to `imageLoader` with every image. A failure (ParseError) has a
// message of one line (tinygltf's error, an exception it threw, or a generic reason); `warnings` are
// "<name>: <warning>" lines.
struct GltfParse : base::Status {
  std::vector<std::string> warnings;
};
GltfParse parseGltf(std::span<const uint8_t> bytes, const std::string& name, bool binary,
                    const std::optional<std::string>& baseDir, tinygltf::LoadImageDataFunction imageLoader,
                    void* imageUserData, tinygltf::Model& model);

}  // namespace cleave::assets::detail
