// SPDX-License-Identifier: MIT
// Internal to the components library: a scene as read from its file, before anything is created
// (scene_read.cpp reads it, scene_loader.cpp builds the world from it).
#pragma once

#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "cleave/components/scene_json.h"
#include "cleave/components/scene_loader.h"
#include "cleave/components/splitable.h"
#include "cleave/ecs/hierarchy.h"
#include "cleave/geometry/mesh_data.h"

namespace cleave::components::scene_json {

enum class BodyKind { None, Static, Dynamic };

struct EntityDesc {
  std::vector<std::string> path;  // JSON pointer tokens, for errors found while creating it
  std::string name;
  std::string material;
  bool hasMesh = false;
  geometry::MeshData mesh;
  bool isBox = false;          // a box primitive (a static box gets a box collider)
  glm::vec3 boxHalfExtents{0.5f};
  ecs::Transform transform;
  BodyKind body = BodyKind::None;
  double density = 1000.0;
  std::optional<double> mass;
  glm::vec3 linearVelocity{0.f};
  glm::vec3 angularVelocity{0.f};
  ColliderMode collider = ColliderMode::Auto;
  bool splitable = false;
  Splitable split;
  bool splitDensityGiven = false;
  std::string capMaterial;
  bool capMaterialIdGiven = false;
  std::vector<EntityDesc> children;
};

struct FloorDesc {
  bool present = false;
  float height = 0.f;
  glm::vec3 halfExtents{30.f, 0.5f, 30.f};
  std::string material = "floor";
};

struct SceneDesc {
  glm::vec3 gravity{0.f, -9.81f, 0.f};
  FloorDesc floor;
  bool budgetGiven = false;
  SplitBudgetSettings budget;
  bool pieceBudgetGiven = false;
  PieceBudgetSettings pieceBudget;
  glm::vec3 cameraPosition{0.f, 2.f, 6.f};
  glm::vec3 cameraTarget{0.f};
  uint64_t ticks = 0;
  std::vector<EntityDesc> entities;
  std::vector<ScheduledSplitter> splitters;
};

// Reads the whole scene; false (with the Reader's error) on the first bad value. Mesh files are
// found relative to `baseDirectory`.
bool readScene(Reader& rd, const json& root, const std::string& baseDirectory, SceneDesc& scene);

}  // namespace cleave::components::scene_json
