// SPDX-License-Identifier: MIT
#include "game/inspector/inspector.h"

#include <algorithm>
#include <cstdio>

#include <nlohmann/json.hpp>

#include "cleave/components/split_stats.h"

#if CLEAVE_HAVE_IMGUI
#include <imgui.h>
#endif

namespace cleave::inspector {

std::string Inspector::toggle(app::App& app) {
  if (open_) {
    close(app);
    return {};
  }
  return open(app).message;
}

base::Status Inspector::open(app::App& app) {
  base::Status opened = app.setUiOpen(true);
  if (opened.ok()) open_ = true;
  return opened;
}

void Inspector::close(app::App& app) {
  app.setUiOpen(false);
  open_ = false;
  clockRects_.clear();
  window_ = glm::vec4(0.f);
}

void Inspector::writeJson(nlohmann::json& out) const {
  nlohmann::json clock = nlohmann::json::array();
  for (const glm::vec4& r : clockRects_) clock.push_back({r.x, r.y, r.z, r.w});
  nlohmann::json settings;  // null without a target
  if (open_ && targetTuning_) {
    const components::SplitableTuning& t = *targetTuning_;
    settings = {{"cap_uv_mode", int(t.capUvMode)}, {"cap_uv_per_metre", t.capUvPerMetre},
                {"collider", int(t.collider)},     {"density", t.density},
                {"split_impulse", t.splitImpulse}, {"islands", t.separateIslands ? int(t.islands) + 1 : 0},
                {"hollow", t.hollow}};
  }
  out = {{"open", open_},
         {"target", open_ ? targetName_ : std::string()},
         {"settings", std::move(settings)},
         {"window", {window_.x, window_.y, window_.z, window_.w}},
         {"clock", std::move(clock)}};
}

#if CLEAVE_HAVE_IMGUI

namespace {

const ImVec4 kDim(0.65f, 0.68f, 0.72f, 1.f), kWarn(1.f, 0.45f, 0.35f, 1.f);

template <typename T>
bool slider(const char* label, ImGuiDataType type, T& value, T lo, T hi, const char* format, bool log = false) {
  return ImGui::SliderScalar(label, type, &value, &lo, &hi, format,
                             log ? ImGuiSliderFlags_Logarithmic : ImGuiSliderFlags_None);
}

// Islands as one choice: each side whole, parts that touch together, or every connected part.
int islandChoice(const components::SplitableTuning& t) {
  if (!t.separateIslands) return 0;
  return t.islands == geometry::IslandMode::Touching ? 1 : 2;
}

void setIslandChoice(components::SplitableTuning& t, int choice) {
  t.separateIslands = choice != 0;
  if (choice != 0) t.islands = choice == 1 ? geometry::IslandMode::Touching : geometry::IslandMode::Connected;
}

}  // namespace

void Inspector::markClock() {
  const ImVec2 lo = ImGui::GetItemRectMin(), hi = ImGui::GetItemRectMax();
  clockRects_.push_back(glm::vec4(lo.x, lo.y, hi.x - lo.x, hi.y - lo.y));
}

void Inspector::draw(app::TickContext& c, const InspectorFeed& feed) {
  if (!open_) return;
  clockRects_.clear();
  const ImVec2 display = ImGui::GetIO().DisplaySize;
  const float width = std::min(display.x * 0.45f, 34.f * ImGui::GetFontSize());
  ImGui::SetNextWindowPos(ImVec2(display.x - width - 8.f, 8.f), ImGuiCond_FirstUseEver);
  ImGui::SetNextWindowSize(ImVec2(width, display.y - 16.f), ImGuiCond_FirstUseEver);
  ImGui::SetNextWindowBgAlpha(0.82f);
  bool keepOpen = true;
  if (ImGui::Begin("Inspector (F1)", &keepOpen, ImGuiWindowFlags_NoCollapse)) {
    // Widgets on the left, their labels on the right: 15 characters, or half a narrow window.
    ImGui::PushItemWidth(-std::min(15.f * ImGui::GetFontSize(), 0.5f * ImGui::GetContentRegionAvail().x));
    drawTarget(feed);
    drawBudget(feed);
    drawPieceBudget(feed);
    drawTiming(c, feed);
    drawLog(feed);
    ImGui::PopItemWidth();
  }
  const ImVec2 at = ImGui::GetWindowPos(), size = ImGui::GetWindowSize();
  window_ = glm::vec4(at.x, at.y, size.x, size.y);
  ImGui::End();
  if (!keepOpen) close(c.app);  // its close button
}

void Inspector::drawTarget(const InspectorFeed& feed) {
  targetTuning_.reset();
  if (!ImGui::CollapsingHeader("Object under the crosshair", ImGuiTreeNodeFlags_DefaultOpen)) return;
  const components::Splitable* sp =
      feed.world.alive(feed.target) ? feed.world.tryGet<components::Splitable>(feed.target) : nullptr;
  const auto* name = sp ? feed.world.tryGet<ecs::Name>(feed.target) : nullptr;
  targetName_ = sp ? (name ? name->value : std::string("(unnamed)")) : std::string();
  if (!sp) {
    ImGui::TextColored(kDim, "nothing splitable under the crosshair");
    return;
  }
  ImGui::Text("%s   (entity %u)", targetName_.c_str(), feed.target.index);
  components::SplitableTuning t = components::tuningOf(*sp);
  bool changed = false;
  static const char* uvModes[] = {"world planar", "normalised to the cap"};
  static const char* colliders[] = {"auto (carried parts)", "convex hull", "compound", "concave mesh"};
  static const char* islands[] = {"one piece per side", "touching parts together", "every connected part"};
  int uv = int(t.capUvMode), collider = int(t.collider), island = islandChoice(t);
  if (ImGui::Combo("cap UV mode", &uv, uvModes, 2)) t.capUvMode = geometry::CapUvMode(uv), changed = true;
  changed |= slider("cap UV per metre", ImGuiDataType_Double, t.capUvPerMetre, 0.05, components::kMaxCapUvPerMetre,
                    "%.2f", true);
  if (ImGui::Combo("collider", &collider, colliders, 4))
    t.collider = components::ColliderMode(collider), changed = true;
  changed |= slider("density kg/m^3", ImGuiDataType_Double, t.density, components::kMinDensity,
                    components::kMaxDensity, "%.0f", true);
  changed |= slider("split impulse m/s", ImGuiDataType_Double, t.splitImpulse, 0.0, 10.0, "%.2f");
  if (ImGui::Combo("islands", &island, islands, 3)) setIslandChoice(t, island), changed = true;
  changed |= ImGui::Checkbox("hollow (no caps)", &t.hollow);
  if (changed) {
    const components::TuningResult r = components::applySplitableTuning(feed.world, feed.target, t);
    lastError_ = r.ok() ? std::string() : r.message;
  }
  targetTuning_ = components::tuningOf(*sp);
  ImGui::TextColored(kDim, "changes apply to the next split of this object");
  if (!lastError_.empty()) ImGui::TextColored(kWarn, "%s", lastError_.c_str());
}

void Inspector::drawBudget(const InspectorFeed& feed) {
  if (!ImGui::CollapsingHeader("Split budget", ImGuiTreeNodeFlags_DefaultOpen)) return;
  components::SplitBudget& budget = feed.splits.budget();
  components::SplitBudgetSettings s = budget.settings();
  bool changed = false;
  changed |= slider("main ms per tick", ImGuiDataType_Double, s.millisecondsPerTick, 0.05, 16.0, "%.2f", true);
  changed |= slider("worker ms per tick", ImGuiDataType_Double, s.workerMillisecondsPerTick, 0.05, 32.0, "%.2f", true);
  changed |= slider("splits per tick", ImGuiDataType_U32, s.maxSplitsPerTick, 1u, 64u, "%u");
  changed |= slider("activations per tick", ImGuiDataType_U32, s.maxActivationsPerTick, 1u, 128u, "%u");
  changed |= slider("commit delay ticks", ImGuiDataType_U32, s.commitDelayTicks, 0u, 8u, "%u");
  changed |= ImGui::Checkbox("deterministic (charge estimates)", &s.deterministic);
  if (changed) {
    const components::TuningResult r = components::applyBudgetTuning(budget, s);
    lastError_ = r.ok() ? std::string() : r.message;
  }
  const components::SplitBudgetStats& st = budget.stats();
  ImGui::Text("queue %u   deferred %u   done %llu in all", st.queueLength, st.deferred,
              static_cast<unsigned long long>(st.totalExecuted));
}

// The piece budget: its limits and policy edited live (applied at the next tick), and what it holds.
void Inspector::drawPieceBudget(const InspectorFeed& feed) {
  if (!ImGui::CollapsingHeader("Piece budget")) return;  // closed at first: the split log stays in view
  components::PieceBudget& pieces = feed.splits.pieces();
  components::PieceBudgetSettings s = pieces.settings();
  bool changed = ImGui::Checkbox("retire pieces", &s.enabled);
  changed |= slider("max live", ImGuiDataType_U32, s.maxLivePieces, 8u, 2000u, "%u");
  changed |= slider("max awake", ImGuiDataType_U32, s.maxAwakePieces, 8u, 1000u, "%u");
  changed |= slider("max frozen", ImGuiDataType_U32, s.maxFrozenPieces, 0u, 5000u, "%u");
  changed |= slider("max debris", ImGuiDataType_U32, s.maxDebris, 0u, 1000u, "%u");
  int policy = int(s.policy) - 1;
  changed |= ImGui::Combo("retire by", &policy, "freeze\0fade\0remove\0");
  s.policy = components::PieceRetirement(policy + 1);
  changed |= slider("smallest body m^3", ImGuiDataType_Double, s.minBodyVolume, 0.0, 1e-3, "%.1e", false);
  if (changed) pieces.setSettings(s);
  const components::PieceBudgetStats& st = pieces.stats();
  ImGui::Text("live %u   awake %u   frozen %u   debris %u", st.live, st.awake, st.frozen, st.debris);
  ImGui::Text("retired: %llu frozen, %llu faded, %llu removed; %llu thawed",
              static_cast<unsigned long long>(st.frozenTotal), static_cast<unsigned long long>(st.fadedTotal),
              static_cast<unsigned long long>(st.removedTotal), static_cast<unsigned long long>(st.thawedTotal));
}

void Inspector::drawTiming(app::TickContext& c, const InspectorFeed& feed) {
  if (!ImGui::CollapsingHeader("Frame and split times", ImGuiTreeNodeFlags_DefaultOpen)) return;
  const components::PieceBudgetStats& kept = feed.splits.pieces().stats();
  ImGui::Text("pieces %u (awake %u, frozen %u)   tick %llu", feed.pieces, kept.awake, kept.frozen,
              static_cast<unsigned long long>(c.tick));
  const auto& phase = c.app.phaseMilliseconds();
  ImGui::BeginGroup();
  if (c.app.headless()) {
    ImGui::Text("ticks per second %7.0f (headless)", c.app.ticksPerSecond());
  } else {
    const double fps = c.app.framesPerSecond();
    ImGui::Text("frame %7.2f ms   %5.0f FPS", fps > 0.0 ? 1000.0 / fps : 0.0, fps);
  }
  ImGui::Text("tick  %7.2f ms   physics %6.2f ms", c.app.lastTickMilliseconds(),
              phase[size_t(app::Phase::PhysicsStep)]);
  ImGui::Text("split %7.2f ms   commit  %6.2f ms", phase[size_t(app::Phase::Split)],
              phase[size_t(app::Phase::Commit)]);
  const components::SplitTickTimes split = components::splitTickTimes(feed.splits);
  ImGui::Text("split work %6.2f ms   wait %6.2f ms   workers %6.2f ms", split.work, split.wait, split.workers);
  ImGui::EndGroup();
  markClock();
  drawGraph(feed);
}

// Main-thread split milliseconds per tick (the last 120), from 0 to twice the budget, and the budget
// line across the middle.
void Inspector::drawGraph(const InspectorFeed& feed) {
  const float budget = float(feed.splits.budget().settings().millisecondsPerTick);
  std::vector<float> values(feed.splitMsHistory.begin(), feed.splitMsHistory.end());
  if (values.empty()) values.push_back(0.f);
  ImGui::TextColored(kDim, "split ms per tick, red: the budget (%.2f ms)", double(budget));
  const ImVec2 size(ImGui::GetContentRegionAvail().x, 4.f * ImGui::GetFontSize());
  ImGui::PlotLines("##split-ms", values.data(), int(values.size()), 0, nullptr, 0.f, 2.f * budget, size);
  markClock();
  const ImVec2 lo = ImGui::GetItemRectMin(), hi = ImGui::GetItemRectMax();
  const float y = 0.5f * (lo.y + hi.y);
  ImGui::GetWindowDrawList()->AddLine(ImVec2(lo.x, y), ImVec2(hi.x, y), IM_COL32(255, 102, 77, 255), 1.f);
}

// The newest splits first, ten rows; the milliseconds column is wall-clock.
void Inspector::drawLog(const InspectorFeed& feed) {
  if (!ImGui::CollapsingHeader("Split log", ImGuiTreeNodeFlags_DefaultOpen)) return;
  const auto& entries = feed.log.entries();
  ImGui::Text("%zu splits", entries.size());
  constexpr size_t kRows = 10;
  const ImGuiTableFlags flags = ImGuiTableFlags_Borders | ImGuiTableFlags_RowBg | ImGuiTableFlags_SizingFixedFit;
  if (!ImGui::BeginTable("split-log", 6, flags)) return;
  for (const char* column : {"tick", "object", "status", "pieces", "mass kg", "ms"}) ImGui::TableSetupColumn(column);
  ImGui::TableHeadersRow();
  for (size_t k = 0; k < std::min(kRows, entries.size()); ++k) {
    const components::SplitLogEntry& e = entries[entries.size() - 1 - k];
    ImGui::TableNextRow();
    ImGui::TableNextColumn();
    ImGui::Text("%llu", static_cast<unsigned long long>(e.tick));
    ImGui::TableNextColumn();
    ImGui::TextUnformatted(e.original.c_str());
    ImGui::TableNextColumn();
    ImGui::TextUnformatted(e.status.c_str());
    ImGui::TableNextColumn();
    ImGui::Text("%zu", e.pieces);
    ImGui::TableNextColumn();
    ImGui::Text("%.2f", e.parentMass);
    ImGui::TableNextColumn();
    ImGui::Text("%7.2f", e.milliseconds);  // one width up to 999.99 ms: the same columns on slow builds
    markClock();
  }
  ImGui::EndTable();
}

#else

void Inspector::draw(app::TickContext&, const InspectorFeed&) {}

#endif

}  // namespace cleave::inspector
