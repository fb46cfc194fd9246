// gpis_surface as a stage: touches of a sphere from known poses (each
// tactile cloud's pose presses along the palm's -z) go in; the cloud out is
// sampled on the zero level set and lies on the sphere; the last mesh is
// written as PLY with each vertex's variance. A first touch without a pose
// (no side known) and a run without points are refused.
#include <cmath>
#include <fstream>
#include <algorithm>
#include <map>
#include <numbers>
#include <sstream>

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include "implicit_fixtures.hpp"
#include "stage_harness.hpp"
#include "test_support.hpp"
#include "touchcloud/scoring/triangle_mesh.hpp"
#include "touchcloud/types/implicit_model.hpp"
#include "touchcloud/types/point_cloud.hpp"
#include "touchcloud/types/surface_model.hpp"
#include "touchcloud/types/tactile_cloud.hpp"

using namespace touchcloud;

namespace {

CloudConstPtr cloud_of(const gp::ImplicitTouch& t) {
  auto c = std::make_shared<PointCloud>();
  for (Eigen::Index i = 0; i < t.points_mm.rows(); ++i)
    c->push_back(pcl::PointXYZ(static_cast<float>(t.points_mm(i, 0)), static_cast<float>(t.points_mm(i, 1)),
                               static_cast<float>(t.points_mm(i, 2))));
  return c;
}

// The sensor's pose for a touch along -n, as the simulator reports it: its
// z axis points along the press, into the object (-n).
TactileCloudPtr tactile_for(const gp::ImplicitTouch& t) {
  auto tactile = std::make_shared<TactileCloud>();
  const Eigen::Vector3d n = t.normals.row(0).transpose();
  tactile->pose.base_from_sensor.linear() = Eigen::Quaterniond::FromTwoVectors(Eigen::Vector3d::UnitZ(), -n).toRotationMatrix();
  tactile->pose.base_from_sensor.translation() = t.points_mm.colwise().mean().transpose() + 10 * n;
  return tactile;
}

// Feeds each touch to the stage; the cloud after the last one.
CloudConstPtr touch_all(test::StageHarness& h, const std::vector<gp::ImplicitTouch>& touches) {
  CloudConstPtr out;
  for (const auto& t : touches)
    out = h.process_one<CloudConstPtr>({{"cloud", cloud_of(t)}, {"tactile", tactile_for(t)}}, "cloud");
  return out;
}

// The largest distance of a point of `cloud` from the sphere's surface.
double farthest_off(const PointCloud& cloud, const test::SphereObject& sphere) {
  double worst = 0;
  for (const auto& p : cloud.points)
    worst = std::max(worst, std::abs((p.getVector3fMap().cast<double>() - sphere.centre_mm).norm() - sphere.radius_mm));
  return worst;
}

class GpisSurfaceStage : public ::testing::Test {
 protected:
  test::TempDir dir_;
};

}  // namespace

TEST_F(GpisSurfaceStage, CloudOnTheSphereAndMeshWithVariance) {
  RunSettings settings;
  settings.staging_dir = dir_.path();
  settings.quiet = true;
  test::StageHarness h("gpis_surface", {{"cells", std::int64_t{24}}, {"samples", std::int64_t{2000}},
                                        {"mesh", std::string("sphere.ply")}, {"reselect_growth", 1.0}},
                       "fit", settings);
  h.configure();
  const test::SphereObject sphere;
  const CloudConstPtr out = touch_all(h, sphere.touches(40));
  h.finish();
  ASSERT_EQ(out->size(), 2000u);
  const double worst = farthest_off(*out, sphere);
  EXPECT_LT(worst, 0.5);  // the tolerance of tests/gp/test_level_set_mesh.cpp
  EXPECT_GE(h.metric("max_vertex_variance_mm2"), h.metric("mean_vertex_variance_mm2"));
  EXPECT_GE(h.metric("mean_vertex_variance_mm2"), 0.0);
  EXPECT_GT(h.metric("mesh_triangles"), 1000);

  const scoring::TriangleMesh mesh = scoring::read_triangle_mesh(dir_ / "sphere.ply");
  EXPECT_EQ(static_cast<double>(mesh.triangles.size()), h.metric("mesh_triangles"));
  std::ifstream in(dir_ / "sphere.ply", std::ios::binary);
  std::stringstream header;
  for (std::string line; std::getline(in, line) && line != "end_header";) header << line << "\n";
  EXPECT_NE(header.str().find("property float variance"), std::string::npos) << header.str();
}

