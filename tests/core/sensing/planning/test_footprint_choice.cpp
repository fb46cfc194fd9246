// footprint_variance_reduction: a hand-made case where it and Eq. 10 differ
// and the footprint-aware cell is provably better (a refit with the press's
// points leaves less variance over the workspace than the press at Eq. 10's
// cell, and less than a press at any other cell), its low-rank update
// against that refit, the guards that keep bad models from choosing, and the
// space-filling first batch.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "touchcloud/error.hpp"
#include "touchcloud/gp/exact_gp.hpp"
#include "touchcloud/gp/gp_surface_model.hpp"
#include "touchcloud/planning/footprint_choice.hpp"
#include "touchcloud/planning/space_filling.hpp"
#include "touchcloud/planning/touch_choice.hpp"

using namespace touchcloud;
using namespace touchcloud::planning;

namespace {

// 8 x 8 cells of 10 mm over [0, 80]^2.
WorkspaceGrid grid_8x8() {
  WorkspaceGrid g;
  g.x_mm = {0, 80};
  g.y_mm = {0, 80};
  g.cells_x = g.cells_y = 8;
  return g;
}

const gp::Hyperparameters kFlat{1.0, 6.0, 1e-4};  // signal 1 mm^2, lengthscale 6 mm

// A flat object (z = 10 mm everywhere) touched on a 5 mm lattice, except
//  - corner A: no point within 9.9 mm of the corner cell's centre (5, 5);
//    that one cell is 10 mm from the nearest data: variance ~0.85 mm^2, the
//    largest anywhere, so Eq. 10 goes there; its press covers only it and
//    three well-known neighbours;
//  - square B = (20, 70)^2: points only at the cell corners (multiples of
//    10 mm), so its 25 cells are 7.1 mm from data: ~0.3-0.4 mm^2 each, less
//    than A's peak, but a 3 x 3 block of them under one press.
struct FlatScene {
  Eigen::MatrixX2d xy{0, 2};
  Eigen::VectorXd z;
};

FlatScene flat_scene() {
  std::vector<Eigen::Vector2d> kept;
  for (int i = 0; i <= 16; ++i)
    for (int j = 0; j <= 16; ++j) {
      const Eigen::Vector2d p(5.0 * i, 5.0 * j);
      if ((p - Eigen::Vector2d(5, 5)).norm() < 9.9) continue;
      const bool in_b = p.x() > 20 && p.x() < 70 && p.y() > 20 && p.y() < 70;
      if (in_b && (i % 2 != 0 || j % 2 != 0)) continue;
      kept.push_back(p);
    }
  FlatScene s;
  s.xy.resize(static_cast<Eigen::Index>(kept.size()), 2);
  for (std::size_t k = 0; k < kept.size(); ++k) s.xy.row(static_cast<Eigen::Index>(k)) = kept[k].transpose();
  s.z = Eigen::VectorXd::Constant(s.xy.rows(), 10.0);
  return s;
}

std::shared_ptr<gp::ExactGp> fit(const Eigen::MatrixX2d& xy, const Eigen::VectorXd& z) {
  auto gp = std::make_shared<gp::ExactGp>(gp::KernelKind::rbf, kFlat);
  gp->fit(xy, z);
  return gp;
}

// On a flat surface the dome of radius R, pressed d past first contact,
// touches a disc of radius sqrt(2 R d - d^2): 18.1 mm for the Palm 2.0's
// R = 32.5 mm and d = 5.5 mm. The cell centres within it, worked out here
// without the code under test.
std::vector<int> flat_contact_cells(const WorkspaceGrid& g, int cell, const PressFootprint& press) {
  const double r = press.gel_radius_mm, d = press.press_depth_mm, a = std::sqrt(2 * r * d - d * d);
  std::vector<int> out;
  for (int c = 0; c < g.cells(); ++c)
    if ((g.cell_centre_mm(c) - g.cell_centre_mm(cell)).norm() < a) out.push_back(c);
  return out;
}

// Mean variance over the cell centres after a refit with the press's points
// (z = 10 mm, the flat surface) added to the data: what the press really
// leaves, computed without the low-rank update.
double mean_variance_after_press(const FlatScene& s, const WorkspaceGrid& g, int cell, const PressFootprint& press) {
  const std::vector<int> touched = flat_contact_cells(g, cell, press);
  Eigen::MatrixX2d xy(s.xy.rows() + static_cast<Eigen::Index>(touched.size()), 2);
  xy.topRows(s.xy.rows()) = s.xy;
  for (std::size_t k = 0; k < touched.size(); ++k)
    xy.row(s.xy.rows() + static_cast<Eigen::Index>(k)) = g.cell_centre_mm(touched[k]).transpose();
  const Eigen::VectorXd z = Eigen::VectorXd::Constant(xy.rows(), 10.0);
  return fit(xy, z)->variance(g.cell_centres_mm()).mean();
}

}  // namespace

