// Arena enemies: kinds, spawning and the walk-to-the-player-and-strike behaviour.
//
// An enemy is one entity with a MeshRenderer, a Splitable and a rigid body that the game moves
// itself every tick (setBodyTransform plus the walking velocity, so the pieces of a cut go on with
// the motion the enemy had): a dynamic body for the gladiators, a kinematic one (the posed hull) for
// the skinned warriors, whose SkinnedMesh plays its walk and idle clips. A blade touching it freezes it until its split is done; the split
// system's event for its entity is its death.
//
// Adding a kind: a value in EnemyKind, a case in kindInfo() (name and tuning), a spawn function in
// spawnEnemy() and, if it is not posed by moving its body, a case in poseEnemy().
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>

#include "components/skinned.h"
#include "engine/assets/procedural_character.h"
#include "engine/ecs/entity.h"
#include "engine/ecs/world.h"
#include "engine/geometry/mesh_data.h"
#include "engine/physics/physics_world.h"
#include "engine/render/renderer.h"
#include "game/arena/arena_art.h"

namespace cleave::arena {

enum class EnemyKind : uint8_t {
  Gladiator,  // convex parts (legs, torso, head, arms) merged into one mesh under one Splitable
  Skinned,    // the generated skinned character, animated; cut in its pose, its halves fall as ragdolls
  Count
};

struct EnemyKindInfo {
  const char* name = "";
  float walkSpeed = 1.8f;      // m/s
  float attackRange = 1.25f;   // m, centre to centre on the floor
  float attackDamage = 6.f;    // health points per blow
  float attackSeconds = 1.1f;  // between blows
  float radius = 0.4f;         // m, on the floor (for crowding and obstacles)
};
const EnemyKindInfo& kindInfo(EnemyKind kind);

struct Enemy {
  ecs::Entity entity;
  EnemyKind kind = EnemyKind::Gladiator;
  glm::vec2 position{0.f};  // on the floor, (x, z), metres
  float yaw = 0.f;          // radians; facing (sin yaw, 0, cos yaw)
  float walkPhase = 0.f;    // radians
  float attackTimer = 0.f;  // seconds until a blow may land
  float lunge = 0.f;        // seconds left of the blow animation
  bool hit = false;         // a blade touches it: frozen until the split lands (or misses)
  uint8_t hitBy = 0;        // the weapon that touched it (ArenaGame's weapon index), for the kill count
  // The body frame (centre of mass, principal axes) in the enemy's own frame.
  glm::vec3 bodyLocalPosition{0.f};
  glm::quat bodyLocalRotation{1.f, 0.f, 0.f, 0.f};
};

// What spawning and posing touch. The renderer may be null (no upload).
struct EnemyContext {
  ecs::World& world;
  physics::PhysicsWorld& physics;
  render::Renderer* renderer = nullptr;
  const ArenaMaterials& materials;
};

// Shared meshes of the kinds (built once; immutable, shared by every enemy's MeshRenderer).
struct EnemyMeshes {
  std::shared_ptr<const geometry::MeshData> gladiator;
  // The skinned kind: the generated character's bind-space mesh and its skeleton with the idle and
  // walk clips.
  std::shared_ptr<const geometry::MeshData> skinned;
  std::shared_ptr<const components::SkinnedAsset> skinnedAsset;
};
EnemyMeshes makeEnemyMeshes(const assets::ProceduralCharacter& character);

// Creates an enemy of `kind` standing at `position` facing `yaw`. Returns an Enemy with a null
// entity (and prints why) when its body cannot be made.
Enemy spawnEnemy(EnemyContext& c, const EnemyMeshes& meshes, EnemyKind kind, glm::vec2 position, float yaw);

// Places the enemy's body for its current position, yaw, walk phase and blow, with `velocity`.
void poseEnemy(EnemyContext& c, const Enemy& enemy, glm::vec3 velocity);

// Round obstacles on the floor (pillars) and the arena's radius, for steering.
struct Obstacle {
  glm::vec2 centre{0.f};
  float radius = 0.f;
};

// One tick of every enemy: walk towards the player (steering around obstacles and each other),
// strike when in range. Returns the damage dealt to the player this tick.
float updateEnemies(EnemyContext& c, std::vector<Enemy>& enemies, glm::vec2 player, float dt,
                    const std::vector<Obstacle>& obstacles, float arenaRadius);

}  // namespace cleave::arena
