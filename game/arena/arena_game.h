// SPDX-License-Identifier: MIT
// The arena sample: a round gladiator arena where waves of enemies (multi-part gladiators and skinned
// warriors that fall as ragdoll halves) walk to the player,
// who cuts them with a thrown energy disc (a persistent Splitter that bounces off the wall and comes
// back), an energy sword (a one-tick Splitter in the swing's plane) and a spin attack (a one-tick
// Splitter around the player). A menu of metal cubes, split on click, starts the match.
//
// It is a game loop on the split components: everything that cuts is a Splitter, everything that is
// cut is a Splitable, the split system's events tell the game who died, and the split budget spreads
// a burst of kills over the following ticks. Pieces stay for a while, shrink and are removed with
// their GPU mesh and body.
#pragma once

#include <cstdint>
#include <deque>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>
#include <nlohmann/json_fwd.hpp>

#include "cleave/components/resource_hooks.h"
#include "cleave/components/split_log.h"
#include "cleave/components/split_stats.h"
#include "cleave/components/simulation.h"
#include "cleave/components/split_system.h"
#include "cleave/anim/animation_clip.h"
#include "cleave/app/app.h"
#include "cleave/assets/procedural_character.h"
#include "cleave/physics/physics_world.h"
#include "game/arena/arena_art.h"
#include "game/arena/arena_tuning.h"
#include "game/arena/enemies.h"
#include "game/inspector/inspector.h"

namespace cleave::arena {

enum class MatchState : uint8_t {
  Menu,          // the Start and Quit cubes wait for a click (on a clean arena: see resetToMenu)
  Starting,      // the Start cube was cut: its pieces fall while the camera moves behind the player
  Intermission,  // no enemy on the sand: the grace period before wave 1 ("GET READY"), or the pause
                 // after a wave ("WAVE n CLEARED", the health bar fills up again)
  Playing,       // a wave is on
  Defeated,      // health ran out: the enemies cheer; Enter (or a click) goes back to the menu
  Quitting,      // the Quit cube was cut: the game ends shortly
};
const char* toString(MatchState state);

enum class PropKind : uint8_t { Crate, Urn };

// What an entity is, for the state dump and the game's own queries.
struct ArenaTag {
  enum Kind : uint8_t { Level, Prop, MenuCube, Enemy, Piece, Player, Weapon } kind = Level;
};

// A piece's clock: it stays for a while, then shrinks about its centre of mass and is removed.
struct Fading {
  uint64_t bornTick = 0;
  glm::mat4 baseOffset{1.f};  // its mesh offset when it was made
};

class ArenaGame {
 public:
  ArenaGame();
  ~ArenaGame();

  // Builds the arena and registers the systems (it cannot fail today; the Status is the shape every
  // setup has).
  base::Status setup(app::App& app);

  // The numbers the match plays by (arena_tuning.h); change them before setup.
  ArenaTuning& tuning() { return tuning_; }

  // What the physics world and the renderer hold now (physics 0 before setup).
  components::ResourceCounts resources() const;
  // Split jobs computed off the main thread so far (the proof a run on N split threads used them).
  uint64_t splitJobsOffMainThread() const { return sim_ ? sim_->splits().jobsComputedOffTheCallingThread() : 0; }
  // Destroys every entity (their hooks free what they hold), then the level's colliders and the
  // player's, the blade's and the disc's GPU meshes, which no entity holds: the counts are then
  // those from before setup. For the --resource-report leak check, after the run.
  void releaseAll();

