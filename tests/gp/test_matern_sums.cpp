// The fused Matern 5/2 sums behind the GP mean (touchcloud/gp/matern_sums.hpp) against a
// long-double reference: every count of points around the vector widths (the
// padded or masked last step), a point at the query itself (r = 0) and one so
// far away that its exponential underflows.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "touchcloud/gp/matern_sums.hpp"

namespace touchcloud::gp {
namespace {

long double reference_sum(const Eigen::VectorXd& px, const Eigen::VectorXd& py, const Eigen::VectorXd& w, double qx,
                          double qy, double c, long double* magnitude) {
  long double sum = 0, abs_sum = 0;
  for (Eigen::Index p = 0; p < px.size(); ++p) {
    const long double dx = px[p] - static_cast<long double>(qx), dy = py[p] - static_cast<long double>(qy);
    const long double s = std::sqrt(c * (dx * dx + dy * dy));
    const long double term = w[p] * (1 + s + s * s / 3) * std::exp(-s);
    sum += term;
    abs_sum += std::fabs(term);
  }
  *magnitude = abs_sum;
  return sum;
}

// Each fused path this build and CPU run.
std::vector<SimdPath> fused_paths_here() {
  std::vector<SimdPath> paths = simd_paths_here();
  paths.erase(paths.begin());  // none
  return paths;
}

TEST(GpMaternSums, EqualALongDoubleReferenceForEveryTailLength) {
  const std::vector<SimdPath> paths = fused_paths_here();
  if (paths.empty()) GTEST_SKIP() << "no fused path in this build or on this CPU; the kernel column path serves";
  for (SimdPath path : paths) {
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> position(-40.0, 40.0), weight(-3.0, 3.0);
  const double c = 5.0 / (9.0 * 9.0);  // lengthscale 9 mm
  for (Eigen::Index n = 0; n <= 19; ++n) {
    Eigen::VectorXd px(n), py(n), w(n);
    for (Eigen::Index p = 0; p < n; ++p) px[p] = position(rng), py[p] = position(rng), w[p] = weight(rng);
    Eigen::VectorXd qx(3), qy(3);
    qx << position(rng), 0.0, 1e4;
    qy << position(rng), 0.0, 0.0;
    if (n > 2) px[n - 1] = qx[0], py[n - 1] = qy[0];  // a training point at the first query
    Eigen::VectorXd out(3);
    ASSERT_TRUE(matern52_unit_sums(px.data(), py.data(), w.data(), n, qx.data(), qy.data(), 0, 3, c, out.data(), path));
    for (Eigen::Index j = 0; j < 3; ++j) {
      long double magnitude = 0;
      const long double expected = reference_sum(px, py, w, qx[j], qy[j], c, &magnitude);
      EXPECT_LE(std::fabs(out[j] - expected), 1e-15L * (magnitude + 1e-300L)) << to_string(path) << ", n " << n << ", query " << j;
    }
    EXPECT_EQ(out[2], 0.0) << "a query 10 m away: every exponential underflows";
  }
  }
}

// One point of unit weight at distances giving s from 0 to past e^-s's
// underflow: each path's term, exponential included, within 4 ulp of the
// long-double one over the whole range, and exactly 0 once e^-s is below the
// smallest double (the AVX-512 path computes its own exp).
TEST(GpMaternSums, OneTermIsExactToAFewUlpFromZeroToUnderflow) {
  const std::vector<SimdPath> paths = fused_paths_here();
  if (paths.empty()) GTEST_SKIP() << "no fused path in this build or on this CPU";
  const double c = 1.0;  // s = r
  const double px = 0.0, py = 0.0, w = 1.0;
  for (SimdPath path : paths) {
    long double worst = 0;
    for (int i = 0; i <= 80000; ++i) {
      const double s = i * 0.01;  // 0 to 800
      double out = -1.0;
      ASSERT_TRUE(matern52_unit_sums(&px, &py, &w, 1, &s, &py, 0, 1, c, &out, path));
      const long double ls = s, expected = (1 + ls + ls * ls / 3) * std::exp(-ls);
      if (expected < 1e-300L) {
        if (expected < 4e-324L / 2) EXPECT_EQ(out, 0.0) << to_string(path) << ", s " << s;
        continue;
      }
      worst = std::max(worst, std::fabs(out - expected) / expected);
    }
    EXPECT_LE(worst, 4 * 1.1102230246251565e-16L) << to_string(path);
  }
}

// A path that cannot run (none; in a build without SLEEF, any) writes
// nothing and says so.
TEST(GpMaternSums, APathThatCannotRunWritesNothing) {
  const Eigen::VectorXd p = Eigen::VectorXd::Ones(5);
  Eigen::VectorXd out = Eigen::VectorXd::Constant(5, -1.0);
  EXPECT_FALSE(matern52_unit_sums(p.data(), p.data(), p.data(), 5, p.data(), p.data(), 0, 5, 1.0, out.data(),
                                  SimdPath::none));
  EXPECT_TRUE((out.array() == -1.0).all());
}

// Only [first, last) is written.
TEST(GpMaternSums, WriteOnlyTheQueriesAsked) {
  const Eigen::VectorXd px = Eigen::VectorXd::LinSpaced(9, -4.0, 4.0), py = Eigen::VectorXd::Zero(9);
  const Eigen::VectorXd w = Eigen::VectorXd::Ones(9), q = Eigen::VectorXd::Zero(5);
  Eigen::VectorXd out = Eigen::VectorXd::Constant(5, -1.0);
  if (fastest_simd_path() == SimdPath::none) GTEST_SKIP() << "no fused path in this build or on this CPU";
  ASSERT_TRUE(matern52_unit_sums(px.data(), py.data(), w.data(), 9, q.data(), q.data(), 1, 3, 0.5, out.data()));
  EXPECT_EQ(out[0], -1.0);
  EXPECT_GT(out[1], 1.0);  // the point at the query gives 1, the others more than 0
  EXPECT_EQ(out[1], out[2]);
  EXPECT_EQ(out[3], -1.0);
  EXPECT_EQ(out[4], -1.0);
}

// In 3-D: every count of points round the vector width (odd query counts
// too, the last query paired with itself), a point at a query and one far
// enough to underflow, against a long-double reference.
TEST(GpMaternSums, ThreeDimensionalSumsEqualALongDoubleReference) {
  if (!simd_path_runs_here(SimdPath::avx2_fma)) GTEST_SKIP() << "no fused path in this build or on this CPU";
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(-30.0, 30.0);
  const double c = 5.0 / (12.0 * 12.0);
  for (Eigen::Index n = 1; n <= 11; ++n) {
    Eigen::MatrixX3d p(n, 3), q(3, 3);
    Eigen::VectorXd w(n);
    for (Eigen::Index i = 0; i < p.size(); ++i) p.data()[i] = u(rng);
    for (Eigen::Index i = 0; i < q.size(); ++i) q.data()[i] = u(rng);
    for (Eigen::Index i = 0; i < n; ++i) w[i] = u(rng);
    q.row(1) = p.row(0);                             // r = 0
    if (n > 1) p.row(n - 1) << 1e4, 0, 0;            // e^-s underflows
    Eigen::VectorXd out(3);
    ASSERT_TRUE(matern52_unit_sums_3d(p, w, q, c, out.data()));
    for (Eigen::Index j = 0; j < 3; ++j) {
      long double sum = 0, magnitude = 0;
      for (Eigen::Index i = 0; i < n; ++i) {
        const long double s = std::sqrt(c * static_cast<long double>((p.row(i) - q.row(j)).squaredNorm()));
        const long double term = w[i] * (1 + s + s * s / 3) * std::exp(-s);
        sum += term;
        magnitude += std::fabs(term);
      }
      EXPECT_LE(std::fabs(out[j] - sum), 8 * 2.2e-16L * magnitude) << "n " << n << ", query " << j;
    }
  }
}

}  // namespace
}  // namespace touchcloud::gp
