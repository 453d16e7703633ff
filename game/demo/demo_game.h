// SPDX-License-Identifier: MIT
// The tech demo: the thesis's playable scene. A checker floor under a sky, objects to cut with a
// drag on screen, spawn keys, material cycling, pushes and a HUD with the split budget's figures.
#pragma once

#include <array>
#include <deque>
#include <memory>
#include <set>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "cleave/components/resource_hooks.h"
#include "cleave/components/scene_loader.h"
#include "cleave/components/skinned.h"
#include "cleave/components/split_log.h"
#include "cleave/components/split_stats.h"
#include "cleave/components/simulation.h"
#include "cleave/components/split_system.h"
#include "cleave/app/app.h"
#include "cleave/physics/physics_world.h"
#include "game/inspector/inspector.h"

namespace cleave::demo {

enum class ObjectKind : int {
  WoodenCube = 1,
  MetalSphere,
  MarbleCylinder,
  MelonEllipsoid,
  MultiPart,
  Skinned,
  Torus,
  StoneBlock,  // key 8: a dense block to shatter (F)
};

class DemoGame {
 public:
  DemoGame();
  ~DemoGame();

  // Builds the scene and registers the systems. The scene file's error when --scene cannot load.
  base::Status setup(app::App& app);

  // Spawns an object of the given kind at a position (used by keys 1-8 and by scenes).
  ecs::Entity spawn(ObjectKind kind, const glm::vec3& position, const glm::quat& rotation);
  // Spawns at the first free spot in front of the player (keys 1-8), standing on the floor.
  ecs::Entity spawnInFront(ObjectKind kind, const glm::vec3& forward);

  components::SplitSystem& splits() { return *splits_; }

  // Benchmarks (demo_bench.cpp), not timed tests. benchmarkSplits: spawns each object type
  // `repeats` times away from the scene, cuts it through its centre by a tilted plane with splitNow
  // (compute inline, pieces committed), and prints medians per type: main-thread ms (prepare +
  // commit), worker ms (compute), collider ms and the collider fit, as a Markdown table or JSON.
  void benchmarkSplits(int repeats, bool json);
  // benchmarkBurst: fifty cubes and a hundred generated characters (ragdoll pieces), each lot cut
  // in one tick; prints the ticks until the last piece is committed and the most main-thread
  // split time in any tick, as a table or JSON.
  void benchmarkBurst(bool json);
  // benchmarkSession (session_bench.cpp): `minutes` of blades sweeping a field of 225 objects (and
  // shatters, and fresh objects), then 30 s of nothing; prints per minute the pieces (live, awake,
  // frozen, debris), tick p50 / p99 / max with split and physics apart, resident memory, GPU meshes.
  void benchmarkSession(int minutes, bool json);
  physics::PhysicsWorld& physics() { return *physics_; }

  // What the physics world and the renderer hold now (physics 0 before setup).
  components::ResourceCounts resources() const;
  // Split jobs computed off the main thread so far (the proof a run on N split threads used them).
  uint64_t splitJobsOffMainThread() const { return sim_ ? sim_->splits().jobsComputedOffTheCallingThread() : 0; }
  // Destroys every entity (their hooks free what they hold). The demo holds nothing else, so the
  // counts are then those from before setup. For the --resource-report leak check, after the run.
  void releaseAll();

