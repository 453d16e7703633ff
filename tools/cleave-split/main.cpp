// cleave-split: reads a mesh file, cuts it by a plane with the concave splitter (caps, islands, mass
// properties) and reports the pieces, optionally writing one file per piece. See docs/cleave-split.md.
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
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

#include "engine/assets/mesh_io.h"
#include "engine/geometry/mass_properties.h"
#include "engine/geometry/mesh_splitter.h"

namespace {

namespace assets = cleave::assets;
namespace geometry = cleave::geometry;

constexpr int kExitData = 1;
constexpr int kExitUsage = 2;
constexpr int kMaxRepeat = 1000000;

constexpr const char* kUsage =
    "usage: cleave-split INPUT --plane NX NY NZ D [--out DIR] [--format obj|glb] [--hollow]\n"
    "                    [--no-islands] [--uv world|bounds] [--repeat N] [--json]\n"
    "\n"
    "Cuts the mesh in INPUT (.obj .off .stl .ply .gltf .glb) by the plane {x : dot(n, x) = D}.\n"
    "The normal n is normalised (and D scaled with it); 'above' means dot(n, x) > D.\n"
    "\n"
    "  --plane NX NY NZ D  the cutting plane (required)\n"
    "  --out DIR           write piece_<k>_<above|below>.<format> per piece into DIR\n"
    "  --format obj|glb    output format for --out (default obj)\n"
    "  --hollow            do not cap the cut (open sections allowed)\n"
    "  --no-islands        keep each side as one piece even when it falls apart\n"
    "  --uv world|bounds   cap texture coordinates: world-planar (default) or normalised bounds\n"
    "  --repeat N          run the split N times and report the median and minimum time\n"
    "  --json              print one JSON object on stdout instead of text\n"
    "  --help              show this help\n"
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
  bool islands = true;
  geometry::CapUvMode uvMode = geometry::CapUvMode::WorldPlanar;
  int repeat = 1;
  bool json = false;
  bool help = false;
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

// Fills `args`; on a usage error returns false with `error` set.
bool parseArguments(int argc, char** argv, Arguments& args, std::string& error) {
  std::vector<std::string_view> list(argv + 1, argv + argc);
  for (size_t i = 0; i < list.size(); ++i) {
    const std::string_view arg = list[i];
    auto needs = [&](size_t count) {
      if (i + count >= list.size()) {
        error = std::string(arg) + " needs " + std::to_string(count) + " value" + (count > 1 ? "s" : "");
        return false;
      }
      return true;
    };
    if (arg == "--help" || arg == "-h") {
      args.help = true;
    } else if (arg == "--plane") {
      if (!needs(4)) return false;
      double values[4];
      for (int k = 0; k < 4; ++k) {
        if (!parseNumber(list[i + 1 + static_cast<size_t>(k)], values[k])) {
          error = "--plane: '" + std::string(list[i + 1 + static_cast<size_t>(k)]) +
                  "' is not a finite number";
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
      i += 4;
    } else if (arg == "--out") {
      if (!needs(1)) return false;
      args.outDir = std::string(list[++i]);
    } else if (arg == "--format") {
      if (!needs(1)) return false;
      args.format = std::string(list[++i]);
      if (args.format != "obj" && args.format != "glb") {
        error = "--format must be obj or glb, not '" + args.format + "'";
        return false;
      }
    } else if (arg == "--hollow") {
      args.hollow = true;
    } else if (arg == "--no-islands") {
      args.islands = false;
    } else if (arg == "--uv") {
      if (!needs(1)) return false;
      const std::string_view mode = list[++i];
      if (mode == "world") args.uvMode = geometry::CapUvMode::WorldPlanar;
      else if (mode == "bounds") args.uvMode = geometry::CapUvMode::NormalizedBounds;
      else {
        error = "--uv must be world or bounds, not '" + std::string(mode) + "'";
        return false;
      }
    } else if (arg == "--repeat") {
      if (!needs(1)) return false;
      if (!parseInt(list[++i], args.repeat) || args.repeat < 1 || args.repeat > kMaxRepeat) {
        error = "--repeat needs an integer from 1 to " + std::to_string(kMaxRepeat);
        return false;
      }
    } else if (arg == "--json") {
      args.json = true;
    } else if (arg.size() > 1 && arg.front() == '-') {
      error = "unknown option '" + std::string(arg) + "'";
      return false;
    } else if (args.input.empty()) {
      args.input = std::string(arg);
    } else {
      error = "more than one input file ('" + args.input + "' and '" + std::string(arg) + "')";
      return false;
    }
  }
  if (args.help) return true;
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

double median(std::vector<double> values) {
  if (values.empty()) return 0.0;
  std::sort(values.begin(), values.end());
  const size_t mid = values.size() / 2;
  return values.size() % 2 == 1 ? values[mid] : 0.5 * (values[mid - 1] + values[mid]);
}

}  // namespace

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

  const assets::MeshReadResult loaded = assets::loadMesh(args.input);
  if (!loaded.ok) {
    std::fprintf(stderr, "cleave-split: %s\n", loaded.error.c_str());
    return kExitData;
  }
  if (!args.json) {
    for (const std::string& warning : loaded.warnings) {
      std::fprintf(stderr, "cleave-split: warning: %s\n", warning.c_str());
    }
  }
  const geometry::MeshData& mesh = loaded.mesh;
  const geometry::MassProperties inputMass = geometry::computeMassProperties(mesh);
  const bool inputClosed = geometry::isClosedAndOriented(mesh.positions, mesh.indices);

  geometry::SplitOptions options;
  options.cap = !args.hollow;
  options.separateIslands = args.islands;
  options.uvMode = args.uvMode;
  options.computeMass = true;
  // The cap gets a material id of its own, after every id the input uses.
  uint32_t capMaterialId = 1;
  for (const geometry::SubMesh& sub : mesh.submeshes) {
    capMaterialId = std::max(capMaterialId, sub.materialId + 1);
  }
  capMaterialId = std::max<uint32_t>(capMaterialId, static_cast<uint32_t>(loaded.materialNames.size()));
  options.capMaterialId = capMaterialId;

  geometry::Plane plane;
  plane.normal = args.normal;
  plane.offset = args.offset;

  // Timed: container setup (copy, weld, cut-space positions) and the split with caps, islands and
  // mass properties. File reading and writing are outside the timing.
  std::unique_ptr<geometry::IMeshSplitter> splitter = geometry::makeConcaveSplitter();
  geometry::SplitResult result;
  std::vector<double> times, setupTimes, cutTimes;  // whole; container set-up; split alone
  times.reserve(static_cast<size_t>(args.repeat));
  setupTimes.reserve(static_cast<size_t>(args.repeat));
  cutTimes.reserve(static_cast<size_t>(args.repeat));
  for (int run = 0; run < args.repeat; ++run) {
    const auto start = std::chrono::steady_clock::now();
    geometry::MeshContainer container;
    std::string message;
    const geometry::SplitStatus setStatus = container.setMesh(mesh, &message);
    if (setStatus != geometry::SplitStatus::Ok) {
      std::fprintf(stderr, "cleave-split: %s: invalid mesh: %s\n", args.input.c_str(),
                   message.empty() ? geometry::toString(setStatus) : message.c_str());
      return kExitData;
    }
    container.setTransform(glm::mat4(1.f));
    const auto setUp = std::chrono::steady_clock::now();
    splitter->split(container, plane, options, result);
    const auto end = std::chrono::steady_clock::now();
    times.push_back(std::chrono::duration<double, std::milli>(end - start).count());
    setupTimes.push_back(std::chrono::duration<double, std::milli>(setUp - start).count());
    cutTimes.push_back(std::chrono::duration<double, std::milli>(end - setUp).count());
    if (result.status != geometry::SplitStatus::Ok) break;
  }
  const bool splitOk = result.status == geometry::SplitStatus::Ok;

  // Files per piece.
  std::vector<std::string> written;
  if (splitOk && args.outDir) {
    std::error_code ec;
    std::filesystem::create_directories(*args.outDir, ec);
    if (ec) {
      std::fprintf(stderr, "cleave-split: %s: cannot create the output folder (%s)\n",
                   args.outDir->c_str(), ec.message().c_str());
      return kExitData;
    }
    assets::MeshWriteOptions writeOptions;
    writeOptions.capMaterialId = capMaterialId;
    writeOptions.materialNames = loaded.materialNames;
    for (size_t k = 0; k < result.pieces.size(); ++k) {
      const geometry::SplitPiece& piece = result.pieces[k];
      const std::string file = "piece_" + std::to_string(k) + (piece.side > 0 ? "_above." : "_below.") +
                               args.format;
      const std::string path = (std::filesystem::path(*args.outDir) / file).string();
      const assets::MeshWriteResult w = args.format == "glb"
                                            ? assets::writeGlb(path, piece.mesh, writeOptions)
                                            : assets::writeObj(path, piece.mesh, writeOptions);
      if (!w.ok) {
        std::fprintf(stderr, "cleave-split: %s\n", w.error.c_str());
        return kExitData;
      }
      written.push_back(path);
    }
  }

  const double medianMs = median(times);
  const double minMs = times.empty() ? 0.0 : *std::min_element(times.begin(), times.end());
  if (args.json) {
    nlohmann::ordered_json out;
    out["input"] = {{"file", args.input},
                    {"vertices", mesh.vertexCount()},
                    {"triangles", mesh.triangleCount()},
                    {"closed", inputClosed},
                    {"volume", inputMass.volume}};
    out["plane"] = {{"normal", {plane.normal.x, plane.normal.y, plane.normal.z}},
                    {"offset", plane.offset}};
    out["status"] = geometry::toString(result.status);
    if (!splitOk) out["message"] = result.message;
    out["section_loops"] = result.sectionLoops;
    nlohmann::ordered_json pieces = nlohmann::ordered_json::array();
    for (const geometry::SplitPiece& piece : result.pieces) {
      nlohmann::ordered_json p;
      p["side"] = piece.side > 0 ? "above" : "below";
      p["triangles"] = piece.mesh.triangleCount();
      p["cap_triangles"] = piece.capTriangles;
      p["cap_loops"] = piece.capLoops;
      p["closed"] = piece.mass.closed;
      const nlohmann::ordered_json mass = massJson(piece.mass);
      for (const auto& [key, value] : mass.items()) p[key] = value;
      pieces.push_back(std::move(p));
    }
    out["pieces"] = std::move(pieces);
    if (!written.empty()) out["files"] = written;
    out["timing"] = {{"repeat", times.size()},          {"split_ms_median", medianMs},
                     {"split_ms_min", minMs},             {"setup_ms_median", median(setupTimes)},
                     {"cut_ms_median", median(cutTimes)}};
    std::puts(out.dump(2).c_str());
  } else {
    std::printf("%s: %zu vertices, %zu triangles, %s, volume %.9g\n", args.input.c_str(),
                mesh.vertexCount(), mesh.triangleCount(), inputClosed ? "closed" : "open",
                inputMass.volume);
    std::printf("plane: normal (%.9g, %.9g, %.9g), offset %.9g\n", plane.normal.x, plane.normal.y,
                plane.normal.z, plane.offset);
    std::printf("status: %s%s%s\n", geometry::toString(result.status), splitOk ? "" : ": ",
                splitOk ? "" : result.message.c_str());
    double total = 0.0;
    for (size_t k = 0; k < result.pieces.size(); ++k) {
      const geometry::SplitPiece& piece = result.pieces[k];
      total += piece.mass.volume;
      std::printf("piece %zu %s: %zu triangles (%u cap, %u loops), %s, volume %.9g, "
                  "centre (%.6g, %.6g, %.6g)\n",
                  k, piece.side > 0 ? "above" : "below", piece.mesh.triangleCount(),
                  piece.capTriangles, piece.capLoops, piece.mass.closed ? "closed" : "open",
                  piece.mass.volume, piece.mass.centerOfMass.x, piece.mass.centerOfMass.y,
                  piece.mass.centerOfMass.z);
    }
    if (splitOk) std::printf("pieces volume total %.9g\n", total);
    for (const std::string& path : written) std::printf("wrote %s\n", path.c_str());
    std::printf("split time: median %.3f ms, min %.3f ms over %zu run%s\n", medianMs, minMs,
                times.size(), times.size() == 1 ? "" : "s");
  }
  if (!splitOk) {
    std::fprintf(stderr, "cleave-split: %s: split failed: %s%s%s\n", args.input.c_str(),
                 geometry::toString(result.status), result.message.empty() ? "" : ": ",
                 result.message.c_str());
    return kExitData;
  }
  return 0;
}