 private:
  struct Disc {
    bool active = false;
    ecs::Entity splitter;
    glm::vec2 position{0.f};
    glm::vec2 direction{0.f, -1.f};
    int bounces = 0;
    bool returning = false;
    float age = 0.f;
    float spin = 0.f;
  };
  struct Swing {
    int ticksLeft = 0;
    int duration = 1;
    bool spin = false;
    float yaw = 0.f;
    float tilt = 0.f;
  };
  // The hammer: raised, then brought down on the floor in front of the player, where it shatters
  // what stands within its reach into cells (a one-tick shatter splitter as it lands).
  struct Hammer {
    int ticksLeft = 0;     // of the blow; the shatter fires as it reaches 0
    glm::vec2 at{0.f};     // where it lands
    float yaw = 0.f;
  };
  struct PendingSpawn {
    uint64_t tick = 0;
    EnemyKind kind = EnemyKind::Gladiator;
    glm::vec2 position{0.f};
    float yaw = 0.f;
  };
  // Kills per enemy kind: [kind][0] in total, [kind][w] by weapon w (disc, sword, spin, hammer).
  static constexpr size_t kKindCount = size_t(EnemyKind::Count);
  static constexpr size_t kWeaponCount = 5;
  static constexpr const char* kWeaponNames[kWeaponCount] = {"", "disc", "sword", "spin", "hammer"};
  static constexpr const char* kWeaponSplitterNames[kWeaponCount] = {"", "energy disc", "sword swing", "spin attack",
                                                                     "hammer blow"};
  static uint8_t weaponIndex(const std::string& splitterName);
  // The figures of the match being played (HUD and state dump): a new match starts from zero.
  struct MatchStats {
    int score = 0;
    uint32_t enemiesKilled = 0;
    uint32_t killsByKind[kKindCount][kWeaponCount] = {};
    uint32_t propsBroken = 0;
    uint32_t discThrows = 0;
    uint32_t swordSwings = 0;
    uint32_t spinAttacks = 0;
    uint32_t hammerBlows = 0;
    uint32_t maxEnemiesHitInOneTick = 0;
    uint32_t maxKillsInOneTick = 0;
  };

  // Building.
  void buildLevel();
  void buildFloorAndWall();
  void buildGatesAndPillars();
  ecs::Entity addStatic(const std::string& name, geometry::MeshData mesh, std::vector<render::Material> materials,
                        bool collide);
  ecs::Entity spawnProp(PropKind kind, glm::vec3 position, float yaw);
  void spawnProps();
  void spawnMenuCubes();
  void createPlayer();
  ecs::Entity spawnDynamic(const std::string& name, geometry::MeshData mesh, std::vector<render::Material> materials,
                           const components::Splitable& splitable, glm::vec3 position, glm::quat rotation,
                           ArenaTag::Kind kind);

  // Systems.
  void gameplay(app::TickContext& c);
  void triggers(app::TickContext& c);
  void committed(app::TickContext& c, const std::vector<components::SplitEvent>& events);
  void physicsSync(app::TickContext& c);
  void animation(app::TickContext& c);
  void render(app::TickContext& c);

  // Gameplay parts.
  void updateCamera(float dt);
  void updateMenu(app::TickContext& c);
  void updatePlayer(app::TickContext& c);
  void updateWeapons(app::TickContext& c);
  void updateHammer(app::TickContext& c);
  void updateDisc(app::TickContext& c);
  void updateWaves(app::TickContext& c);
  void startWave(uint64_t tick);
  void enterIntermission(uint64_t tick, float seconds);
  void updateIntermission(app::TickContext& c);
  void enterDefeat(uint64_t tick);
  void updateDefeat(app::TickContext& c);
  void resetToMenu(uint64_t tick);
  void clearArena();
  void throwDisc();
  void swingSword(bool spin);
  ecs::Entity makeSplitter(const std::string& name, const physics::ShapeDef& shape, glm::vec3 position,
                           glm::quat rotation, bool persistent);
  void onSplit(const components::SplitEvent& ev, uint64_t tick);
  void adoptPieces(const components::SplitEvent& ev, uint64_t tick);
  void throwPiecesAway(const Enemy& enemy, const std::vector<ecs::Entity>& pieces);
  void updatePieces(uint64_t tick);
  void removeEntity(ecs::Entity e);

  // Camera and cursor.
  glm::vec2 cursorInFrame(const input::InputState& in, glm::ivec2 frame) const;
  glm::vec3 rayDirection(glm::vec2 framePixel, glm::ivec2 frame) const;
  bool cursorOnFloor(const input::InputState& in, glm::ivec2 frame, glm::vec3* point) const;
  // The splitable the cursor's ray hits first (null: none), for the inspector.
  ecs::Entity splitableUnderCursor(const input::InputState& in, glm::ivec2 frame) const;

  // The inspector (F1, --inspector; game/inspector): the window over the HUD.
  void toggleInspector(app::TickContext& c);
  void drawInspector(app::TickContext& c);