TEST_F(GpisSurfaceStage, RefusesTouchesWithoutSide) {
  test::StageHarness h("gpis_surface", {});
  h.configure();
  const auto t = test::SphereObject().touches(1).front();
  // No pose: a lone patch does not say which side is outside.
  try {
    h.process({{"cloud", cloud_of(t)}}, {"cloud"});
    FAIL() << "accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("inside and outside cannot be told apart"), std::string::npos) << e.what();
  }
  try {
    h.process({{"cloud", CloudConstPtr(std::make_shared<PointCloud>())}}, {"cloud"});
    FAIL() << "accepted";
  } catch (const RunError& e) {
    EXPECT_NE(std::string(e.what()).find("no touched points yet"), std::string::npos) << e.what();
  }
}

// A ball standing on a table 10 mm below its centre, touched above the
// table only: with table_z_mm the cloud out stops at the table and the disc
// where the ball meets it (radius sqrt(20^2 - 10^2)) closes it; without, the
// model's surface goes on below the table. Touched points well below the
// table are named once.
TEST_F(GpisSurfaceStage, TheTableClosesTheObjectStandingOnItAndNothingLiesBelow) {
  const test::SphereObject sphere;
  const double table_z = sphere.centre_mm.z() - 10;
  std::vector<gp::ImplicitTouch> above;
  for (const auto& t : sphere.touches(40))
    if (t.points_mm.col(2).minCoeff() > table_z + 1) above.push_back(t);
  ASSERT_GE(above.size(), 24u);
  // The stage run over those touches; its harness holds the metrics and
  // notes, and the plugin's library the cloud's code.
  struct Fit {
    std::unique_ptr<test::StageHarness> stage;
    CloudConstPtr cloud;
  };
  const auto fit = [&](std::map<std::string, ParamValue> params) {
    params.insert({{"cells", std::int64_t{24}}, {"samples", std::int64_t{4000}}, {"reselect_growth", 1.0}});
    Fit f{std::make_unique<test::StageHarness>("gpis_surface", params, "fit"), nullptr};
    f.stage->configure();
    f.cloud = touch_all(*f.stage, above);
    f.stage->finish();
    return f;
  };
  const Fit unbounded = fit({});
  const CloudConstPtr free = unbounded.cloud;
  const auto lowest = [](const PointCloud& c) {
    float z = 1e9f;
    for (const auto& p : c.points) z = std::min(z, p.z);
    return double{z};
  };
  EXPECT_LT(lowest(*free), table_z - 2);

  const Fit standing = fit({{"table_z_mm", table_z}});
  const CloudConstPtr on_table = standing.cloud;
  EXPECT_TRUE(standing.stage->record().notes.empty());
  EXPECT_GE(lowest(*on_table), table_z - 1e-4);
  const double disc_radius = std::sqrt(20.0 * 20 - 10 * 10);
  std::size_t on_disc = 0;
  double worst_ball = 0;
  for (const auto& p : on_table->points) {
    const Eigen::Vector3d q = p.getVector3fMap().cast<double>();
    if (std::abs(q.z() - table_z) < 1e-3) {
      ++on_disc;
      EXPECT_LT(std::hypot(q.x() - sphere.centre_mm.x(), q.y() - sphere.centre_mm.y()), disc_radius + 1.0);
    } else if (q.z() > table_z + 3) {  // the last touches' points lie 1 mm or more above the table
      worst_ball = std::max(worst_ball, std::abs((q - sphere.centre_mm).norm() - sphere.radius_mm));
    }
  }
  EXPECT_LT(worst_ball, 0.5);
  // Sampled by area: the disc's share of the ball's cap above the table and the disc (pi r^2 against 2 pi R h).
  const double disc_share = disc_radius * disc_radius / (disc_radius * disc_radius + 2 * 20.0 * 30.0);
  EXPECT_NEAR(static_cast<double>(on_disc) / on_table->size(), disc_share, 0.3 * disc_share);

  const Fit too_high = fit({{"table_z_mm", sphere.centre_mm.z() + 5}});
  const auto& notes = too_high.stage->record().notes;
  ASSERT_EQ(notes.count("fit.below_table"), 1u);
  EXPECT_NE(notes.at("fit.below_table").find("below the table (table_z_mm 45)"), std::string::npos)
      << notes.at("fit.below_table");
}

