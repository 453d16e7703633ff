// SPDX-License-Identifier: MIT
#include "cleave/app/app.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>

#include <glm/gtc/quaternion.hpp>
#include <nlohmann/json.hpp>

#include "cleave/ecs/hierarchy.h"
#include "cleave/log/log.h"

namespace cleave::app {

namespace {

double nowMs() {
  using namespace std::chrono;
  return duration<double, std::milli>(steady_clock::now().time_since_epoch()).count();
}

void fnv(uint64_t& h, const void* data, size_t size) {
  const auto* p = static_cast<const uint8_t*>(data);
  for (size_t i = 0; i < size; ++i) {
    h ^= p[i];
    h *= 1099511628211ull;
  }
}

}  // namespace

App::App() = default;
App::~App() {
  // GPU resources go before the context that owns them.
  ui_.reset();
  renderer_.reset();
  platform_.reset();
}

base::Status App::init(const AppOptions& options, const std::string& title) {
  auto ioError = [](std::string reason) {
    return base::Status::failure(base::StatusCode::IoError, std::move(reason));
  };
  options_ = options;
  if (!options_.replayPath.empty()) {
    auto loaded = input::loadReplay(options_.replayPath);
    if (!loaded.ok()) return loaded;
    replay_ = std::make_unique<input::ReplaySource>(std::move(loaded.replay));
  }
  if (!options_.recordPath.empty()) {
    // Fail now, not after a long session, when the file cannot be written.
    std::ofstream probe(options_.recordPath, std::ios::app);
    if (!probe) return ioError(options_.recordPath + ": cannot open the replay file for writing");
    // A recording of a replayed run names the same scene and seed as the replay.
    std::string scene = options_.sceneName;
    uint64_t seed = options_.seed;
    if (replay_) {
      scene = replay_->replay().scene;
      seed = replay_->replay().seed;
    }
    recorder_ = std::make_unique<input::ReplayRecorder>(scene, seed);
  }
  if (!options_.headless) {
    auto window = createWindowPlatform(options_.width, options_.height, title);
    if (window.ok()) {
      platform_ = std::move(window).value();
    } else {
      log::warning("cleave", "no window (%s); running headless", window.message().c_str());
      options_.headless = true;
    }
  }
  if (!platform_) {
    auto headless = createHeadlessPlatform(options_.width, options_.height);
    if (!headless.ok()) return base::Status::failure(headless.code(), "no OpenGL context: " + headless.message());
    platform_ = std::move(headless).value();
  }
  renderer_ = std::make_unique<render::Renderer>();
  if (const base::Status started = renderer_->init(); !started.ok())
    return base::Status::failure(started.code, "renderer: " + started.message);
  applyRenderScale();
  if (!options_.dumpStatePath.empty()) {
    dumpFile_ = std::make_unique<std::ofstream>(options_.dumpStatePath);
    if (!*dumpFile_) return ioError(options_.dumpStatePath + ": cannot open the state dump for writing");
  }
  if (!options_.screenshotDir.empty()) {
    std::error_code ec;
    std::filesystem::create_directories(options_.screenshotDir, ec);
    if (ec) {
      return ioError(options_.screenshotDir + ": cannot create the screenshot directory (" + ec.message() +
                     ")");
    }
  }
  return {};
}

// An explicit --render-scale is used as given. Auto: a window on a software rasteriser draws the
// scene at a dynamic scale (render/dynamic_scale.h: real time needs it there); headless runs and
// GPUs draw at 1, so screenshots and golden images keep their full detail. A window composes its frames straight
// into the window's framebuffer (no extra copy); on a software rasteriser it does not wait for a
// refresh that no display paces (the fixed ticks pace the loop).
void App::applyRenderScale() {
  const std::string device = renderer_->deviceName();
  const bool software = render::Renderer::isSoftwareRasterizer(device);
  if (!platform_->headless()) {
    renderer_->setDrawIntoWindow(true);
    if (software) platform_->setVsync(false);
  }
  float scale = options_.renderScale;
  if (scale <= 0.f && !platform_->headless() && software) {
    dynamicScale_.emplace();
    scale = dynamicScale_->scale();
    log::info("cleave", "%s is a software rasteriser: the scene is drawn at 0.35 to 0.6 x the window as the "
              "frame time allows (--render-scale 1 for full resolution)", device.c_str());
  } else if (scale <= 0.f) {
    scale = 1.f;
  }
  renderer_->setRenderScale(scale);
}

void App::addSystem(Phase phase, std::string name, System system) {
  systems_[size_t(phase)].emplace_back(std::move(name), std::move(system));
}

void App::setUi(std::function<void(TickContext&)> build) { uiBuild_ = std::move(build); }

base::Status App::setUiOpen(bool open) {
  if (!open) {
    uiOpen_ = false;
    return {};
  }
  if (!ui_) {
    auto ui = std::make_unique<UiLayer>();
    if (base::Status started = ui->start(*platform_, platform_->frameSize()); !started.ok()) return started;
    ui_ = std::move(ui);
  }
  if (!uiOpen_) ui_->ignoreHeldButtons();  // the press of a drag in the game is no click on it
  uiOpen_ = true;
  return {};
}

// Presses and scrolls over the UI, and keys typed into it, stay with it. Releases and moves always
// reach the game, so that a drag begun in the game ends there.
bool App::uiTakes(const input::InputEvent& event) const {
  if (!uiOpen_ || !ui_) return false;
  if (std::holds_alternative<input::MouseDown>(event) || std::holds_alternative<input::Scroll>(event))
    return ui_->wantsMouse();
  if (const auto* key = std::get_if<input::KeyDown>(&event)) {
    const bool functionKey = int(key->key) >= int(input::Key::F1) && int(key->key) <= int(input::Key::F12);
    return !functionKey && ui_->wantsKeyboard();
  }
  return false;
}

void App::setStateDumpExtension(StateDumpExtension extension) {
  dumpExtension_ = std::move(extension);
}

void App::setFrameDumpExtension(FrameDumpExtension extension) {
  frameDumpExtension_ = std::move(extension);
}

int64_t App::totalTicks() const {
  if (options_.ticks >= 0) return options_.ticks;
  if (replay_) return int64_t(replay_->length());
  return -1;
}

bool App::runTick(bool render) {
  const double tickStart = nowMs();
  // Input: the replay's events for this tick, or what the window delivered since the last tick.
  input::InputFrame frame;
  frame.tick = tick_;
  if (replay_) {
    replay_->next(tick_, frame);
  } else {
    liveQueue_.next(tick_, frame);
  }
  if (recorder_) recorder_->record(frame);
  inputState_.begin(frame);

  TickContext context{*this, tick_, kTickSeconds, world_, inputState_, *renderer_, *platform_,
                      platform_->frameSize(), render};
  for (size_t p = 0; p < size_t(Phase::Count); ++p) {
    const double start = nowMs();
    if (Phase(p) == Phase::Render) {
      if (render) renderFrame(context);
    } else {
      for (auto& [name, system] : systems_[p]) system(context);
    }
    phaseMs_[p] = nowMs() - start;
  }
  lastTickMs_ = nowMs() - tickStart;
  countTickRate();

  const int64_t total = totalTicks();
  const bool last = total >= 0 && int64_t(tick_) + 1 >= total;
  // The state is dumped every dumpEvery ticks, and at the end: the last tick, or a quit.
  if (dumpFile_ && ((options_.dumpEvery > 0 && tick_ % uint64_t(options_.dumpEvery) == 0) || last || quit_))
    dumpState();
  ++tick_;
  return !last;
}

void App::countTickRate() {
  const double now = nowMs();
  if (tpsWindowStart_ < 0.0) tpsWindowStart_ = now;
  ++tpsTicks_;
  // Until the first half second is full, the rate so far (a short headless run shows one too).
  if (tps_ == 0.0 && now > tpsWindowStart_) tpsProvisional_ = double(tpsTicks_) * 1000.0 / (now - tpsWindowStart_);
  if (now - tpsWindowStart_ >= 500.0) {
    tps_ = double(tpsTicks_) * 1000.0 / (now - tpsWindowStart_);
    tpsTicks_ = 0;
    tpsWindowStart_ = now;
  }
}

void App::renderFrame(TickContext& context) {
  const glm::ivec2 size = platform_->frameSize();
  context.frameSize = size;
  for (auto& [name, system] : systems_[size_t(Phase::Render)]) system(context);
  renderer_->endFrame();
  if (uiOpen_ && ui_ && uiBuild_) {
    // Headless, the clock is the fixed ticks: the same picture on every run.
    const double seconds = platform_->headless() ? double(tick_) * kTickSeconds : platform_->timeSeconds();
    ui_->frame(*renderer_, size, seconds, [&] { uiBuild_(context); });
  }
  framePending_ = true;
}

base::Status App::writeScreenshot(const std::string& path) {
  std::vector<uint8_t> pixels;
  int w = 0, h = 0;
  renderer_->readPixels(pixels, w, h);
  base::Status written = render::writePng(path, w, h, pixels);
  if (written.ok()) screenshots_.push_back(path);
  return written;
}

// Fixed ticks at kTickSeconds, as many per frame as the wall clock needs (so a slow frame does not
// slow the game down), up to kMaxCatchUpTicks: only a real stall (a quarter second without a frame)
// drops time. One frame is rendered per loop, on its last tick.
void App::runWindowLoop() {
  constexpr int kMaxCatchUpTicks = 15;
  double accumulator = 0.0;
  double previous = platform_->timeSeconds();
  double fpsWindowStart = previous;
  int fpsFrames = 0;
  double lastPresent = -1.0;
  while (!quit_ && !platform_->closeRequested()) {
    platform_->pollEvents([this](const input::InputEvent& e) {
      if (!uiTakes(e)) liveQueue_.push(e);
    });
    const double now = platform_->timeSeconds();
    const double workStart = now;
    accumulator += std::min(now - previous, kMaxCatchUpTicks * kTickSeconds);
    previous = now;
    const int due = int(accumulator / kTickSeconds);
    const int steps = std::min(due, kMaxCatchUpTicks);
    for (int s = 0; s < steps && !quit_; ++s) {
      accumulator -= kTickSeconds;
      if (!runTick(s + 1 == steps)) quit_ = true;
    }
    if (due > kMaxCatchUpTicks) accumulator = std::fmod(accumulator, kTickSeconds);
    if (framePending_) {
      render::Renderer* r = renderer_.get();
      platform_->present([r](int w, int h) { r->presentToDefaultFramebuffer(w, h); });
      framePending_ = false;
      ++fpsFrames;
      const double presented = platform_->timeSeconds();
      if (lastPresent >= 0.0) frameMs_.push_back((presented - lastPresent) * 1000.0);
      lastPresent = presented;
      if (dynamicScale_ && dynamicScale_->addFrame((presented - workStart) * 1000.0))
        renderer_->setRenderScale(dynamicScale_->scale());
    }
    if (now - fpsWindowStart >= 0.5) {
      fps_ = fpsFrames / (now - fpsWindowStart);
      fpsFrames = 0;
      fpsWindowStart = now;
    }
  }
}

int App::run() {
  const int64_t total = totalTicks();
  if (platform_->headless()) {
    if (total < 0) {
      log::error("cleave", "headless runs need --ticks N or --replay FILE");
      return 2;
    }
    // Screenshots: every N ticks when asked, otherwise four spread over the run plus the last tick.
    int64_t every = options_.screenshotEvery;
    if (every <= 0) every = std::max<int64_t>(1, total / 4);
    while (!quit_ && int64_t(tick_) < total) {
      const uint64_t t = tick_;
      const bool shoot = !options_.screenshotDir.empty() &&
                         ((t > 0 && int64_t(t) % every == 0) || int64_t(t) + 1 == total);
      runTick(shoot);
      if (shoot) {
        char name[64];
        std::snprintf(name, sizeof(name), "frame_%06llu.png", static_cast<unsigned long long>(t));
        const std::string path = (std::filesystem::path(options_.screenshotDir) / name).string();
        if (const base::Status written = writeScreenshot(path); !written.ok()) {
          log::error("cleave", "%s", written.message.c_str());
          return 1;
        }
      }
    }
  } else {
    runWindowLoop();
  }
  if (recorder_) {
    const input::ReplaySaveResult saved = input::saveReplay(options_.recordPath, recorder_->replay());
    if (!saved.ok()) {
      log::error("cleave", "%s", saved.message.c_str());
      return 1;
    }
    log::info("", "replay: %s", options_.recordPath.c_str());
  }
  for (const auto& path : screenshots_) log::info("", "screenshot: %s", path.c_str());
  if (!frameMs_.empty()) {
    // Frame times of the window run (present to present), for performance reports.
    std::vector<double> sorted = frameMs_;
    std::sort(sorted.begin(), sorted.end());
    double sum = 0.0;
    for (double ms : sorted) sum += ms;
    const size_t p95 = std::min(sorted.size() - 1, size_t(double(sorted.size()) * 0.95));
    log::info("", "frames: %zu  mean %.2f ms  median %.2f ms  p95 %.2f ms  max %.2f ms  render scale %.2f",
                sorted.size(), sum / double(sorted.size()), sorted[sorted.size() / 2], sorted[p95], sorted.back(),
                double(renderer_->renderScale()));
  }
  if (options_.printStateHash)
    log::info("", "state-hash: %016llx", static_cast<unsigned long long>(stateHash()));
  std::fflush(stdout);
  return 0;
}

uint64_t App::stateHash() const {
  uint64_t h = 1469598103934665603ull;
  for (ecs::Entity e : world_.entities()) {
    const auto* t = world_.tryGet<ecs::Transform>(e);
    if (!t) continue;
    fnv(h, &e.index, sizeof(e.index));
    fnv(h, &e.generation, sizeof(e.generation));
    fnv(h, &t->position, sizeof(t->position));
    fnv(h, &t->rotation, sizeof(t->rotation));
  }
  return h;
}

void App::dumpState() {
  nlohmann::json line;
  line["tick"] = tick_;
  nlohmann::json entities = nlohmann::json::array();
  for (ecs::Entity e : world_.entities()) {
    const auto* t = world_.tryGet<ecs::Transform>(e);
    if (!t) continue;
    nlohmann::json item;
    item["id"] = (uint64_t(e.generation) << 32) | e.index;
    if (const auto* name = world_.tryGet<ecs::Name>(e)) item["name"] = name->value;
    item["position"] = {t->position.x, t->position.y, t->position.z};
    item["rotation"] = {t->rotation.w, t->rotation.x, t->rotation.y, t->rotation.z};
    if (dumpExtension_) dumpExtension_(e, item);
    entities.push_back(std::move(item));
  }
  line["entities"] = std::move(entities);
  line["state_hash"] = stateHash();
  if (frameDumpExtension_) frameDumpExtension_(line);
  *dumpFile_ << line.dump() << '\n';
  dumpFile_->flush();
}

}  // namespace cleave::app
