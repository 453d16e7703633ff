// SPDX-License-Identifier: MIT
// The cap triangulator on a fixture corpus of real section polygons (tests/geometry/data/caps, see
// cap_fixtures.h), each with the triangle count and area deviation recorded when it was written,
// and on the sections of the generated meshes cut here and now. Every polygon that ever failed is
// kept as a fixture. CLEAVE_WRITE_CAP_FIXTURES=<folder> writes the sections of the generated meshes
// there as fixtures (how the recorded ones were made).
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>

#include "cleave/geometry/mesh_splitter.h"
#include "cleave/geometry/primitives.h"
#include "tests/geometry/cap_fixtures.h"
#include "tests/geometry/test_meshes.h"

namespace cleave::geometry {
namespace {

namespace fs = std::filesystem;
namespace prim = primitives;

const fs::path kFixtures = fs::path(CLEAVE_SOURCE_DIR) / "tests" / "geometry" / "data" / "caps";

// What a triangulation must be: done, with every ring edge in a triangle and no triangle without
// area, and (for a recorded fixture) as many triangles as recorded, the area as close.
::testing::AssertionResult clean(const testing::CapFixture& f, const testing::Triangulated& t, bool recorded) {
  auto failure = [&] { return ::testing::AssertionFailure() << f.name << ": "; };
  if (!t.ok) return failure() << "the triangulation failed";
  if (t.ringEdgesMissing > 0) return failure() << t.ringEdgesMissing << " ring edge(s) in no triangle";
  if (t.flat > 0) return failure() << t.flat << " triangle(s) without area";
  if (recorded && t.triangles != f.triangles) return failure() << t.triangles << " triangles, recorded " << f.triangles;
  const double allowed = recorded ? std::max(2.0 * f.deviation, 1e-14) : 1e-9;
  if (t.deviation > allowed) return failure() << "area deviation " << t.deviation << ", allowed " << allowed;
  return ::testing::AssertionSuccess();
}

TEST(CapFixtures, RecordedSectionPolygonsTriangulateAsRecorded) {
  std::vector<fs::path> files;
  for (const auto& entry : fs::directory_iterator(kFixtures)) {
    if (entry.path().extension() == ".txt") files.push_back(entry.path());
  }
  std::sort(files.begin(), files.end());
  ASSERT_GE(files.size(), 10u) << "the fixture corpus is missing from " << kFixtures;
  size_t holes = 0, points = 0;
  for (const fs::path& file : files) {
    testing::CapFixture f;
    f.name = file.filename().string();
    const std::string error = testing::readFixture(file.string(), f);
    ASSERT_EQ(error, "");
    holes += f.rings.size() - 1;
    for (const auto& ring : f.rings) points += ring.size();
    EXPECT_TRUE(clean(f, testing::triangulateFixture(f), true));
  }
  std::printf("[ fixtures ] %zu recorded cap polygons, %zu points, %zu holes\n", files.size(), points, holes);
}

// The meshes and planes the fixtures come from: sections with holes, many points, nearly collinear
// runs (the comb's spine, where the cap once had slivers), and nested rings.
struct Source {
  std::string name;
  MeshData mesh;
  std::vector<Plane> planes;
  std::string note;  // of the first planes, for the fixture's comment
};

std::vector<Source> sources() {
  std::vector<Source> out;
  out.push_back({"comb16", prim::combPrism(16),
                 {{{-0.07785878809401009, 0.45207639629532809, 0.88857466823512454}, 0.082036273283756553},
                  {{-0.080286286891327246, 0.68327515729270671, -0.7257335403326971}, 0.12906667705542588},
                  {{0, 1, 0}, 0.5},
                  {{0, 0, 1}, 0.02}},
                 "planes 0 and 1 once gave cap triangles along the spine that were flat in float"});
  out.push_back({"star7", prim::starPrism(7), {{{0, 1, 0}, 0.1}, {{0.2, 1, 0.1}, 0.05}}, ""});
  out.push_back({"torus", prim::torus(1.f, 0.3f, 48, 16), {{{0, 1, 0}, 0.05}, {{1, 0, 0}, 0.0}, {{0.3, 1, 0.2}, 0.1}}, ""});
  out.push_back({"hollowSphere", prim::hollowSphere(1.f, 0.6f, 32, 16), {{{0, 1, 0}, 0.05}, {{1, 1, 0}, 0.2}}, ""});
  out.push_back({"nestedShells3", prim::nestedShells(3, 1.f, 32, 16), {{{0, 1, 0}, 0.03}}, ""});
  MeshData grid;  // a 4 x 4 grid of tori side by side: one cap of many holes
  for (int i = 0; i < 16; ++i) {
    MeshData t = prim::torus(0.4f, 0.15f, 32, 12);
    prim::transform(t, glm::translate(glm::mat4(1.f), glm::vec3(float(i % 4), 0.f, float(i / 4))));
    grid = grid.positions.empty() ? std::move(t) : prim::merge(grid, t);
  }
  out.push_back({"toriGrid", std::move(grid), {{{0, 1, 0}, 0.02}}, ""});
  return out;
}

TEST(CapFixtures, SectionsOfGeneratedMeshesTriangulateCleanly) {
  const char* writeTo = std::getenv("CLEAVE_WRITE_CAP_FIXTURES");
  size_t polygons = 0;
  for (const Source& source : sources()) {
    for (size_t k = 0; k < source.planes.size(); ++k) {
      const SplitResult result = splitMesh(source.mesh, glm::mat4(1.f), source.planes[k], SplitOptions{});
      ASSERT_EQ(result.status, SplitStatus::Ok) << source.name << " plane " << k << ": " << result.message;
      std::vector<testing::CapFixture> found = testing::capPolygonsOf(result, source.planes[k]);
      EXPECT_FALSE(found.empty()) << source.name << " plane " << k;
      for (size_t p = 0; p < found.size(); ++p) {
        testing::CapFixture& f = found[p];
        f.name = source.name + "_plane" + std::to_string(k) + "_cap" + std::to_string(p);
        f.tolerance = 4.0 * 0x1.0p-24 * 2.0;  // four float steps of the meshes' size, as the splitter's
        const testing::Triangulated t = testing::triangulateFixture(f);
        EXPECT_TRUE(clean(f, t, false));
        ++polygons;
        if (!writeTo) continue;
        f.triangles = t.triangles;
        f.deviation = t.deviation;
        char plane[160];
        std::snprintf(plane, sizeof plane, "dot((%.17g, %.17g, %.17g), x) = %.17g", source.planes[k].normal.x,
                      source.planes[k].normal.y, source.planes[k].normal.z, source.planes[k].offset);
        f.comment = "a cap of " + source.name + " cut by the plane " + plane;
        if (k < 2 && !source.note.empty()) f.comment += "; " + source.note;
        EXPECT_TRUE(testing::writeFixture((fs::path(writeTo) / (f.name + ".txt")).string(), f));
      }
    }
  }
  std::printf("[ fixtures ] %zu cap polygons of generated meshes\n", polygons);
}

TEST(CapFixtures, MalformedFixturesAreReportedWithTheirLine) {
  const fs::path path = fs::temp_directory_path() / "cleave_bad_fixture.txt";
  {
    std::ofstream out(path);
    out << "# bad\ntolerance 1e-9\nring 3\n0 0\n1 0\n";
  }
  testing::CapFixture f;
  const std::string error = testing::readFixture(path.string(), f);
  EXPECT_NE(error.find(path.string() + ":"), std::string::npos) << error;
  fs::remove(path);
}

}  // namespace
}  // namespace cleave::geometry