// form: sparse (inducing sites 5 mm apart) meets the exact form's tolerance on the sphere.
TEST_F(GpisSurfaceStage, SparseFormOnTheSphere) {
  test::StageHarness h("gpis_surface", {{"form", std::string("sparse")}, {"inducing_spacing_mm", 5.0},
                                        {"cells", std::int64_t{24}}, {"samples", std::int64_t{2000}},
                                        {"reselect_growth", 1.0}});
  h.configure();
  const test::SphereObject sphere;
  const CloudConstPtr out = touch_all(h, sphere.touches(40));
  h.finish();
  const double worst = farthest_off(*out, sphere);
  EXPECT_LT(worst, 0.5);
  EXPECT_GE(h.metric("mean_vertex_variance_mm2"), 0.0);
}

// The exact form refuses a touch beyond exact_max_points, naming the sparse form.
TEST_F(GpisSurfaceStage, ExactRefusesBeyondItsPointCount) {
  test::StageHarness h("gpis_surface", {{"exact_max_points", std::int64_t{50}}});
  h.configure();
  const auto touches = test::SphereObject().touches(3);  // 21 training points each
  h.process({{"cloud", cloud_of(touches[0])}, {"tactile", tactile_for(touches[0])}}, {"cloud"});
  h.process({{"cloud", cloud_of(touches[1])}, {"tactile", tactile_for(touches[1])}}, {"cloud"});
  try {
    h.process({{"cloud", cloud_of(touches[2])}, {"tactile", tactile_for(touches[2])}}, {"cloud"});
    FAIL() << "accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("sparse form"), std::string::npos) << e.what();
  }
}

// form: exact_then_sparse goes on where the exact form refuses: the touch
// that would pass exact_max_points switches to the sparse form, fitted again
// to every touch, says so in a note, and gives the cloud a sparse form fed
// the same touches from the first gives.
TEST_F(GpisSurfaceStage, ExactThenSparseGoesOnInTheSparseFormBeyondTheExactPointCount) {
  const std::map<std::string, ParamValue> common{{"exact_max_points", std::int64_t{50}}, {"inducing_spacing_mm", 5.0},
                                                 {"cells", std::int64_t{24}}, {"samples", std::int64_t{500}}};
  auto switching_params = common;
  switching_params["form"] = std::string("exact_then_sparse");
  auto sparse_params = common;
  sparse_params["form"] = std::string("sparse");
  test::StageHarness switching("gpis_surface", switching_params, "fit");
  test::StageHarness sparse("gpis_surface", sparse_params, "fit");
  switching.configure();
  sparse.configure();
  const auto touches = test::SphereObject().touches(4);  // 21 training points each: the third passes 50
  CloudConstPtr a, b;
  for (std::size_t i = 0; i < touches.size(); ++i) {
    a = switching.process_one<CloudConstPtr>({{"cloud", cloud_of(touches[i])}, {"tactile", tactile_for(touches[i])}},
                                             "cloud");
    b = sparse.process_one<CloudConstPtr>({{"cloud", cloud_of(touches[i])}, {"tactile", tactile_for(touches[i])}},
                                          "cloud");
    EXPECT_EQ(switching.record().notes.count("fit.form"), i >= 2 ? 1u : 0u) << "touch " << i + 1;
  }
  EXPECT_EQ(switching.metric("training_points"), 84);
  const std::string note = switching.record().notes.at("fit.form");
  EXPECT_NE(note.find("exact form for touches 1-2 (42 training points); touch 3"), std::string::npos) << note;
  ASSERT_EQ(a->size(), b->size());
  for (std::size_t i = 0; i < a->size(); ++i)
    ASSERT_EQ(a->points[i].getVector3fMap(), b->points[i].getVector3fMap()) << "point " << i;
}