TEST(FootprintChoice, DiffersFromEq10AndLeavesLessVarianceThanAnyOtherPress) {
  const FlatScene s = flat_scene();
  const WorkspaceGrid g = grid_8x8();
  const gp::GpSurfaceModel model(fit(s.xy, s.z), std::nullopt);
  const PressFootprint press;  // 65 mm gel, 5.5 mm past first contact

  const VarianceChoice eq10 = max_variance_cell(model, g, 1);
  ASSERT_EQ(eq10.cell, 0) << "the corner cell A has the greatest variance";
  const FootprintChoice choice = footprint_variance_reduction_cell(model, g, press);
  EXPECT_NE(choice.cell, eq10.cell);
  EXPECT_LT(choice.variance_mm2, eq10.variance_mm2) << "it does not press where the variance peaks";
  EXPECT_EQ(choice.footprint_points, 9) << "a 3 x 3 block of cell centres within 18.1 mm";

  // Provably better: the refit after each possible press.
  std::vector<double> left(static_cast<std::size_t>(g.cells()));
  for (int c = 0; c < g.cells(); ++c) left[static_cast<std::size_t>(c)] = mean_variance_after_press(s, g, c, press);
  const double chosen = left[static_cast<std::size_t>(choice.cell)];
  EXPECT_LT(chosen, 0.9 * left[static_cast<std::size_t>(eq10.cell)])
      << "Eq. 10's press leaves " << left[static_cast<std::size_t>(eq10.cell)] << " mm^2, this one " << chosen;
  for (int c = 0; c < g.cells(); ++c) EXPECT_LE(chosen, left[static_cast<std::size_t>(c)] + 1e-12) << "cell " << c;
  // The low-rank update predicts the refit.
  EXPECT_NEAR(choice.expected_mean_variance_mm2, chosen, 1e-9 * chosen);
  EXPECT_NEAR(choice.mean_variance_mm2, model.variance(g.cell_centres_mm()).mean(), 1e-12);
  // The contact model agrees with the hand-worked disc on a flat surface.
  const Eigen::MatrixX2d centres = g.cell_centres_mm();
  const Eigen::VectorXd mean = model.mean(centres);
  for (int c : {0, 27, 63}) {
    const std::vector<Eigen::Index> f = likely_contact(centres, mean, g.cell_centre_mm(c), press);
    const std::vector<int> expected = flat_contact_cells(g, c, press);
    EXPECT_EQ(std::vector<int>(f.begin(), f.end()), expected) << "cell " << c;
  }
}

TEST(FootprintChoice, ThePressTouchesOnlyWhatTheDomeReachesOnARelief) {
  // Cell centres on a line, 10 mm apart; a 20 mm tall block under the 3rd.
  // Lowered over the 2nd, the dome first meets the block's top and goes
  // 5.5 mm further: it cannot reach the floor 20 mm below within 32.5 mm.
  Eigen::MatrixX2d centres(5, 2);
  Eigen::VectorXd mean(5);
  for (int i = 0; i < 5; ++i) centres.row(i) << 10.0 * i, 0.0;
  mean << 0, 0, 20, 0, 0;
  const PressFootprint press;
  EXPECT_EQ(likely_contact(centres, mean, Eigen::Vector2d(10, 0), press), (std::vector<Eigen::Index>{2}));
  mean[2] = 2.0;  // a low step: the dome covers it and the floor beside it
  EXPECT_EQ(likely_contact(centres, mean, Eigen::Vector2d(10, 0), press), (std::vector<Eigen::Index>{0, 1, 2}));
}

namespace {
// A model given by its covariance function (mean 0).
class CovarianceField final : public SurfaceModel {
 public:
  using Field = std::function<double(const Eigen::Vector2d&, const Eigen::Vector2d&)>;
  explicit CovarianceField(Field f, bool has_covariance = true) : f_(std::move(f)), has_(has_covariance) {}
  std::size_t training_size() const override { return 0; }
  Eigen::VectorXd mean(const Eigen::MatrixX2d& xy) const override { return Eigen::VectorXd::Zero(xy.rows()); }
  Eigen::VectorXd variance(const Eigen::MatrixX2d& xy) const override { return covariance_of(xy).diagonal(); }
  std::optional<Eigen::MatrixXd> covariance(const Eigen::MatrixX2d& xy) const override {
    if (!has_) return std::nullopt;
    return covariance_of(xy);
  }
  std::optional<double> noise_variance_mm2() const override { return 0.01; }
  std::map<std::string, double> hyperparameters() const override { return {}; }