 private:
  void createMaterials();
  void createCharacterLooks();  // the character's asset, meshes and materials
  void createFloor();
  // Object 6: the generated character, walking a small circle, cut into ragdolls by default.
  ecs::Entity spawnCharacter(const glm::vec3& position, const glm::quat& rotation);
  // Object 5: the character's convex multi-part variant (a box per bone), playing the idle clip in
  // place, animated as one through the same skeleton; its pieces are baked into physics pieces.
  ecs::Entity spawnFigure(const glm::vec3& position, const glm::quat& rotation);
  void walkCharacters(double dt);
  // --scene FILE: the objects, splitters, budget and camera of a JSON scene (docs/scene-format.md).
  base::Status loadSceneFile(const std::string& path);
  void gameplay(app::TickContext& c);
  void render(app::TickContext& c);
  void drawHud(app::TickContext& c);
  void drawStatsPanel(app::TickContext& c, float scale);
  void drawHelp(app::TickContext& c, float scale);
  // F1 (and --inspector): the inspector window over the HUD (game/inspector).
  void drawInspector(app::TickContext& c);
  void toggleInspector(app::TickContext& c);
  uint32_t countPieces() const;
  // A HUD rectangle, and text (inside the last open box, or on its own), both recorded in hudLayout_.
  void hudBox(app::TickContext& c, const char* what, const glm::vec4& box, const glm::vec4& color);
  void hudText(app::TickContext& c, const std::string& text, glm::vec2 at, float scale, const glm::vec4& color);
  void dragCut(app::TickContext& c, glm::vec2 from, glm::vec2 to);
  glm::vec3 rayDirection(glm::vec2 pixel, glm::ivec2 frame) const;
  ecs::Entity entityUnderCrosshair(glm::vec3* hitPoint = nullptr);
  ecs::Entity splitableAlong(const glm::vec3& direction, glm::vec3* hitPoint = nullptr) const;
  components::SplitWorld splitWorld();
  void dumpExtension(ecs::Entity e, nlohmann::json& out);

  app::App* app_ = nullptr;
  std::unique_ptr<components::Simulation> sim_;
  physics::PhysicsWorld* physics_ = nullptr;     // sim_'s
  components::SplitSystem* splits_ = nullptr;    // sim_'s
  std::unique_ptr<components::SceneRunner> sceneRunner_;

  // Camera (fly camera: yaw around +Y, pitch up).
  glm::vec3 cameraPosition_{0.f, 2.2f, 7.5f};
  float yaw_ = 0.f;
  float pitch_ = -0.18f;
  bool splitMode_ = false;
  bool dragging_ = false;
  glm::vec2 dragStart_{0.f};
  glm::vec2 dragEnd_{0.f};
  bool showHelp_ = false;
  bool mouseFree_ = false;  // Escape freed the mouse: no mouse look until a click
  // The cursor shows (no mouse look): in split mode, after Escape, and while the inspector is open.
  bool cursorFree_ = false;
  inspector::Inspector inspector_;
  // A short message under the crosshair (a drag that crossed nothing, a push at nothing), shown
  // until noticeUntil_ (a tick) and written to the state dump.
  std::string notice_;
  uint64_t noticeUntil_ = 0;
  uint64_t tick_ = 0;
  void notify(const std::string& text);
  void shatterUnderCrosshair(app::TickContext& c);
  // gameplay, in steps.
  bool updateModes(app::TickContext& c);
  glm::vec3 updateCamera(app::TickContext& c);
  void objectKeys(app::TickContext& c, const glm::vec3& forward);
  void cycleLook(app::TickContext& c, int step);
  void pushUnderCrosshair(app::TickContext& c);
  void dragToCut(app::TickContext& c);
  bool lineCrossesSplitable(glm::vec2 from, glm::vec2 to, glm::ivec2 frame) const;

  // Materials: seven looks the player cycles with Q/E, and the matching cap materials.
  std::array<render::Material, 7> looks_{};
  std::array<std::string, 7> lookNames_{};
  std::array<render::Material, 7> capLooks_{};
  render::Material floorMaterial_;
  // The generated character (object 6): shared skeleton and clips, mesh, and its materials by id.
  std::shared_ptr<const components::SkinnedAsset> characterAsset_;
  std::shared_ptr<const geometry::MeshData> characterMesh_;
  std::shared_ptr<const geometry::MeshData> figureMesh_;
  // The generated mesh of each other kind (by ObjectKind), made at its first spawn and shared after.
  std::array<std::shared_ptr<const geometry::MeshData>, 9> kindMeshes_{};
  std::vector<render::Material> characterMaterials_;
  std::vector<render::TextureHandle> textures_;

  // Every split of the run, for the state dump (replay tests check mass conservation per cut).
  components::SplitLog splitLog_;
  std::set<std::string> looksShown_;  // looks Q/E switched an object to (for the state dump)

  // The split figures of the HUD, the dump and the inspector (history: the split-time graph).
  components::SplitTickStats splitStats_;
  // The last frame's HUD layout (pixels): each box and the extent of the text drawn in it.
  struct HudItem {
    std::string what;
    glm::vec4 box;
    glm::vec4 content;
    bool open = true;  // text drawn next goes into this box
  };
  std::vector<HudItem> hudLayout_;
};

}  // namespace cleave::demo