  // Drawing.
  void drawWeapons(render::Renderer& r);
  void drawHud(app::TickContext& c);
  void drawMatchPanel(render::Renderer& r, float u);
  void drawBudgetPanel(app::TickContext& c, float u);
  void drawBanners(app::TickContext& c, float u);
  void drawIntermission(render::Renderer& r, uint64_t tick, glm::vec2 frame, float u);
  void dumpEntity(ecs::Entity e, nlohmann::json& out);
  void dumpEnemy(const Enemy& enemy, nlohmann::json& out);
  void dumpFrame(nlohmann::json& line);
  nlohmann::json dumpMatch();
  components::SplitWorld splitWorld();
  EnemyContext enemyContext();

  app::App* app_ = nullptr;
  ArenaTuning tuning_;
  std::unique_ptr<components::Simulation> sim_;
  physics::PhysicsWorld* physics_ = nullptr;   // sim_'s
  components::SplitSystem* splits_ = nullptr;  // sim_'s
  ArenaMaterials materials_;
  EnemyMeshes enemyMeshes_;
  std::vector<Obstacle> pillars_;
  std::vector<physics::BodyId> staticBodies_;
  std::vector<physics::ShapeId> staticShapes_;
  uint64_t rng_ = 1;
  float nextRandom();

  // Match.
  MatchState state_ = MatchState::Menu;
  uint64_t stateTick_ = 0;  // tick the state was entered
  ecs::Entity startCube_, quitCube_;
  int health_ = 100;
  int wave_ = 0;
  uint64_t nextWaveTick_ = 0;    // Intermission: the tick the next wave begins
  uint64_t refillTick_ = 0;      // Intermission: the tick the health bar starts to fill up
  uint64_t waveBannerTick_ = 0;
  uint32_t matchesStarted_ = 0;  // Start cubes cut since the game began
  MatchStats match_;
  std::vector<Enemy> enemies_;
  std::vector<PendingSpawn> pendingSpawns_;

  // Player.
  ecs::Entity player_;
  glm::vec2 playerPosition_{0.f, 0.f};
  float playerYaw_ = 0.f;
  float playerSpeed_ = 0.f;
  glm::vec3 aimPoint_{0.f, 0.f, -3.f};
  float hurtFlash_ = 0.f;
  assets::ProceduralCharacter character_;
  render::MeshHandle characterMesh_;
  anim::Animator animator_;
  std::vector<glm::mat4> jointMatrices_;
  std::vector<glm::mat4> jointGlobals_;
  anim::Pose pose_;
  render::MeshHandle bladeMesh_, discMesh_, hammerMesh_;

  // Weapons.
  Disc disc_;
  Swing swing_;
  Hammer hammer_;
  uint64_t hammerReadyTick_ = 0;
  uint64_t swordReadyTick_ = 0;
  uint64_t spinReadyTick_ = 0;

  // Camera: blends from the menu view to the follow view.
  glm::vec3 cameraPosition_{0.f, 1.8f, 6.4f};
  glm::vec3 cameraTarget_{0.f, 0.9f, 1.6f};
  float cameraBlend_ = 0.f;

  // Figures of the whole run (every match) for the HUD and the state dump.
  uint64_t piecesSpawned_ = 0;
  uint64_t piecesRemoved_ = 0;
  uint32_t ragdollPiecesSpawned_ = 0;
  uint32_t ragdollPiecesRemoved_ = 0;
  uint32_t ragdollPiecesCut_ = 0;     // ragdoll pieces cut again (their pieces are counted as spawned)
  std::map<ecs::Entity, std::vector<physics::BodyId>> ragdollBones_;  // live ragdoll pieces' bone bodies
  uint32_t ragdollBodiesLeaked_ = 0;  // bone bodies still in the physics world after their piece went
  components::SplitLog splitLog_;
  components::SplitTickStats splitStats_;  // HUD, dump and inspector figures; the split-time graph
  inspector::Inspector inspector_;
  std::string inspectorNotice_;  // why F1 could not open it, shown until inspectorNoticeUntil_
  uint64_t inspectorNoticeUntil_ = 0;
};

}  // namespace cleave::arena
