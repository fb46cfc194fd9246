// touchcloud-make-scene: a user's mesh in metres becomes a scene whose object
// sits centred on the table in mm, and is the ground truth of the object as
// placed (no sparse sampled copy beside it); what does not fit (the unit, the gel's reach) is said, and bad input is
// exit 2 with nothing written. apex_gap_mm is the reach check under it.
#include "cloud_files.hpp"
#include "touchcloud/scoring/ground_truth.hpp"
#include "touchcloud/simulation/objects/reach_check.hpp"
#include "touchcloud/simulation/scene/scene.hpp"
#include "sim_fixture.hpp"

using namespace touchcloud;
namespace fs = std::filesystem;

namespace {
test::CliResult make_scene(const std::vector<std::string>& args) {
  return test::run_program(test::binary_dir() / "bin" / "touchcloud-make-scene", args);
}
}  // namespace

TEST(ReachCheck, TheGelCannotReachTheTableInARingsHoleButReachesItsTop) {
  test::TempDir dir;
  test::write_file(dir / "ring.obj", test::ring_obj());
  simulation::ObjectSpec spec;
  spec.kind = simulation::ObjectKind::Mesh;
  spec.mesh = dir / "ring.obj";
  const auto ring = simulation::make_object_surface(spec);
  // In the hole the dome rests on the 20 mm rim: sag(20) = 32.5 - sqrt(32.5^2 - 20^2) = 6.88 mm below its top.
  EXPECT_NEAR(simulation::apex_gap_mm(*ring, {0, 0}, 32.5), 50 - 6.88, 0.3);
  EXPECT_NEAR(simulation::apex_gap_mm(*ring, {30, 0}, 32.5), 0.0, 1e-9);
}

TEST(MakeScene, AMeshInMetresBecomesACentredSceneThatIsItsGroundTruthAndTheReachIsChecked) {
  test::TempDir dir;
  test::write_file(dir / "ring.obj", test::ring_obj(0.001));
  const auto r = make_scene({(dir / "ring.obj").string(), "--name", "ring", "--scale", "1000", "--out",
                             (dir / "objects").string()});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("object 80 x 80 x 50 mm, grid 10 x 10"), std::string::npos) << r.out;
  EXPECT_NE(r.err.find("cannot be reached by the gel"), std::string::npos) << r.err;
  EXPECT_EQ(r.err.find("is the mesh in metres"), std::string::npos) << r.err;

  const simulation::Scene scene = simulation::load_scene(dir / "objects/ring/scene.yaml");
  EXPECT_EQ(scene.name, "ring");
  EXPECT_EQ(scene.object.scale, 1000);
  EXPECT_EQ(scene.workspace.cells_x, 10);
  // The scene is the ground truth, sampled as densely as the chamfer stage samples it.
  EXPECT_FALSE(fs::exists(dir / "objects/ring/ground_truth.pcd"));
  const scoring::GroundTruth truth = scoring::load_ground_truth(dir / "objects/ring/scene.yaml");
  ASSERT_GE(truth.points.size(), scoring::kMinMeshSamples);
  EXPECT_NEAR(truth.sample_spacing_mm(), 0.1, 1e-3);
  for (const auto& p : truth.points.points()) {
    ASSERT_LE(std::hypot(p.x(), p.y()), 40.01);
    ASSERT_GE(p.z(), -1e-3);
    ASSERT_LE(p.z(), 50.01);
  }
}

