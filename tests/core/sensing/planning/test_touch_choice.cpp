// Eq. 10 on a surface whose variance peak is known, the random baseline, and
// the guard that keeps bad variances from choosing a touch.
#include <gtest/gtest.h>

#include <cmath>
#include <set>

#include "touchcloud/error.hpp"
#include "touchcloud/planning/touch_choice.hpp"

using namespace touchcloud;
using namespace touchcloud::planning;

namespace {
// Variance = a field given per candidate by a function.
class FieldSurface final : public SurfaceModel {
 public:
  explicit FieldSurface(std::function<double(double, double)> v) : v_(std::move(v)) {}
  std::size_t training_size() const override { return 0; }
  Eigen::VectorXd mean(const Eigen::MatrixX2d& xy) const override { return Eigen::VectorXd::Zero(xy.rows()); }
  Eigen::VectorXd variance(const Eigen::MatrixX2d& xy) const override {
    Eigen::VectorXd out(xy.rows());
    for (Eigen::Index i = 0; i < xy.rows(); ++i) out[i] = v_(xy(i, 0), xy(i, 1));
    return out;
  }
  std::map<std::string, double> hyperparameters() const override { return {}; }

 private:
  std::function<double(double, double)> v_;
};

WorkspaceGrid grid_10mm() {
  WorkspaceGrid g;
  g.x_mm = {0, 100};
  g.y_mm = {0, 50};
  g.cells_x = 10;
  g.cells_y = 5;
  return g;
}
}  // namespace

TEST(TouchChoice, ChoosesTheCellOfGreatestVariance) {
  // A bump of variance centred at (73, 28): the cell whose centre is (75, 25).
  FieldSurface s([](double x, double y) { return std::exp(-((x - 73) * (x - 73) + (y - 28) * (y - 28)) / 50.0); });
  const VarianceChoice c = max_variance_cell(s, grid_10mm(), 1);
  EXPECT_EQ(c.cell, 2 * 10 + 7);
  // Oversampled candidates find the peak more finely, then snap to its cell.
  EXPECT_EQ(max_variance_cell(s, grid_10mm(), 4).cell, 2 * 10 + 7);
  EXPECT_GT(max_variance_cell(s, grid_10mm(), 4).variance_mm2, c.variance_mm2);
}

TEST(TouchChoice, TouchedCellsAreSkippedUntilAllAreTouched) {
  // x + 2y: 185 at cell 49 (95, 45), then 175 at cell 48 (85, 45).
  FieldSurface s([](double x, double y) { return x + 2 * y; });
  const WorkspaceGrid g = grid_10mm();
  EXPECT_EQ(max_variance_cell(s, g, 1).cell, 49);
  EXPECT_EQ(max_variance_cell(s, g, 1, {49}).cell, 48);
  std::set<int> all;
  for (int c = 0; c < g.cells(); ++c) all.insert(c);
  EXPECT_EQ(max_variance_cell(s, g, 1, all).cell, 49) << "with every cell touched, revisit the best";
}

TEST(TouchChoice, NegativeOrNaNVarianceNeverChoosesATouch) {
  FieldSurface negative([](double x, double) { return x > 50 ? -1e-9 : 1.0; });
  EXPECT_THROW(max_variance_cell(negative, grid_10mm(), 1), RunError);
  FieldSurface nan([](double, double y) { return y > 40 ? std::nan("") : 1.0; });
  EXPECT_THROW(max_variance_cell(nan, grid_10mm(), 1), RunError);
}

TEST(TouchChoice, RandomCellsDoNotRepeatUntilAllAreUsed) {
  const WorkspaceGrid g = grid_10mm();
  std::mt19937_64 rng(3);
  std::set<int> used;
  for (int i = 0; i < g.cells(); ++i) {
    const int c = random_cell(g, used, rng);
    EXPECT_FALSE(used.count(c));
    used.insert(c);
  }
  EXPECT_EQ(static_cast<int>(used.size()), g.cells());
  const int again = random_cell(g, used, rng);
  EXPECT_TRUE(again >= 0 && again < g.cells());
}
