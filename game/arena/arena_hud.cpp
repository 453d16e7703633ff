// SPDX-License-Identifier: MIT
// The arena's HUD, laid out for 720 lines and scaled to the frame: the match panel (top left), the
// split budget panel (top right, wall-clock figures), the banners of the match (wave, get ready,
// wave cleared and the refill, defeat), the controls (F1, the inspector, on the menu) and the
// crosshair.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "game/arena/arena_game.h"

namespace cleave::arena {

namespace {

const glm::vec4 kWhite(1.f), kShade(0.f, 0.f, 0.f, 0.5f), kGold(1.f, 0.82f, 0.35f, 1.f);

// `text` centred horizontally on the frame, its top at `y`.
void centredText(render::Renderer& r, const std::string& text, float frameWidth, float y, float scale,
                 const glm::vec4& color) {
  r.submitText(text, {frameWidth * 0.5f - render::Renderer::textWidth(text, scale) * 0.5f, y}, scale, color);
}

}  // namespace

void ArenaGame::drawHud(app::TickContext& c) {
  render::Renderer& r = c.renderer;
  const float u = float(c.frameSize.y) / 720.f;  // HUD scale: laid out for 720 lines
  const float W = float(c.frameSize.x);
  if (state_ == MatchState::Menu || state_ == MatchState::Quitting) {
    centredText(r, "CLEAVE ARENA", W, 40.f * u, 5.f * u, kGold);
    centredText(r, "click a cube to cut it", W, 100.f * u, 2.4f * u, kWhite);
    centredText(r, "F1: inspector (split settings, budget, log)", W, float(c.frameSize.y) - 40.f * u, 1.8f * u,
                glm::vec4(1.f, 1.f, 1.f, 0.85f));
  } else {
    drawMatchPanel(r, u);
  }
  drawBudgetPanel(c, u);
  drawBanners(c, u);
  // F1 could not open the inspector: why, for two seconds.
  if (c.tick < inspectorNoticeUntil_)
    centredText(r, inspectorNotice_, W, float(c.frameSize.y) * 0.85f, 1.8f * u, kGold);
}

void ArenaGame::drawMatchPanel(render::Renderer& r, float u) {
  // Top left: the match (deterministic figures only).
  char line[160];
  const float full = float(std::max(tuning_.player.health, 1));
  r.submitOverlayRect(glm::vec4(10 * u, 10 * u, 300 * u, 112 * u), kShade);
  r.submitText("HEALTH", {20 * u, 20 * u}, 2.f * u, kWhite);
  r.submitOverlayRect(glm::vec4(110 * u, 20 * u, 185 * u, 16 * u), glm::vec4(0.2f, 0.05f, 0.05f, 0.9f));
  r.submitOverlayRect(glm::vec4(110 * u, 20 * u, 185 * u * std::clamp(float(health_) / full, 0.f, 1.f), 16 * u),
                      glm::vec4(0.85f, 0.12f, 0.1f, 1.f));
  std::snprintf(line, sizeof(line), "SCORE %d", match_.score);
  r.submitText(line, {20 * u, 48 * u}, 2.6f * u, kGold);
  std::snprintf(line, sizeof(line), "WAVE %d   ENEMIES %zu", wave_, enemies_.size() + pendingSpawns_.size());
  r.submitText(line, {20 * u, 80 * u}, 2.f * u, kWhite);
  // Pieces on the sand now: simulated (of which awake) and fading; the match's figures after them.
  const components::PieceBudgetStats& pieces = splits_->pieces().stats();
  std::snprintf(line, sizeof(line), "pieces %u (%u awake)  kills %u  skinned %u", pieces.live + pieces.frozen,
                pieces.awake, match_.enemiesKilled, match_.killsByKind[size_t(EnemyKind::Skinned)][0]);
  r.submitText(line, {20 * u, 102 * u}, 1.5f * u, kWhite);
}

void ArenaGame::drawBudgetPanel(app::TickContext& c, float u) {
  // Top right: the split budget and frame figures (wall-clock, masked in golden frames).
  render::Renderer& r = c.renderer;
  char line[160];
  const auto& stats = splits_->budget().stats();
  const float bx = float(c.frameSize.x) - 290 * u;
  r.submitOverlayRect(glm::vec4(bx, 10 * u, 280 * u, 100 * u), kShade);
  // Headless runs draw no frames to count: the tick rate instead.
  const bool headless = c.app.headless();
  std::snprintf(line, sizeof(line), "%s %.0f  tick %.1f ms", headless ? "TPS" : "FPS",
                headless ? c.app.ticksPerSecond() : c.app.framesPerSecond(), c.app.lastTickMilliseconds());
  r.submitText(line, {bx + 10 * u, 18 * u}, 1.7f * u, kWhite);
  std::snprintf(line, sizeof(line), "split queue %u  this tick %u", stats.queueLength, splitStats_.splitsThisTick);
  r.submitText(line, {bx + 10 * u, 36 * u}, 1.7f * u, kWhite);
  // The main thread's own split work against the budget, and what it waited for the workers (their
  // own time is in the inspector).
  std::snprintf(line, sizeof(line), "split ms %.2f / %.1f  wait %.1f", splitStats_.times.work,
                splits_->budget().settings().millisecondsPerTick, splitStats_.times.wait);
  r.submitText(line, {bx + 10 * u, 54 * u}, 1.7f * u, kWhite);
  components::drawSplitGraph(r, splitStats_.history, splits_->budget().settings().millisecondsPerTick,
                             glm::vec4(bx + 10 * u, 74 * u, 260 * u, 28 * u));
}

void ArenaGame::drawBanners(app::TickContext& c, float u) {
  render::Renderer& r = c.renderer;
  const float W = float(c.frameSize.x), H = float(c.frameSize.y);
  if (state_ == MatchState::Playing && c.tick < waveBannerTick_ + 120 && wave_ > 0)
    centredText(r, "WAVE " + std::to_string(wave_), W, H * 0.28f, 5.f * u, kGold);
  if (state_ == MatchState::Intermission) drawIntermission(r, c.tick, glm::vec2(W, H), u);
  if (state_ == MatchState::Defeated) {
    // Low on the screen: the player and the cheering enemies are in the middle.
    const float y = H * 0.72f;
    r.submitOverlayRect(glm::vec4(0, y, W, 90 * u), glm::vec4(0.f, 0.f, 0.f, 0.6f));
    centredText(r, "DEFEATED", W, y + 12 * u, 5.f * u, glm::vec4(1.f, 0.3f, 0.2f, 1.f));
    centredText(r, "your foes cheer   press Enter for the menu", W, y + 62 * u, 2.f * u, kWhite);
  }
  if (state_ != MatchState::Playing && state_ != MatchState::Intermission) return;
  r.submitText("WASD move   mouse aim   left: sword   right: disc   space: spin   E: hammer", {20 * u, H - 30 * u}, 1.8f * u,
               glm::vec4(1.f, 1.f, 1.f, 0.85f));
  const glm::vec2 m = cursorInFrame(c.input, c.frameSize);
  const float k = 9.f * u;
  const glm::vec2 cross[8] = {m + glm::vec2(-k, 0), m + glm::vec2(-k * 0.35f, 0), m + glm::vec2(k, 0),
                              m + glm::vec2(k * 0.35f, 0), m + glm::vec2(0, -k), m + glm::vec2(0, -k * 0.35f),
                              m + glm::vec2(0, k), m + glm::vec2(0, k * 0.35f)};
  r.submitOverlayLines(cross, glm::vec4(0.6f, 1.f, 1.f, 1.f));
}

void ArenaGame::drawIntermission(render::Renderer& r, uint64_t tick, glm::vec2 frame, float u) {
  // Before wave 1: GET READY and a countdown. After a wave: WAVE n CLEARED, then the refill, then
  // the countdown to the next wave.
  const uint64_t ticksLeft = nextWaveTick_ > tick ? nextWaveTick_ - tick : 0;
  const int secondsLeft = int((ticksLeft + 59) / 60);
  const float y = frame.y * 0.28f;
  r.submitOverlayRect(glm::vec4(0, y - 12 * u, frame.x, 112 * u), glm::vec4(0.f, 0.f, 0.f, 0.35f));
  const std::string title = wave_ == 0 ? "GET READY" : "WAVE " + std::to_string(wave_) + " CLEARED";
  centredText(r, title, frame.x, y, 5.f * u, kGold);
  std::string detail;
  if (wave_ > 0 && tick >= refillTick_)
    detail = health_ < tuning_.player.health ? "health restoring...   " : "HEALTH RESTORED   ";
  detail += "wave " + std::to_string(wave_ + 1) + " in " + std::to_string(secondsLeft);
  centredText(r, detail, frame.x, y + 56 * u, 2.4f * u, kWhite);
}

}  // namespace cleave::arena