TEST(MakeScene, SaysWhenTheUnitLooksWrongAndRefusesBadInputWritingNothing) {
  test::TempDir dir;
  test::write_file(dir / "ring.obj", test::ring_obj(0.001));
  const auto metres = make_scene({(dir / "ring.obj").string(), "--name", "ring", "--out", (dir / "a").string()});
  EXPECT_EQ(metres.exit_code, 0) << metres.err;
  EXPECT_NE(metres.err.find("is the mesh in metres or centimetres? (--scale 1000 or 10)"), std::string::npos)
      << metres.err;

  test::write_file(dir / "broken.stl", "solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0\n");
  const auto broken = make_scene({(dir / "broken.stl").string(), "--name", "b", "--out", (dir / "b").string()});
  EXPECT_EQ(broken.exit_code, 2);
  EXPECT_NE(broken.err.find("broken.stl"), std::string::npos) << broken.err;
  EXPECT_FALSE(fs::exists(dir / "b"));
  const auto bad_name = make_scene({(dir / "ring.obj").string(), "--name", "../x", "--out", (dir / "c").string()});
  EXPECT_EQ(bad_name.exit_code, 2);
  EXPECT_FALSE(fs::exists(dir / "c"));
}

// A cell far smaller than the object would make a grid of 10^16 cells to
// check for reach (hours): refused as a stage's grid is.
TEST(MakeScene, AGridBeyondAStagesLimitIsRefusedAtOnce) {
  test::TempDir dir;
  test::write_file(dir / "ring.obj", test::ring_obj(0.001));
  for (const std::string cell : {"1e-6", "0.05"}) {
    const auto r = make_scene({(dir / "ring.obj").string(), "--name", "ring", "--scale", "1000", "--cell-mm", cell,
                               "--out", (dir / "o").string()});
    EXPECT_EQ(r.exit_code, 2) << cell << ": " << r.err;
    EXPECT_NE(r.err.find("touchcloud-make-scene: error: --cell-mm " + cell.substr(0, cell == "1e-6" ? 1 : 4)),
              std::string::npos)
        << r.err;
    EXPECT_NE(r.err.find("over the 80 x 80 mm footprint; the grid must be in [1, 1000] cells each way (--cell-mm 0.08"),
              std::string::npos)
        << r.err;
    EXPECT_FALSE(fs::exists(dir / "o"));
  }
}

// An output folder that cannot be made is bad input with one clear line.
TEST(MakeScene, AnOutputFolderUnderAFileIsBadInput) {
  test::TempDir dir;
  test::write_file(dir / "ring.obj", test::ring_obj(0.001));
  test::write_file(dir / "file", "a regular file");
  const auto r = make_scene({(dir / "ring.obj").string(), "--name", "ring", "--scale", "1000", "--out",
                             (dir / "file/o").string()});
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("touchcloud-make-scene: error: cannot create the output folder " + (dir / "file/o/ring").string()),
            std::string::npos)
      << r.err;
  EXPECT_EQ(r.err.find("filesystem error"), std::string::npos) << r.err;
}

// --sensor writes the sensor section of each family, which its simulator
// stage takes; the reach check is for the GelStereo's dome, not a flat pad.
TEST(MakeScene, EachSensorFamilyGetsItsOwnSensorSection) {
  test::TempDir dir;
  test::write_file(dir / "ring.obj", test::ring_obj());
  const std::vector<std::pair<std::string, std::string>> families = {
      {"marker_gelstereo", "markers"}, {"colour_gelstereo", "colour_pattern"}, {"gelsight", "gelsight"}};
  for (const auto& [family, kind] : families) {
    const auto r = make_scene({(dir / "ring.obj").string(), "--name", family, "--sensor", family, "--out",
                               (dir / "objects").string()});
    ASSERT_EQ(r.exit_code, 0) << family << ": " << r.err;
    const simulation::Scene scene = simulation::load_scene(dir / "objects" / family / "scene.yaml");
    EXPECT_EQ(scene.family == sensor::SensorFamily::GelSight, family == "gelsight") << family;
    if (family != "gelsight") {
      EXPECT_EQ(scene.sensor.pattern == sensor::GelPattern::ColourPattern, family == "colour_gelstereo") << family;
    }
    EXPECT_EQ(r.err.find("cannot be reached by the gel") != std::string::npos, family != "gelsight") << r.err;
  }
  const auto bad = make_scene({(dir / "ring.obj").string(), "--name", "x", "--sensor", "digit", "--out",
                               (dir / "bad").string()});
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_FALSE(fs::exists(dir / "bad"));
}