// The `surface` output is the sphere as a press from above meets it: its top
// over the sphere, the table (z = 0) beside it; the variance is lower where
// the sphere was touched than over the table far from any touch, never
// negative; and the view stays as it was while the stage takes more touches.
TEST_F(GpisSurfaceStage, SurfaceOutIsTheSphereSeenFromAboveWithItsVariance) {
  test::StageHarness h("gpis_surface", {{"cells", std::int64_t{24}}, {"samples", std::int64_t{500}},
                                        {"reselect_growth", 1.0}});
  h.configure();
  const test::SphereObject sphere;  // centre (5, -3, 40), radius 20
  const auto touches = sphere.touches(40);
  SurfaceModelPtr first;
  for (std::size_t i = 0; i < touches.size(); ++i) {
    const auto outputs =
        h.process({{"cloud", cloud_of(touches[i])}, {"tactile", tactile_for(touches[i])}}, {"cloud", "surface"});
    if (i == 30) first = std::any_cast<SurfaceModelPtr>(outputs.at("surface"));
    if (i + 1 == touches.size()) {
      const SurfaceModelPtr top = std::any_cast<SurfaceModelPtr>(outputs.at("surface"));
      Eigen::MatrixX2d xy(3, 2);
      xy << 5, -3,   // over the centre: the top at z = 60
          17, 9,     // over the sphere: z = 40 + sqrt(400 - 288)
          60, 60;    // beside it: the table
      const Eigen::VectorXd z = top->mean(xy);
      EXPECT_NEAR(z(0), 60.0, 0.3);
      EXPECT_NEAR(z(1), 40.0 + std::sqrt(112.0), 0.5);
      EXPECT_EQ(z(2), 0.0);
      const Eigen::VectorXd v = top->variance(xy);
      EXPECT_GE(v.minCoeff(), 0.0);
      EXPECT_LT(v(0), v(2));
      ASSERT_TRUE(top->data_z_range_mm());
      EXPECT_NEAR((*top->data_z_range_mm())[1], 60.0, 0.01);
      EXPECT_EQ(top->training_size(), static_cast<std::size_t>(h.metric("training_points")));
    }
  }
  // Taken after 31 touches, the first view still answers for those 31.
  ASSERT_TRUE(first);
  EXPECT_LT(first->training_size(), static_cast<std::size_t>(h.metric("training_points")));
}

