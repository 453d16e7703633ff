// SPDX-License-Identifier: MIT
// cleave-split: reads a mesh file, cuts it by a plane with the concave splitter (caps, islands, mass
// properties) and reports the pieces, optionally writing one file per piece. With --pose it cuts the
// skinned mesh of a glTF model in a sampled pose and writes skinned, animated pieces. See
// docs/cleave-split.md.
//
// Exit codes: 0 success, 1 data error (unreadable or invalid file, split failure, write failure),
// 2 usage error.
#include <algorithm>
#include <charconv>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

#include "cleave_version.h"
#include "cleave/anim/animation_clip.h"
#include "cleave/anim/skeleton.h"
#include "cleave/assets/mesh_io.h"
#include "cleave/assets/model.h"
#include "cleave/geometry/mass_properties.h"
#include "cleave/geometry/mesh_splitter.h"
#include "cleave/geometry/primitives.h"

namespace {

namespace assets = cleave::assets;
namespace geometry = cleave::geometry;
namespace anim = cleave::anim;

constexpr int kExitData = 1;
constexpr int kExitUsage = 2;
constexpr int kMaxRepeat = 1000000;

constexpr const char* kUsage =
    "usage: cleave-split INPUT --plane NX NY NZ D [--out DIR] [--format obj|glb] [--hollow]\n"
    "                    [--open refuse|cap-closed|bridge] [--islands touching|connected] [--no-islands]\n"
    "                    [--all-pieces] [--uv world|bounds]\n"
    "                    [--pose CLIP:SECONDS] [--threads N] [--repeat N] [--warmup N] [--json]\n"
    "\n"
    "Cuts the mesh in INPUT (.obj .off .stl .ply .gltf .glb) by the plane {x : dot(n, x) = D}.\n"
    "The normal n is normalised (and D scaled with it); 'above' means dot(n, x) > D.\n"
    "\n"
    "  --plane NX NY NZ D  the cutting plane (required)\n"
    "  --out DIR           write piece_<k>_<above|below>.<format> per piece into DIR\n"
    "  --format obj|glb    output format for --out (default obj); GLB pieces of a glTF input keep\n"
    "                      its materials, textures and images\n"
    "  --hollow            do not cap the cut (open sections allowed)\n"
    "  --open MODE         a section that is not all closed loops (open art): cap-closed (default)\n"
    "                      caps the closed loops and leaves the open chains open; bridge also\n"
    "                      closes a chain whose ends are close, or whose chord crosses nothing,\n"
    "                      and caps it; refuse fails\n"
    "  --islands MODE      how a side that falls apart is divided: touching (default) keeps parts\n"
    "                      that touch, pass into or hold one another as one piece, and puts a part\n"
    "                      the plane does not reach with the nearest piece of its side (multi-part\n"
    "                      art); connected makes every separate part of the mesh a piece\n"
    "  --no-islands        keep each side as one piece even when it falls apart\n"
    "  --all-pieces        with --out, also write the pieces the plane did not reach (parts of the\n"
    "                      mesh wholly on one side, touching nothing that was cut)\n"
    "  --uv world|bounds   cap texture coordinates: world-planar (default) or normalised bounds\n"
    "  --pose CLIP:SECONDS cut the skinned mesh of a glTF model posed by clip CLIP (name or index)\n"
    "                      at SECONDS (wrapped into the clip); --format glb pieces keep the skin\n"
    "                      and the animations\n"
    "  --threads N         threads the split may use (default 1): a mesh of 50,000 triangles or\n"
    "                      more is cut in parts at once; the pieces are the same bytes for any N\n"
    "  --repeat N          run the split N times and report the median and minimum time (of a cut\n"
    "                      of the mesh with its weld known, as the engine cuts a mesh it has seen\n"
    "                      and every piece; the weld from nothing is timed on its own)\n"
    "  --warmup N          before the timed runs, N untimed ones (default 0): the timed runs then\n"
    "                      find the caches, the allocator and the splitter's scratch warm, as in a\n"
    "                      game that has cut before\n"
    "  --json              print one JSON object on stdout instead of text\n"
    "  --help              show this help\n"
    "  --version           print the version\n"
    "\n"
    "Exit status: 0 success, 1 bad data or failed split, 2 bad arguments.\n";

struct Arguments {
  std::string input;
  glm::dvec3 normal{0.0};
  double offset = 0.0;
  bool havePlane = false;
  std::optional<std::string> outDir;
  std::string format = "obj";
  bool hollow = false;
  geometry::OpenSectionMode open = geometry::OpenSectionMode::CapClosedLoops;
  bool islands = true;
  geometry::IslandMode islandMode = geometry::IslandMode::Touching;
  bool allPieces = false;
  geometry::CapUvMode uvMode = geometry::CapUvMode::WorldPlanar;
  int repeat = 1;
  int warmup = 0;
  int threads = 1;
  std::optional<std::string> poseClip;  // --pose: clip name or index
  double poseSeconds = 0.0;
  bool json = false;
  bool help = false;
  bool version = false;
};

bool parseNumber(std::string_view text, double& value) {
  if (!text.empty() && text.front() == '+') text.remove_prefix(1);
  if (text.empty()) return false;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  return ec == std::errc() && end == text.data() + text.size() && std::isfinite(value);
}

bool parseInt(std::string_view text, int& value) {
  if (text.empty()) return false;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  return ec == std::errc() && end == text.data() + text.size();
}

// The word after the option at list[i] (i moves onto it), as one of `choices`; otherwise false, with
// an error that lists the words.
template <class Enum>
bool parseChoice(const std::vector<std::string_view>& list, size_t& i,
                 std::initializer_list<std::pair<std::string_view, Enum>> choices, Enum& out, std::string& error) {
  const std::string option(list[i]);
  const std::string_view word = i + 1 < list.size() ? list[++i] : std::string_view();
  std::string words;
  for (const auto& [name, value] : choices) {
    if (name == word) {
      out = value;
      return true;
    }
    words += (words.empty() ? "" : " or ") + std::string(name);
  }
  error = option + " must be " + words + ", not '" + std::string(word) + "'";
  return false;
}

using Values = std::span<const std::string_view>;

bool parsePlane(Values v, Arguments& args, std::string& error) {
  double values[4];
  for (size_t k = 0; k < 4; ++k) {
    if (!parseNumber(v[k], values[k])) {
      error = "--plane: '" + std::string(v[k]) + "' is not a finite number";
      return false;
    }
  }
  args.normal = glm::dvec3(values[0], values[1], values[2]);
  args.offset = values[3];
  const double length = glm::length(args.normal);
  if (!(length > 0.0) || !std::isfinite(length)) {
    error = "--plane: the normal must not be zero";
    return false;
  }
  // The tool normalises: {x : dot(n, x) = D} is the same plane as {x : dot(n/|n|, x) = D/|n|}.
  args.normal /= length;
  args.offset /= length;
  args.havePlane = true;
  return true;
}

bool parseFormat(Values v, Arguments& args, std::string& error) {
  args.format = std::string(v[0]);
  if (args.format == "obj" || args.format == "glb") return true;
  error = "--format must be obj or glb, not '" + args.format + "'";
  return false;
}

bool parseUv(Values v, Arguments& args, std::string& error) {
  if (v[0] == "world")
    args.uvMode = geometry::CapUvMode::WorldPlanar;
  else if (v[0] == "bounds")
    args.uvMode = geometry::CapUvMode::NormalizedBounds;
  else {
    error = "--uv must be world or bounds, not '" + std::string(v[0]) + "'";
    return false;
  }
  return true;
}

bool parseCount(std::string_view text, int low, int high, int& value) {
  return parseInt(text, value) && value >= low && value <= high;
}

bool parsePose(Values v, Arguments& args, std::string& error) {
  const std::string_view value = v[0];
  const size_t colon = value.rfind(':');
  if (colon == std::string_view::npos || colon == 0 ||
      !parseNumber(value.substr(colon + 1), args.poseSeconds)) {
    error = "--pose needs CLIP:SECONDS (a clip name or index, a finite time), not '" +
            std::string(value) + "'";
    return false;
  }
  args.poseClip = std::string(value.substr(0, colon));
  return true;
}

// One command-line option: its names, how many values follow it, and what it sets. The word
// options (--open, --islands) take their word themselves (see parseChoice), so that a missing word
// is reported with the words it may be.
struct Option {
  std::string_view name;
  std::string_view alias;
  size_t values;
  bool (*apply)(Values values, Arguments& args, std::string& error);
};

bool setFlag(bool Arguments::*flag, Arguments& args) {
  args.*flag = true;
  return true;
}

constexpr Option kOptions[] = {
    {"--help", "-h", 0,
     [](Values, Arguments& a, std::string&) { return setFlag(&Arguments::help, a); }},
    {"--version", "", 0,
     [](Values, Arguments& a, std::string&) { return setFlag(&Arguments::version, a); }},
    {"--plane", "", 4, parsePlane},
    {"--out", "", 1,
     [](Values v, Arguments& a, std::string&) {
       a.outDir = std::string(v[0]);
       return true;
     }},
    {"--format", "", 1, parseFormat},
    {"--hollow", "", 0,
     [](Values, Arguments& a, std::string&) { return setFlag(&Arguments::hollow, a); }},
    {"--no-islands", "", 0,
     [](Values, Arguments& a, std::string&) {
       a.islands = false;
       return true;
     }},
    {"--all-pieces", "", 0,
     [](Values, Arguments& a, std::string&) { return setFlag(&Arguments::allPieces, a); }},
    {"--uv", "", 1, parseUv},
    {"--repeat", "", 1,
     [](Values v, Arguments& a, std::string& error) {
       if (parseCount(v[0], 1, kMaxRepeat, a.repeat)) return true;
       error = "--repeat needs an integer from 1 to " + std::to_string(kMaxRepeat);
       return false;
     }},
    {"--warmup", "", 1,
     [](Values v, Arguments& a, std::string& error) {
       if (parseCount(v[0], 0, kMaxRepeat, a.warmup)) return true;
       error = "--warmup needs an integer from 0 to " + std::to_string(kMaxRepeat);
       return false;
     }},
    {"--threads", "", 1,
     [](Values v, Arguments& a, std::string& error) {
       if (parseCount(v[0], 1, 64, a.threads)) return true;
       error = "--threads needs an integer from 1 to 64";
       return false;
     }},
    {"--pose", "", 1, parsePose},
    {"--json", "", 0,
     [](Values, Arguments& a, std::string&) { return setFlag(&Arguments::json, a); }},
};

// The word options: the word after the option at list[i] (i moves onto it). False when `arg` is
// not one of them (`handled` false) or the word is not one of its choices (`handled` true).
bool parseWordOption(const std::vector<std::string_view>& list, size_t& i, Arguments& args,
                     bool& handled, std::string& error) {
  const std::string_view arg = list[i];
  handled = arg == "--open" || arg == "--islands";
  if (arg == "--open") {
    using geometry::OpenSectionMode;
    return parseChoice(list, i,
                       {{"refuse", OpenSectionMode::Refuse},
                        {"cap-closed", OpenSectionMode::CapClosedLoops},
                        {"bridge", OpenSectionMode::Bridge}},
                       args.open, error);
  }
  if (arg == "--islands") {
    using geometry::IslandMode;
    return parseChoice(list, i,
                       {{"touching", IslandMode::Touching}, {"connected", IslandMode::Connected}},
                       args.islandMode, error);
  }
  return false;
}

// The input file, or a usage error for an unknown option or a second input.
bool parsePositional(std::string_view arg, Arguments& args, std::string& error) {
  if (arg.size() > 1 && arg.front() == '-') {
    error = "unknown option '" + std::string(arg) + "'";
    return false;
  }
  if (!args.input.empty()) {
    error = "more than one input file ('" + args.input + "' and '" + std::string(arg) + "')";
    return false;
  }
  args.input = std::string(arg);
  return true;
}

// One argument at list[i] (i moves onto the last value it takes).
bool parseArgument(const std::vector<std::string_view>& list, size_t& i, Arguments& args,
                   std::string& error) {
  const std::string_view arg = list[i];
  bool handled = false;
  const bool ok = parseWordOption(list, i, args, handled, error);
  if (handled) return ok;
  for (const Option& option : kOptions) {
    if (arg != option.name && (option.alias.empty() || arg != option.alias)) continue;
    if (i + option.values >= list.size()) {
      error = std::string(arg) + " needs " + std::to_string(option.values) + " value" +
              (option.values > 1 ? "s" : "");
      return false;
    }
    const Values values(list.data() + i + 1, option.values);
    i += option.values;
    return option.apply(values, args, error);
  }
  return parsePositional(arg, args, error);
}

// Fills `args`; on a usage error returns false with `error` set.
bool parseArguments(int argc, char** argv, Arguments& args, std::string& error) {
  const std::vector<std::string_view> list(argv + 1, argv + argc);
  for (size_t i = 0; i < list.size(); ++i) {
    if (!parseArgument(list, i, args, error)) return false;
  }
  if (args.help || args.version) return true;
  if (args.input.empty()) {
    error = "no input file";
    return false;
  }
  if (!args.havePlane) {
    error = "--plane NX NY NZ D is required";
    return false;
  }
  return true;
}

nlohmann::ordered_json massJson(const geometry::MassProperties& mass) {
  nlohmann::ordered_json out;
  out["volume"] = mass.volume;
  out["center_of_mass"] = {mass.centerOfMass.x, mass.centerOfMass.y, mass.centerOfMass.z};
  const glm::dmat3& I = mass.inertia;  // column-major: I[column][row]
  out["inertia"] = {I[0][0], I[1][1], I[2][2], I[1][0], I[2][0], I[2][1]};
  return out;
}

// The materials of `model` with the textures, samplers and images they use, for the GLB pieces; its
// meshes and skins are dropped.
assets::Model materialsOf(assets::Model&& model) {
  assets::Model out;
  out.materials = std::move(model.materials);
  out.textures = std::move(model.textures);
  out.samplers = std::move(model.samplers);
  out.images = std::move(model.images);
  return out;
}

// The materials of a glTF input for its GLB pieces, read with the model loader (the mesh reader
// keeps the names only). A model the loader refuses gives none and a warning: the pieces then get
// the material names only.
assets::Model inputMaterials(const std::string& path, std::vector<std::string>& warnings) {
  assets::ModelLoadResult loaded = assets::loadModel(path);
  if (!loaded.ok()) {
    warnings.push_back(loaded.message + " (the GLB pieces get the material names only)");
    return {};
  }
  return materialsOf(std::move(loaded.model));
}

double median(std::vector<double> values) {
  if (values.empty()) return 0.0;
  std::sort(values.begin(), values.end());
  const size_t mid = values.size() / 2;
  return values.size() % 2 == 1 ? values[mid] : 0.5 * (values[mid - 1] + values[mid]);
}

// What the load stage gives: the mesh to cut with its materials and, with --pose, the skin and the
// joint matrices of the sampled pose; then what the measure stage finds out about it.
struct Input {
  geometry::MeshData mesh;
  std::vector<std::string> materialNames;
  std::vector<glm::vec4> materialColors;
  std::vector<std::string> warnings;
  assets::Model materials;  // a glTF input's materials, copied into GLB pieces
  // --pose: the skinned mesh of the model's first skin (all of its meshes merged), its skin and the
  // joint matrices of the sampled pose.
  assets::ModelSkin skin;
  std::string clipName;
  std::vector<glm::mat4> jointMatrices;
  // The container shares the mesh read (no copy), as the engine shares a renderer's mesh.
  std::shared_ptr<const geometry::MeshData> shared;