 private:
  Eigen::MatrixXd covariance_of(const Eigen::MatrixX2d& xy) const {
    Eigen::MatrixXd s(xy.rows(), xy.rows());
    for (Eigen::Index i = 0; i < xy.rows(); ++i)
      for (Eigen::Index j = 0; j < xy.rows(); ++j) s(i, j) = f_(xy.row(i).transpose(), xy.row(j).transpose());
    return s;
  }
  Field f_;
  bool has_;
};

double rbf(const Eigen::Vector2d& a, const Eigen::Vector2d& b) { return std::exp(-(a - b).squaredNorm() / 200.0); }
}  // namespace

TEST(FootprintChoice, NoNaNOrNegativeVarianceEverReachesTheChoice) {
  const WorkspaceGrid g = grid_8x8();
  const PressFootprint press;
  // A NaN covariance between two cells far from the diagonal.
  const CovarianceField nan([](const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
    return a.x() > 70 && b.y() > 70 && a != b ? std::nan("") : rbf(a, b);
  });
  EXPECT_THROW(footprint_variance_reduction_cell(nan, g, press), RunError);
  // A negative variance at one cell.
  const CovarianceField negative([](const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
    return a == b && a.x() > 70 && a.y() > 70 ? -1e-9 : rbf(a, b);
  });
  try {
    footprint_variance_reduction_cell(negative, g, press);
    FAIL() << "a negative variance chose a touch";
  } catch (const RunError& e) {
    EXPECT_NE(std::string(e.what()).find("variance -1e-09 mm^2 at (75, 75) mm"), std::string::npos) << e.what();
  }
  // A model that gives no covariance is refused, not guessed at.
  const CovarianceField none(rbf, false);
  try {
    footprint_variance_reduction_cell(none, g, press);
    FAIL() << "a model without covariance chose a touch";
  } catch (const RunError& e) {
    EXPECT_NE(std::string(e.what()).find("no posterior covariance"), std::string::npos) << e.what();
  }
  // The healthy field chooses, and what it expects to leave is finite, >= 0
  // and below what there is now.
  const FootprintChoice ok = footprint_variance_reduction_cell(CovarianceField(rbf), g, press);
  EXPECT_TRUE(ok.cell >= 0 && ok.cell < g.cells());
  EXPECT_TRUE(std::isfinite(ok.expected_mean_variance_mm2));
  EXPECT_GE(ok.expected_mean_variance_mm2, 0.0);
  EXPECT_LT(ok.expected_mean_variance_mm2, ok.mean_variance_mm2);
}

TEST(FootprintChoice, AnEmptyOrOneCellWorkspaceIsAClearError) {
  const CovarianceField field(rbf);
  std::mt19937_64 rng(1);
  WorkspaceGrid one = grid_8x8();
  one.cells_x = one.cells_y = 1;
  WorkspaceGrid empty = grid_8x8();
  empty.x_mm = {10, 10};
  for (const WorkspaceGrid& g : {one, empty}) {
    EXPECT_THROW(footprint_variance_reduction_cell(field, g, PressFootprint{}), InputError);
    EXPECT_THROW(max_variance_cell(field, g, 1), InputError);
    EXPECT_THROW(random_cell(g, {}, rng), InputError);
    EXPECT_THROW(space_filling_cells(g, 4, rng), InputError);
  }
  try {
    check_choice_grid(one);
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("1 x 1 cells: choosing a touch needs at least 2 cells"), std::string::npos)
        << e.what();
  }
  try {
    check_choice_grid(empty);
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("the workspace is empty"), std::string::npos) << e.what();
  }
}

TEST(SpaceFilling, FourTouchesOneInEachQuadrantFixedByTheSeed) {
  WorkspaceGrid g;
  g.x_mm = {-60, 60};
  g.y_mm = {-60, 60};
  g.cells_x = g.cells_y = 14;  // the fox mask's grid
  for (std::uint64_t seed : {1u, 2u, 3u}) {
    std::mt19937_64 a(seed), b(seed);
    const std::vector<int> design = space_filling_cells(g, 4, a);
    EXPECT_EQ(design, space_filling_cells(g, 4, b)) << "seed " << seed;
    ASSERT_EQ(design.size(), 4u);
    std::set<int> quadrants;
    for (int c : design) {
      const Eigen::Vector2d p = g.cell_centre_mm(c);
      // k-means of a square into 4: the quadrants' centres, (+-30, +-30) mm,
      // snapped to the nearest cell centre (4.3 mm away at most).
      EXPECT_NEAR(std::abs(p.x()), 30.0, 4.3) << c;
      EXPECT_NEAR(std::abs(p.y()), 30.0, 4.3) << c;
      quadrants.insert((p.x() > 0 ? 1 : 0) + (p.y() > 0 ? 2 : 0));
    }
    EXPECT_EQ(quadrants.size(), 4u) << "seed " << seed;
  }
  std::mt19937_64 rng(5);
  const std::vector<int> all = space_filling_cells(grid_8x8(), 100, rng);
  EXPECT_EQ(std::set<int>(all.begin(), all.end()).size(), 64u) << "more touches than cells: every cell once";
}