// A cup's wall 4 mm thick, touched every 30 degrees outside and every 60
// degrees inside, all at 45 mm (test::CupWall, markers 2 mm apart): beside
// the inner touches the GP's mean puts the inner face into the hollow;
// surface: local_quadrics keeps it on the face. Scored on the cloud's points at the
// inner touches' height (40-50 mm) whose angle lies 10-20 degrees from an
// inner touch (0-6 mm beyond its patch): the share within 1 mm of a face.
TEST_F(GpisSurfaceStage, LocalQuadricsKeepAThinWallThinBetweenItsInnerTouches) {
  const test::CupWall wall;
  const auto on_a_face = [&](const PointCloud& cloud) {
    std::size_t near = 0, counted = 0;
    for (const auto& p : cloud.points) {
      const double deg = std::fmod(std::atan2(p.y, p.x) * 180 / std::numbers::pi + 360, 60.0);
      if (p.z < 40 || p.z > 50 || std::min(deg, 60 - deg) < 10 || std::min(deg, 60 - deg) > 20) continue;
      const double r = std::hypot(p.x, p.y);
      ++counted;
      if (std::abs(r - wall.inner_mm) < 1 || std::abs(r - wall.outer_mm) < 1) ++near;
    }
    EXPECT_GT(counted, 50u);
    return static_cast<double>(near) / static_cast<double>(std::max<std::size_t>(counted, 1));
  };
  std::map<std::string, double> share;
  for (const std::string surface : {"gp_mean", "local_quadrics"}) {
    test::StageHarness h("gpis_surface", {{"kernel", std::string("matern52")}, {"cells", std::int64_t{48}},
                                          {"samples", std::int64_t{20000}}, {"surface", surface}},
                         "fit");
    h.configure();
    const CloudConstPtr out = touch_all(h, wall.touches(2.0, 30, {45}));
    share[surface] = on_a_face(*out);
    if (surface == "local_quadrics") {
      EXPECT_GT(h.metric("quadric_patches"), 100);
    }
  }
  EXPECT_GT(share["local_quadrics"], 0.93);
  EXPECT_LT(share["gp_mean"], 0.6);
}

// plan_gaps: the planner's candidates are the cloud and the centre of every
// triangle dropped on a jump of the field; the cloud itself (what is scored)
// is the same with and without. On the cup wall touched all round outside
// and every 60 degrees inside, gaps lie in the hollow, where the inner face
// between the inner touches is not meshed.
TEST_F(GpisSurfaceStage, PlanGapsAddTheMeshsGapsToTheCandidatesOnly) {
  const test::CupWall wall;
  std::map<bool, std::vector<Eigen::Vector3f>> clouds, candidates;
  for (const bool gaps : {false, true}) {
    test::StageHarness h("gpis_surface", {{"kernel", std::string("matern52")}, {"cells", std::int64_t{32}},
                                          {"samples", std::int64_t{5000}}, {"surface", std::string("local_quadrics")},
                                          {"plan_gaps", gaps}},
                         "fit");
    h.configure();
    std::map<std::string, std::any> out;
    for (const auto& t : wall.touches(2.0, 30, {45}))
      out = h.process({{"cloud", cloud_of(t)}, {"tactile", tactile_for(t)}}, {"cloud", "candidates"});
    for (const auto& p : std::any_cast<CloudConstPtr>(out.at("cloud"))->points) clouds[gaps].push_back(p.getVector3fMap());
    for (const auto& p : std::any_cast<CloudConstPtr>(out.at("candidates"))->points)
      candidates[gaps].push_back(p.getVector3fMap());
    if (gaps) EXPECT_EQ(candidates[gaps].size(), clouds[gaps].size() + h.metric("dropped_jump_triangles"));
  }
  EXPECT_EQ(clouds[false], clouds[true]);
  EXPECT_EQ(candidates[false], clouds[false]);
  ASSERT_GT(candidates[true].size(), clouds[true].size());
  EXPECT_TRUE(std::equal(clouds[true].begin(), clouds[true].end(), candidates[true].begin()));
  std::size_t in_hollow = 0;
  for (std::size_t i = clouds[true].size(); i < candidates[true].size(); ++i) {
    const Eigen::Vector3f& p = candidates[true][i];
    if (std::hypot(p.x(), p.y()) < wall.inner_mm - 2 && p.z() > 35 && p.z() < 55) ++in_hollow;
  }
  EXPECT_GT(in_hollow, 20u);
}

TEST_F(GpisSurfaceStage, PlanGapsNeedLocalQuadrics) {
  test::StageHarness h("gpis_surface", {{"plan_gaps", true}}, "fit");
  try {
    h.configure();
    ADD_FAILURE() << "plan_gaps taken without local_quadrics";
  } catch (const ParameterError& e) {
    EXPECT_NE(std::string(e.what()).find("plan_gaps"), std::string::npos) << e.what();
  }
}

