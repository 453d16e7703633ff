// SPDX-License-Identifier: MIT
// Arena enemies: kinds, spawning and the walk-to-the-player-and-strike behaviour.
//
// An enemy is one entity with a MeshRenderer, a Splitable and a rigid body that the game moves
// itself every tick (setBodyTransform plus the walking velocity, so the pieces of a cut go on with
// the motion the enemy had): a dynamic body for the gladiators, a kinematic one (the posed hull) for
// the skinned warriors, whose SkinnedMesh plays its walk and idle clips. A blade touching it freezes it until its split is done; the split
// system's event for its entity is its death.
//
// Adding a kind: a value in EnemyKind, a case in kindName() and kindTuning() (its EnemyTuning in
// ArenaTuning), a spawn function in spawnEnemy() and, if it is not posed by moving its body, a case
// in poseEnemy().
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>

#include "cleave/components/skinned.h"
#include "cleave/anim/animation_clip.h"
#include "cleave/assets/procedural_character.h"
#include "cleave/ecs/entity.h"
#include "cleave/ecs/world.h"
#include "cleave/geometry/mesh_data.h"
#include "cleave/physics/physics_world.h"
#include "cleave/render/renderer.h"
#include "game/arena/arena_art.h"
#include "game/arena/arena_tuning.h"

namespace cleave::arena {

enum class EnemyKind : uint8_t {
  Gladiator,  // convex parts (legs, torso, head, arms) merged into one mesh under one Splitable
  Skinned,    // the generated skinned character, animated; cut in its pose, its halves fall as ragdolls
  Count
};

// The kind's name in the state dump ("gladiator", "skinned") and its tuning (arena_tuning.h).
const char* kindName(EnemyKind kind);
const EnemyTuning& kindTuning(const ArenaTuning& tuning, EnemyKind kind);

// What an enemy is doing this tick (shown in the state dump as `behaviour`).
enum class EnemyBehaviour : uint8_t {
  Approach,  // walking towards the player, or to its place among those who wait
  Wait,      // near the player, waiting its turn: MatchTuning::maxAttackers strike at once
  Strike,    // in range: winding up, then a blow every attackSeconds
  Frozen,    // a blade touches it: still until its split lands (or misses)
  Cheer,     // the player is beaten: it stays where it is, upright, arms up and hopping; no blows
};
const char* toString(EnemyBehaviour behaviour);

struct Enemy {
  ecs::Entity entity;
  EnemyKind kind = EnemyKind::Gladiator;
  glm::vec2 position{0.f};  // on the floor, (x, z), metres
  float yaw = 0.f;          // radians; facing (sin yaw, 0, cos yaw)
  float walkPhase = 0.f;    // radians
  float attackTimer = 0.f;  // seconds until a blow may land
  float lunge = 0.f;        // seconds left of the blow animation
  bool engaged = false;     // in range since its wind-up began (it strikes when attackTimer runs out)
  EnemyBehaviour behaviour = EnemyBehaviour::Approach;
  uint64_t spawnTick = 0;   // the tick it came through its gate
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
  // walk clips, and a "cheer" clip of its own (arms up, hopping; makeCheerClip).
  std::shared_ptr<const geometry::MeshData> skinned;
  std::shared_ptr<const components::SkinnedAsset> skinnedAsset;
};
EnemyMeshes makeEnemyMeshes(const assets::ProceduralCharacter& character);

// The skinned warriors' cheer for the generated character's skeleton: a looping clip named "cheer"
// (0.8 s) with both arms raised over the head and pumping, the chest thrown back and a small hop
// (the hips rise up to 6 cm, so the feet leave the sand).
anim::AnimationClip makeCheerClip(const anim::Skeleton& skeleton);

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

// Where the enemies walk: the player's place, the pillars and the wall.
struct EnemyField {
  glm::vec2 player{0.f};
  float playerRadius = 0.35f;                        // m: nobody walks into the player
  const std::vector<Obstacle>* obstacles = nullptr;  // may be null: no pillars
  float arenaRadius = 12.f;                          // m, the inner face of the wall
};

// One tick of every enemy while a wave is on. The nearest MatchTuning::maxAttackers (those already
// striking first) walk up to the player and strike after their wind-up; the others stop
// waitDistance from the player and wait their turn. Everyone steers around the pillars and keeps
// apart from the others. Returns the damage dealt to the player this tick (health points).
int updateEnemies(EnemyContext& c, std::vector<Enemy>& enemies, const EnemyField& field, const ArenaTuning& tuning,
                  float dt);

// One tick of every enemy after the player is beaten: each stays where it stands, turns to the
// player and cheers (behaviour Cheer, upright, no blows). One still frozen by a blade stays frozen
// until its split lands.
void cheerEnemies(EnemyContext& c, std::vector<Enemy>& enemies, glm::vec2 player, float dt);

// A blade touched the enemy: it stands still for `seconds` (its split lands meanwhile) and starts
// its wind-up again afterwards.
void freezeEnemy(Enemy& enemy, float seconds);

}  // namespace cleave::arena
