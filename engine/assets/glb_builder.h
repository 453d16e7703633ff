// SPDX-License-Identifier: MIT
// Internal to engine/assets: the GLB writing core that the static mesh writer (gltf_io.cpp) and the
// skinned writer (skinned_glb_writer.cpp) share, so the buffer, the accessors, the materials and
// the primitives are built in one place. A writer starts a model, adds the mesh's vertex attributes
// (the skinned writer adds JOINTS_0 and WEIGHTS_0 of its own), the mesh with its primitives and
// materials, its nodes, and serialises. Not installed for users' code in any other way than as a
// header of the assets layer; it needs <tiny_gltf.h>.
//
// Everything goes into one buffer (buffer 0), in the order it is added: the GLB's BIN chunk. Byte
// order is the platform's, which is little-endian on every platform the engine builds for, as glTF
// requires.
#pragma once

#include <tiny_gltf.h>

#include <cstddef>
#include <cstdint>
#include <map>
#include <span>
#include <string>
#include <vector>

#include "cleave/assets/mesh_io.h"
#include "cleave/geometry/mesh_data.h"

namespace cleave::assets::detail {

// An empty glTF 2.0 model (generator "Cleave") with the one buffer everything is written into.
tinygltf::Model newGlbModel();

// Appends `size` bytes to the buffer at the next multiple of 4, as glTF requires for float and
// 32-bit data, and gives their offset.
size_t appendToBuffer(tinygltf::Model& model, const void* bytes, size_t size);
// A view of `length` bytes at `offset` of the buffer; `target` 0 leaves it without a target (data
// that is not vertex or index data: inverse bind matrices, animation keys). Gives its index.
int addView(tinygltf::Model& model, size_t offset, size_t length, int target);
// An accessor of `count` elements at `byteOffset` in view `view`. Gives its index.
int addAccessor(tinygltf::Model& model, int view, size_t byteOffset, int componentType, int type,
                size_t count);

// `values` in a view of their own and an accessor over all of them. Gives the accessor's index.
template <typename T>
int addData(tinygltf::Model& model, const std::vector<T>& values, int target, int componentType,
            int type) {
  const size_t length = values.size() * sizeof(T);
  const int view = addView(model, appendToBuffer(model, values.data(), length), length, target);
  return addAccessor(model, view, 0, componentType, type, values.size());
}

// Attribute name -> accessor, shared by every primitive of the mesh.
using GlbAttributes = std::map<std::string, int>;

// The validated submesh runs of a mesh a GLB writer gets (writableRuns), which must also have a
// triangle; false with a reason otherwise.
bool glbRuns(const geometry::MeshData& mesh, std::vector<geometry::SubMesh>& runs,
             std::string& reason);

// The vertex data of a mesh that passed glbRuns: POSITION with its bounds (glTF requires
// them), NORMAL and TEXCOORD_0 when the mesh has them and `options` asks for them.
GlbAttributes addVertexAttributes(tinygltf::Model& model, const geometry::MeshData& mesh,
                                  const MeshWriteOptions& options);

// Whether materials without a source material get MeshWriteOptions::materialColors as their base
// colours. The static writer writes none (the options document the colours for the skinned
// writer), so its output does not depend on them.
enum class GlbColors : uint8_t { Omit, Write };

// Copies materials of MeshWriteOptions::materials into a GLB model as they are asked for; the
// textures, samplers and images they use are written once each, in order of first use (images as
// buffer views of the source's encoded bytes, with its mime type). Lives for one model.
class GlbMaterialCopy {
 public:
  // `uvSets`: how many TEXCOORD_<n> sets the primitives have; a texture read with a set beyond
  // them is left out.
  GlbMaterialCopy(tinygltf::Model& model, const MaterialSource& source, int uvSets);
  // Fills the factors, doubleSided and the textures of `out` from source material `id`; false
  // (and `out` untouched) when the source has no material `id`.
  bool copy(uint32_t id, tinygltf::Material& out);

 private:
  // The written index of a source texture, sampler or image, written on first use; -1 when it
  // cannot be written (a missing image, or one without encoded PNG or JPEG bytes).
  int texture(const ModelTextureRef& ref);
  int sampler(int32_t index);
  int image(int32_t index);

  tinygltf::Model& model_;
  MaterialSource source_;
  int uvSets_;
  std::vector<int> textures_, samplers_, images_;  // source index -> written index, -2 unseen
};

// The indices as one view, then mesh 0 ("mesh") with one primitive per non-empty run: `attributes`,
// uint32 indices (an accessor into that view) and a material per material id, in order of first
// use, named by materialName and copied from options.materials when it has the id (not the cap).
// Call it after the vertex data, so that the index view follows it.
void addMesh(tinygltf::Model& model, const geometry::MeshData& mesh,
             std::span<const geometry::SubMesh> runs, const GlbAttributes& attributes,
             const MeshWriteOptions& options, GlbColors colors);

// The node of mesh 0 ("piece", with skin `skin`, -1 for none) and the default scene: `roots`, then
// that node. The node has no transform (glTF places a skinned mesh by its joints only).
void addMeshScene(tinygltf::Model& model, std::vector<int> roots, int skin);

// Pads the buffer to a multiple of 4 bytes and serialises the model as GLB into `out`; false (and
// `out` untouched) when tinygltf fails or throws.
bool serialiseGlb(tinygltf::Model& model, std::vector<uint8_t>& out);

}  // namespace cleave::assets::detail