// Touches after the first without a pose: local quadrics take each one's
// side as the GP does (its patch's plane, turned away from the points
// touched so far), which on a sphere is the palm's normal: the same cloud as
// with every pose, on the sphere to within a millimetre on average.
TEST_F(GpisSurfaceStage, LocalQuadricsTakeTheSideOfATouchWithoutAPoseAsTheGpDoes) {
  const test::SphereObject sphere;
  const auto touches = sphere.touches(24);
  std::vector<PointCloud> clouds;  // copies: a cloud the plugin made must not outlive it
  for (const bool posed : {true, false}) {
    test::StageHarness h("gpis_surface", {{"cells", std::int64_t{24}}, {"samples", std::int64_t{2000}},
                                          {"reselect_growth", 1.0}, {"surface", std::string("local_quadrics")}},
                         "fit");
    h.configure();
    CloudConstPtr out;
    for (std::size_t i = 0; i < touches.size(); ++i)
      out = posed || i == 0
                ? h.process_one<CloudConstPtr>({{"cloud", cloud_of(touches[i])}, {"tactile", tactile_for(touches[i])}}, "cloud")
                : h.process_one<CloudConstPtr>({{"cloud", cloud_of(touches[i])}}, "cloud");
    clouds.push_back(*out);
  }
  ASSERT_EQ(clouds[0].size(), clouds[1].size());
  double mean_off = 0;
  for (std::size_t i = 0; i < clouds[0].size(); ++i) {
    ASSERT_EQ(clouds[0][i].getVector3fMap(), clouds[1][i].getVector3fMap()) << "point " << i;
    mean_off += std::abs((clouds[1][i].getVector3fMap().cast<double>() - sphere.centre_mm).norm() - sphere.radius_mm);
  }
  EXPECT_LT(mean_off / static_cast<double>(clouds[1].size()), 1.0);  // 24 touches: 0.53 mm
}

// swept_mm: the floor's press, from above through the cup's mouth
// (test::cup_and_floor_press), tells the GP the axis it came down is free,
// which the `implicit` output the planner reads then says: outside over the
// floor where without it the smooth field closes the mouth. Each touch adds
// twenty points, every 4 mm from the contact nearest the sensor's axis.
TEST_F(GpisSurfaceStage, SweptApproachOpensTheMouthAPressWentThrough) {
  const auto touches = test::cup_and_floor_press(3.0);
  const Eigen::MatrixX3d mouth = test::one_row({0, 0, 75});
  std::map<double, double> mean_at_mouth, training;
  for (const double swept : {0.0, 80.0}) {
    test::StageHarness h("gpis_surface", {{"cells", std::int64_t{24}}, {"samples", std::int64_t{500}},
                                          {"swept_mm", swept}});
    h.configure();
    ImplicitModelPtr model;
    for (const auto& t : touches)
      model = std::any_cast<ImplicitModelPtr>(
          h.process({{"cloud", cloud_of(t)}, {"tactile", tactile_for(t)}}, {"cloud", "implicit"}).at("implicit"));
    mean_at_mouth[swept] = model->mean(mouth)[0];
    training[swept] = h.metric("training_points");
  }
  EXPECT_LT(mean_at_mouth[0], -5);
  EXPECT_NEAR(mean_at_mouth[80], 65, 3);
  EXPECT_EQ(training[80] - training[0], 20.0 * static_cast<double>(touches.size()));
}

TEST_F(GpisSurfaceStage, SweptApproachNeedsThePressesPose) {
  test::StageHarness h("gpis_surface", {{"swept_mm", 40.0}});
  h.configure();
  const gp::ImplicitTouch t = test::SphereObject().touch({0, 0, 1});
  try {
    h.process({{"cloud", cloud_of(t)}}, {"cloud"});
    ADD_FAILURE() << "a touch without its pose taken with swept_mm";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("swept_mm needs the press's approach"), std::string::npos) << e.what();
  }
}