  geometry::MassProperties mass;
  // The bounds of the mesh as it is cut (posed with --pose), to choose a plane by.
  glm::dvec3 lo{INFINITY};
  glm::dvec3 hi{-INFINITY};
  bool closed = false;
};

// The clip --pose names (by name first, then by index); null when there is none.
const anim::AnimationClip* findClip(const assets::ModelSkin& skin, const std::string& wanted) {
  for (const anim::AnimationClip& c : skin.clips) {
    if (c.name == wanted) return &c;
  }
  int index = -1;
  if (parseInt(wanted, index) && index >= 0 && size_t(index) < skin.clips.size()) {
    return &skin.clips[static_cast<size_t>(index)];
  }
  return nullptr;
}

void printNoClip(const Arguments& args, const assets::ModelSkin& skin) {
  std::string names;
  for (size_t k = 0; k < skin.clips.size(); ++k) {
    names += (k ? ", '" : "'") + skin.clips[k].name + "'";
  }
  std::fprintf(stderr, "cleave-split: %s: --pose: no clip '%s' (the skin has %zu clip(s)%s%s)\n",
               args.input.c_str(), args.poseClip->c_str(), skin.clips.size(),
               names.empty() ? "" : ": ", names.c_str());
}

// --pose: the skinned mesh of a glTF model, posed by the clip; false (told on stderr) on failure.
bool loadPosed(const Arguments& args, Input& in) {
  assets::ModelLoadResult model = assets::loadModel(args.input);
  if (!model.ok()) {
    std::fprintf(stderr, "cleave-split: %s\n", model.message.c_str());
    return false;
  }
  in.warnings = model.warnings;
  int32_t skinIndex = -1;
  for (const assets::ModelMesh& part : model.model.meshes) {
    if (part.skin >= 0) {
      skinIndex = part.skin;
      break;
    }
  }
  if (skinIndex < 0) {
    std::fprintf(stderr, "cleave-split: %s: --pose needs a skinned mesh and the model has none\n",
                 args.input.c_str());
    return false;
  }
  for (const assets::ModelMesh& part : model.model.meshes) {
    if (part.skin == skinIndex) {
      in.mesh =
          in.mesh.positions.empty() ? part.mesh : geometry::primitives::merge(in.mesh, part.mesh);
    }
  }
  in.skin = std::move(model.model.skins[static_cast<size_t>(skinIndex)]);
  const anim::AnimationClip* clip = findClip(in.skin, *args.poseClip);
  if (clip == nullptr) {
    printNoClip(args, in.skin);
    return false;
  }
  in.clipName = clip->name;
  anim::Pose pose;
  anim::sampleClip(in.skin.skeleton, *clip, static_cast<float>(args.poseSeconds), true, pose);
  anim::poseToJointMatrices(in.skin.skeleton, pose, in.jointMatrices);
  for (const assets::ModelMaterial& material : model.model.materials) {
    in.materialNames.push_back(material.name);
    in.materialColors.push_back(material.baseColorFactor);
  }
  in.materials = materialsOf(std::move(model.model));
  return true;
}

// Any mesh file; a glTF input cut into GLB pieces also gives its materials.
bool loadStatic(const Arguments& args, Input& in) {
  assets::MeshReadResult loaded = assets::loadMesh(args.input);
  if (!loaded.ok()) {
    std::fprintf(stderr, "cleave-split: %s\n", loaded.message.c_str());
    return false;
  }
  in.mesh = std::move(loaded.mesh);
  in.materialNames = std::move(loaded.materialNames);
  in.warnings = std::move(loaded.warnings);
  const assets::MeshFormat format = assets::formatFromPath(args.input);
  if (args.outDir && args.format == "glb" &&
      (format == assets::MeshFormat::Gltf || format == assets::MeshFormat::Glb)) {
    in.materials = inputMaterials(args.input, in.warnings);
  }
  return true;
}

// The load stage: reads the input and tells its warnings (on stderr, not with --json).
bool load(const Arguments& args, Input& in) {
  if (!(args.poseClip ? loadPosed(args, in) : loadStatic(args, in))) return false;
  if (!args.json) {
    for (const std::string& warning : in.warnings) {
      std::fprintf(stderr, "cleave-split: warning: %s\n", warning.c_str());
    }
  }
  in.shared = std::shared_ptr<const geometry::MeshData>(std::shared_ptr<void>(), &in.mesh);
  return true;
}

// The container's cut space: the source positions, or the skinned positions of the pose. With a
// weld, the mesh is not welded again (as the engine cuts a mesh it has seen, and every piece).
geometry::SplitStatus prepare(const Arguments& args, const Input& in,
                              geometry::MeshContainer& container, const geometry::MeshWeld* weld,
                              std::string& message) {
  geometry::MeshStatus set = container.setMesh(in.shared, weld);
  if (set.ok() && args.poseClip) set = container.setSkinningPose(in.jointMatrices, glm::mat4(1.f));
  else if (set.ok()) container.setTransform(glm::mat4(1.f));
  message = std::move(set.message);
  return set.code;
}

// The input's volume, bounds and closedness, as it is cut (posed with --pose).
bool measure(const Arguments& args, Input& in) {
  auto grow = [&](const glm::dvec3& q) {
    in.lo = glm::min(in.lo, q);
    in.hi = glm::max(in.hi, q);
  };
  if (args.poseClip) {
    geometry::MeshContainer posed;
    std::string message;
    const geometry::SplitStatus status = prepare(args, in, posed, nullptr, message);
    if (status != geometry::SplitStatus::Ok) {
      std::fprintf(stderr, "cleave-split: %s: invalid skinned mesh: %s\n", args.input.c_str(),
                   message.empty() ? geometry::toString(status) : message.c_str());
      return false;
    }
    std::vector<glm::dvec3> scratch;
    in.mass = geometry::computeMassProperties(posed.cutPositions().doubles(scratch), in.mesh.indices);
    for (const glm::dvec3& q : posed.cutPositions()) grow(q);
  } else {
    in.mass = geometry::computeMassProperties(in.mesh);
    for (const glm::vec3& p : in.mesh.positions) grow(glm::dvec3(p));
  }
  in.closed = geometry::isClosedAndOriented(in.mesh.positions, in.mesh.indices);
  return true;
}

// What the cut stage gives: the split and its times (milliseconds per run).
struct Cut {
  geometry::Plane plane;
  geometry::SplitOptions options;
  geometry::SplitResult result;
  geometry::MeshWeld weld;
  std::vector<double> times, setupTimes, cutTimes;  // a cut; set-up from nothing; split() alone
  bool ok() const { return result.status == geometry::SplitStatus::Ok; }
};

geometry::SplitOptions splitOptions(const Arguments& args, const Input& in) {
  geometry::SplitOptions options;
  options.cap = !args.hollow;
  options.threads = static_cast<uint32_t>(args.threads);
  options.openSections = args.open;
  options.separateIslands = args.islands;
  options.islands = args.islandMode;
  options.uvMode = args.uvMode;
  options.computeMass = true;
  // The cap gets a material id of its own, after every id the input uses.
  uint32_t capMaterialId = 1;
  for (const geometry::SubMesh& sub : in.mesh.submeshes) {
    capMaterialId = std::max(capMaterialId, sub.materialId + 1);
  }
  options.capMaterialId =
      std::max<uint32_t>(capMaterialId, static_cast<uint32_t>(in.materialNames.size()));
  return options;
}

using Clock = std::chrono::steady_clock;

double ms(Clock::time_point a, Clock::time_point b) {
  return std::chrono::duration<double, std::milli>(b - a).count();
}

// The cut stage. Timed, each run, outside file I/O:
//  - set-up from nothing: a new container takes the mesh (checks, weld by position, closedness, cut
//    space), what the first cut of a mesh never seen before pays once;
//  - a cut: a container in use takes the mesh with the weld it had (checks, cut space),
//    then the split with caps, islands and mass properties: what the engine pays for every cut of
//    a mesh it has seen, and of every piece (pieces carry their weld). The split alone is also
//    reported.
// The set-ups from nothing first, then the cuts, each in a loop of its own, so that neither
// measures the other's cache and page-fault traffic; each loop begins with --warmup untimed runs. False (told on stderr) when the mesh is
// refused; a failed split is in cut.result.
bool cut(const Arguments& args, const Input& in, Cut& cut) {
  cut.plane = geometry::Plane{args.normal, args.offset};
  cut.options = splitOptions(args, in);
  const size_t repeat = static_cast<size_t>(args.repeat);
  const size_t warmup = static_cast<size_t>(args.warmup);
  cut.times.reserve(repeat);
  cut.setupTimes.reserve(repeat);
  cut.cutTimes.reserve(repeat);
  for (size_t run = 0; run < warmup + repeat; ++run) {
    std::string message;
    const auto setupStart = Clock::now();
    geometry::MeshContainer fresh;
    const geometry::SplitStatus setStatus = prepare(args, in, fresh, nullptr, message);
    const auto setupEnd = Clock::now();
    if (setStatus != geometry::SplitStatus::Ok) {
      std::fprintf(stderr, "cleave-split: %s: invalid mesh: %s\n", args.input.c_str(),
                   message.empty() ? geometry::toString(setStatus) : message.c_str());
      return false;
    }
    if (run >= warmup) cut.setupTimes.push_back(ms(setupStart, setupEnd));
    if (run == 0) fresh.copyWeld(cut.weld);
  }
  std::unique_ptr<geometry::IMeshSplitter> splitter = geometry::makeConcaveSplitter();
  geometry::MeshContainer container;
  for (size_t run = 0; run < warmup + repeat; ++run) {
    std::string message;
    const auto start = Clock::now();
    if (prepare(args, in, container, &cut.weld, message) != geometry::SplitStatus::Ok) {
      std::fprintf(stderr, "cleave-split: %s: %s\n", args.input.c_str(), message.c_str());
      return false;
    }
    const auto setUp = Clock::now();
    splitter->split(container, cut.plane, cut.options, cut.result);
    const auto end = Clock::now();
    if (run >= warmup || !cut.ok()) {
      cut.times.push_back(ms(start, end));
      cut.cutTimes.push_back(ms(setUp, end));
    }
    if (!cut.ok()) break;
  }
  return true;
}

// The write stage: one file per piece into --out (the pieces the plane did not reach only with
// --all-pieces); `written` gets their paths. False (told on stderr) on a write failure.
bool write(const Arguments& args, const Input& in, const Cut& cut,
           std::vector<std::string>& written) {
  std::error_code ec;
  std::filesystem::create_directories(*args.outDir, ec);
  if (ec) {
    std::fprintf(stderr, "cleave-split: %s: cannot create the output folder (%s)\n",
                 args.outDir->c_str(), ec.message().c_str());
    return false;
  }
  assets::MeshWriteOptions writeOptions;
  writeOptions.capMaterialId = cut.options.capMaterialId;
  writeOptions.materialNames = in.materialNames;
  writeOptions.materialColors = in.materialColors;
  writeOptions.materials = in.materials.materialSource();
  for (size_t k = 0; k < cut.result.pieces.size(); ++k) {
    const geometry::SplitPiece& piece = cut.result.pieces[k];
    if (!piece.reached && !args.allPieces)
      continue;  // a part the plane did not reach: not asked for
    const std::string file =
        "piece_" + std::to_string(k) + (piece.side > 0 ? "_above." : "_below.") + args.format;
    const std::string path = (std::filesystem::path(*args.outDir) / file).string();
    // With --pose: pieces in bind space; GLB keeps the skin and the clips, OBJ is the bind-space
    // mesh.
    const assets::MeshWriteResult w =
        args.format != "glb" ? assets::writeObj(path, piece.mesh, writeOptions)
        : args.poseClip ? assets::writeSkinnedGlb(path, piece.mesh, in.skin.skeleton, in.skin.clips,
                                                  writeOptions)
                        : assets::writeGlb(path, piece.mesh, writeOptions);
    if (!w.ok()) {
      std::fprintf(stderr, "cleave-split: %s\n", w.message.c_str());
      return false;
    }
    written.push_back(path);
  }
  return true;
}

double fastest(const std::vector<double>& times) {
  return times.empty() ? 0.0 : *std::min_element(times.begin(), times.end());
}

nlohmann::ordered_json inputJson(const Arguments& args, const Input& in, const Cut& cut) {
  const glm::dvec3 centre = 0.5 * (in.lo + in.hi);
  return {{"file", args.input},
          {"vertices", in.mesh.vertexCount()},
          {"triangles", in.mesh.triangleCount()},
          {"closed", in.closed},
          {"wound_inwards", cut.weld.inverted},
          {"volume", in.mass.volume},
          {"volume_from_hull", in.mass.fromConvexHull},
          {"bounds",
           {{"min", {in.lo.x, in.lo.y, in.lo.z}},
            {"max", {in.hi.x, in.hi.y, in.hi.z}},
            {"centre", {centre.x, centre.y, centre.z}}}}};
}

nlohmann::ordered_json piecesJson(const Arguments& args, const geometry::SplitResult& result) {
  nlohmann::ordered_json pieces = nlohmann::ordered_json::array();
  for (const geometry::SplitPiece& piece : result.pieces) {
    nlohmann::ordered_json p;
    p["side"] = piece.side > 0 ? "above" : "below";
    p["triangles"] = piece.mesh.triangleCount();
    p["cap_triangles"] = piece.capTriangles;
    p["cap_loops"] = piece.capLoops;
    p["closed"] = piece.mass.closed;
    p["reached"] = piece.reached;
    if (args.poseClip) p["joints_used"] = piece.joints.size();
    const nlohmann::ordered_json mass = massJson(piece.mass);
    for (const auto& [key, value] : mass.items()) p[key] = value;
    pieces.push_back(std::move(p));
  }
  return pieces;
}

nlohmann::ordered_json timingJson(const Arguments& args, const Cut& cut) {
  std::vector<double> firstCut(cut.times.size());
  for (size_t k = 0; k < cut.times.size(); ++k)
    firstCut[k] = cut.setupTimes[k] + cut.cutTimes[k];  // run k of each
  return {{"repeat", cut.times.size()},
          {"threads", args.threads},
          {"split_ms_median", median(cut.times)},
          {"split_ms_min", fastest(cut.times)},
          {"setup_ms_median", median(cut.setupTimes)},
          {"cut_ms_median", median(cut.cutTimes)},
          {"first_cut_ms_median", median(firstCut)}};
}

// The report stage with --json: one object on stdout.
void reportJson(const Arguments& args, const Input& in, const Cut& cut,
                const std::vector<std::string>& written) {
  const geometry::SplitResult& result = cut.result;
  nlohmann::ordered_json out;
  out["input"] = inputJson(args, in, cut);
  if (args.poseClip) {
    out["pose"] = {{"clip", in.clipName},
                   {"seconds", args.poseSeconds},
                   {"joints", in.skin.skeleton.size()},
                   {"clips", in.skin.clips.size()}};
  }
  out["plane"] = {{"normal", {cut.plane.normal.x, cut.plane.normal.y, cut.plane.normal.z}},
                  {"offset", cut.plane.offset}};
  out["status"] = geometry::toString(result.status);
  if (!cut.ok()) out["message"] = result.message;
  out["section_loops"] = result.sectionLoops;
  out["open_chains"] = result.openChains;
  out["bridged_chains"] = result.bridgedChains;
  out["uncapped_loops"] = result.uncappedLoops;
  out["pieces"] = piecesJson(args, result);
  if (!written.empty()) out["files"] = written;
  out["timing"] = timingJson(args, cut);
  std::puts(out.dump(2).c_str());
}

void printInput(const Arguments& args, const Input& in, const Cut& cut) {
  const glm::dvec3 lo = in.lo, hi = in.hi, centre = 0.5 * (lo + hi);
  std::printf("%s: %zu vertices, %zu triangles, %s, volume %.9g%s\n", args.input.c_str(),
              in.mesh.vertexCount(), in.mesh.triangleCount(), in.closed ? "closed" : "open",
              in.mass.volume,
              in.mass.fromConvexHull
                  ? " (not the mesh's own: it is open, so its convex hull, or its closed parts "
                    "and the hulls of its open ones)"
                  : "");
  std::printf("bounds: (%.6g, %.6g, %.6g) to (%.6g, %.6g, %.6g), centre (%.6g, %.6g, %.6g)\n", lo.x,
              lo.y, lo.z, hi.x, hi.y, hi.z, centre.x, centre.y, centre.z);
  if (args.poseClip) {
    std::printf("pose: clip '%s' at %.6g s, %zu joints\n", in.clipName.c_str(), args.poseSeconds,
                in.skin.skeleton.size());
  }
  std::printf("plane: normal (%.9g, %.9g, %.9g), offset %.9g\n", cut.plane.normal.x,
              cut.plane.normal.y, cut.plane.normal.z, cut.plane.offset);
}

void printPieces(const Arguments& args, const geometry::SplitResult& result, bool ok) {
  double total = 0.0;
  for (size_t k = 0; k < result.pieces.size(); ++k) {
    const geometry::SplitPiece& piece = result.pieces[k];
    total += piece.mass.volume;
    std::printf(
        "piece %zu %s: %zu triangles (%u cap, %u loops), %s, volume %.9g, "
        "centre (%.6g, %.6g, %.6g)%s\n",
        k, piece.side > 0 ? "above" : "below", piece.mesh.triangleCount(), piece.capTriangles,
        piece.capLoops, piece.mass.closed ? "closed" : "open", piece.mass.volume,
        piece.mass.centerOfMass.x, piece.mass.centerOfMass.y, piece.mass.centerOfMass.z,
        piece.reached                    ? ""
        : args.allPieces || !args.outDir ? ", not reached by the plane"
                                         : ", not reached by the plane (not written)");
  }
  if (ok) std::printf("pieces volume total %.9g\n", total);
}

// The report stage as text on stdout.
void reportText(const Arguments& args, const Input& in, const Cut& cut,
                const std::vector<std::string>& written) {
  const geometry::SplitResult& result = cut.result;
  printInput(args, in, cut);
  if (cut.ok()) std::printf("status: Ok\n");  // a failure is told once, on stderr, by reportFailure
  if (result.openChains > 0 || result.uncappedLoops > 0)
    std::printf(
        "section: %u closed loop(s), %u left open; %u open chain(s) left open (the mesh is open or "
        "non-manifold where it is cut)\n",
        result.sectionLoops, result.uncappedLoops, result.openChains);
  printPieces(args, result, cut.ok());
  for (const std::string& path : written) std::printf("wrote %s\n", path.c_str());
  if (args.poseClip && args.outDir && args.format == "obj")
    std::printf(
        "note: OBJ pieces are written in bind space; --format glb writes skinned pieces that keep "
        "the pose's "
        "clips\n");
  std::printf(
      "split time: %.3f ms a cut with the mesh's weld known (median of %zu run%s, fastest %.3f "
      "ms); welding "
      "the mesh the first time costs %.3f ms more, once per mesh\n",
      median(cut.times), cut.times.size(), cut.times.size() == 1 ? "" : "s", fastest(cut.times),
      median(cut.setupTimes));
}

// A failed split, told once on stderr with a hint at what to change.
void reportFailure(const Arguments& args, const Input& in, const Cut& cut) {
  const geometry::SplitResult& result = cut.result;
  char bounds[320] = "";
  if (result.status == geometry::SplitStatus::PlaneMissesMesh) {
    const glm::dvec3 lo = in.lo, hi = in.hi, centre = 0.5 * (lo + hi);
    // The offsets along this normal at which a plane crosses the mesh's bounding box.
    double low = INFINITY, high = -INFINITY;
    for (int k = 0; k < 8; ++k) {
      const glm::dvec3 corner((k & 1) ? hi.x : lo.x, (k & 2) ? hi.y : lo.y, (k & 4) ? hi.z : lo.z);
      low = std::min(low, glm::dot(cut.plane.normal, corner));
      high = std::max(high, glm::dot(cut.plane.normal, corner));
    }
    std::snprintf(bounds, sizeof bounds,
                  " (the mesh spans (%.6g, %.6g, %.6g) to (%.6g, %.6g, %.6g), centre (%.6g, %.6g, "
                  "%.6g): with this "
                  "normal, an offset between %.6g and %.6g crosses its box)",
                  lo.x, lo.y, lo.z, hi.x, hi.y, hi.z, centre.x, centre.y, centre.z, low, high);
  }
  const char* hint = result.status == geometry::SplitStatus::OpenSection
                         ? " (--open cap-closed cuts it and leaves the open chains open, --open "
                           "bridge also closes them where it can; --hollow cuts it uncapped)"
                         : bounds;
  std::fprintf(stderr, "cleave-split: %s: split failed: %s%s%s%s\n", args.input.c_str(),
               geometry::toString(result.status), result.message.empty() ? "" : ": ",
               result.message.c_str(), hint);
}

}  // namespace

// parse -> load (and measure) -> cut -> write -> report: each stage tells its own failure.
int main(int argc, char** argv) {
  Arguments args;
  std::string usageError;
  if (!parseArguments(argc, argv, args, usageError)) {
    std::fprintf(stderr, "cleave-split: %s (see --help)\n", usageError.c_str());
    return kExitUsage;
  }
  if (args.help) {
    std::fputs(kUsage, stdout);
    return 0;
  }
  if (args.version) {
    std::printf("cleave-split %s\n", cleave::kVersion);
    return 0;
  }
  Input in;
  if (!load(args, in) || !measure(args, in)) return kExitData;
  Cut split;
  if (!cut(args, in, split)) return kExitData;
  std::vector<std::string> written;
  if (split.ok() && args.outDir && !write(args, in, split, written)) return kExitData;
  if (args.json)
    reportJson(args, in, split, written);
  else
    reportText(args, in, split, written);
  if (!split.ok()) {
    reportFailure(args, in, split);
    return kExitData;
  }
  return 0;
}
