// SPDX-License-Identifier: MIT
// The GLB writing core of glb_builder.h: the buffer, views and accessors, the mesh with its
// materials and primitives, the scene and the serialisation that both GLB writers share (the
// copy of source materials is in glb_materials.cpp).
#include "cleave/assets/glb_builder.h"

#include <cstring>
#include <sstream>
#include <utility>

#include "cleave/assets/gltf_attributes.h"
#include "cleave/assets/mesh_reader.h"

namespace cleave::assets::detail {

namespace {

// The material of id `id`: its name, then the source material's properties when options.materials
// has it (the cap never takes one), else the id's colour when `colors` asks for it.
tinygltf::Material glbMaterial(const MeshWriteOptions& options, GlbColors colors,
                               GlbMaterialCopy& copy, uint32_t id) {
  tinygltf::Material material;
  material.name = materialName(options, id);
  if (id != options.capMaterialId && copy.copy(id, material)) return material;
  if (colors == GlbColors::Write && id < options.materialColors.size()) {
    const glm::vec4 c = glm::clamp(options.materialColors[id], glm::vec4(0.f), glm::vec4(1.f));
    material.pbrMetallicRoughness.baseColorFactor = {c.r, c.g, c.b, c.a};
  }
  return material;
}

}  // namespace

tinygltf::Model newGlbModel() {
  tinygltf::Model model;
  model.asset.version = "2.0";
  model.asset.generator = "Cleave";
  model.buffers.emplace_back();
  return model;
}

size_t appendToBuffer(tinygltf::Model& model, const void* bytes, size_t size) {
  std::vector<unsigned char>& buffer = model.buffers[0].data;
  while (buffer.size() % 4 != 0) buffer.push_back(0);
  const size_t offset = buffer.size();
  buffer.resize(offset + size);
  if (size > 0) std::memcpy(buffer.data() + offset, bytes, size);
  return offset;
}

int addView(tinygltf::Model& model, size_t offset, size_t length, int target) {
  tinygltf::BufferView view;
  view.buffer = 0;
  view.byteOffset = offset;
  view.byteLength = length;
  view.target = target;
  model.bufferViews.push_back(view);
  return static_cast<int>(model.bufferViews.size() - 1);
}

int addAccessor(tinygltf::Model& model, int view, size_t byteOffset, int componentType, int type,
                size_t count) {
  tinygltf::Accessor accessor;
  accessor.bufferView = view;
  accessor.byteOffset = byteOffset;
  accessor.componentType = componentType;
  accessor.type = type;
  accessor.count = count;
  model.accessors.push_back(accessor);
  return static_cast<int>(model.accessors.size() - 1);
}

bool glbRuns(const geometry::MeshData& mesh, std::vector<geometry::SubMesh>& runs,
             std::string& reason) {
  if (!writableRuns(mesh, runs, reason)) return false;
  if (mesh.indices.empty()) {
    reason = "the mesh has no triangles";
    return false;
  }
  return true;
}

namespace {

// `values` of the attribute of `field` as the attribute table writes it.
template <typename T>
int addAttribute(tinygltf::Model& model, const std::vector<T>& values, VertexField field,
                 GlbAttributes& attributes) {
  const GltfAttribute& attribute = gltfAttribute(field);
  const int accessor = addData(model, values, TINYGLTF_TARGET_ARRAY_BUFFER,
                               attribute.writtenComponentType, attribute.type);
  attributes[attribute.name] = accessor;
  return accessor;
}

}  // namespace

GlbAttributes addVertexAttributes(tinygltf::Model& model, const geometry::MeshData& mesh,
                                  const MeshWriteOptions& options) {
  GlbAttributes attributes;
  const int position = addAttribute(model, mesh.positions, VertexField::Positions, attributes);
  glm::vec3 lo(0.f), hi(0.f);
  if (!mesh.positions.empty()) lo = hi = mesh.positions[0];
  for (const glm::vec3& p : mesh.positions) {
    lo = glm::min(lo, p);
    hi = glm::max(hi, p);
  }
  model.accessors[static_cast<size_t>(position)].minValues = {lo.x, lo.y, lo.z};
  model.accessors[static_cast<size_t>(position)].maxValues = {hi.x, hi.y, hi.z};
  // writableRuns made sure that normals and uv0 are either empty or one per vertex.
  if (options.writeNormals && !mesh.normals.empty()) {
    addAttribute(model, mesh.normals, VertexField::Normals, attributes);
  }
  if (options.writeUvs && !mesh.uv0.empty()) {
    addAttribute(model, mesh.uv0, VertexField::Uv0, attributes);
  }
  return attributes;
}

void addMesh(tinygltf::Model& model, const geometry::MeshData& mesh,
             std::span<const geometry::SubMesh> runs, const GlbAttributes& attributes,
             const MeshWriteOptions& options, GlbColors colors) {
  const size_t indexBytes = mesh.indices.size() * sizeof(uint32_t);
  const int indexView = addView(model, appendToBuffer(model, mesh.indices.data(), indexBytes),
                                indexBytes, TINYGLTF_TARGET_ELEMENT_ARRAY_BUFFER);
  tinygltf::Mesh gltfMesh;
  gltfMesh.name = "mesh";
  GlbMaterialCopy copy(model, options.materials, attributes.count("TEXCOORD_0") != 0 ? 1 : 0);
  // glTF material index -> our material id, in order of first use.
  std::vector<uint32_t> materialIds;
  for (const geometry::SubMesh& run : runs) {
    if (run.indexCount == 0) continue;
    int material = -1;
    for (size_t i = 0; i < materialIds.size(); ++i) {
      if (materialIds[i] == run.materialId) material = static_cast<int>(i);
    }
    if (material < 0) {
      materialIds.push_back(run.materialId);
      model.materials.push_back(glbMaterial(options, colors, copy, run.materialId));
      material = static_cast<int>(model.materials.size() - 1);
    }
    tinygltf::Primitive primitive;
    primitive.mode = TINYGLTF_MODE_TRIANGLES;
    primitive.material = material;
    primitive.attributes = attributes;
    primitive.indices =
        addAccessor(model, indexView, size_t{run.firstIndex} * sizeof(uint32_t),
                    TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT, TINYGLTF_TYPE_SCALAR, run.indexCount);
    gltfMesh.primitives.push_back(primitive);
  }
  model.meshes.push_back(gltfMesh);
}

void addMeshScene(tinygltf::Model& model, std::vector<int> roots, int skin) {
  tinygltf::Node node;
  node.name = "piece";
  node.mesh = 0;
  node.skin = skin;
  model.nodes.push_back(node);
  tinygltf::Scene scene;
  scene.nodes = std::move(roots);
  scene.nodes.push_back(static_cast<int>(model.nodes.size() - 1));
  model.scenes.push_back(scene);
  model.defaultScene = 0;
}

bool serialiseGlb(tinygltf::Model& model, std::vector<uint8_t>& out) {
  // tinygltf pads the BIN chunk itself; padding the buffer too keeps its byteLength equal to the
  // chunk's.
  std::vector<unsigned char>& data = model.buffers[0].data;
  data.resize((data.size() + 3) / 4 * 4, 0);
  std::ostringstream stream;
  tinygltf::TinyGLTF writer;
  bool written = false;
  try {
    written = writer.WriteGltfSceneToStream(&model, stream, false, true);
  } catch (...) {
    written = false;
  }
  if (!written) return false;
  const std::string bytes = stream.str();
  out.assign(bytes.begin(), bytes.end());
  return true;
}

}  // namespace cleave::assets::detail
