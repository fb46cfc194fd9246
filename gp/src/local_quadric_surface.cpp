#include "touchcloud/gp/local_quadric_surface.hpp"

#include <cmath>
#include <cstdint>
#include <limits>
#include <algorithm>
#include <map>
#include <sstream>
#include <tuple>
#include <utility>

#include <Eigen/Dense>
#include <nanoflann.hpp>

#include "touchcloud/error.hpp"
#include "touchcloud/parallel_ranges.hpp"

namespace touchcloud::gp {

namespace local_quadric {  // named: LocalQuadricSurface::Impl holds these

struct Rows {
  const Eigen::MatrixX3d* m = nullptr;
  std::size_t kdtree_get_point_count() const { return static_cast<std::size_t>(m->rows()); }
  double kdtree_get_pt(std::size_t i, std::size_t dim) const {
    return (*m)(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(dim));
  }
  template <class BoundingBox>
  bool kdtree_get_bbox(BoundingBox&) const { return false; }
};

using KdTree =
    nanoflann::KDTreeSingleIndexAdaptor<nanoflann::L2_Simple_Adaptor<double, Rows, double>, Rows, 3, std::uint32_t>;
using Hits = std::vector<std::pair<std::uint32_t, double>>;  // index, squared distance

struct Tree {
  Eigen::MatrixX3d points;
  Rows rows;
  KdTree index;
  explicit Tree(Eigen::MatrixX3d p)
      : points(std::move(p)), rows{&points}, index(3, rows, nanoflann::KDTreeSingleIndexAdaptorParams(10)) {
    index.buildIndex();
  }
  Hits within(const Eigen::Vector3d& q, double radius_mm) const {
    Hits hits;
    index.radiusSearch(q.data(), radius_mm * radius_mm, hits, nanoflann::SearchParams(32, 0, false));
    return hits;
  }
};

// A quadric height w = h(u, v) over the patch's tangent frame at its centre.
struct Patch {
  Eigen::Vector3d centre, u, v, n;  // n: outward normal
  Eigen::Matrix<double, 6, 1> h;    // u^2, uv, v^2, u, v, 1
  // Distance along n from the quadric (positive outside) and across n from the centre.
  std::pair<double, double> at(const Eigen::Vector3d& p) const {
    const Eigen::Vector3d d = p - centre;
    const double a = d.dot(u), b = d.dot(v), w = d.dot(n);
    return {w - (h[0] * a * a + h[1] * a * b + h[2] * b * b + h[3] * a + h[4] * b + h[5]), std::hypot(a, b)};
  }
};

}  // namespace local_quadric

using local_quadric::Patch;
using local_quadric::Tree;

void LocalQuadricOptions::validate() const {
  auto positive = [](const char* field, double value) {
    if (!(value > 0) || !std::isfinite(value)) {
      std::ostringstream msg;
      msg << "local quadric option " << field << " = " << value << " must be finite and > 0";
      throw InputError(msg.str());
    }
  };
  positive("patch_spacing_mm", patch_spacing_mm);
  positive("fit_radius_mm", fit_radius_mm);
  positive("reach_mm", reach_mm);
  positive("free_radius_mm", free_radius_mm);
  positive("free_depth_mm", free_depth_mm);
  if (!(fit_normal_deg > 0 && fit_normal_deg < 90))
    throw InputError("local quadric option fit_normal_deg = " + std::to_string(fit_normal_deg) + " must lie in (0, 90)");
  if (normal_neighbours < 3) throw InputError("local quadric option normal_neighbours must be >= 3");
  if (min_fit_points < 6) throw InputError("local quadric option min_fit_points must be >= 6 (a quadric has six terms)");
  if (!(lateral_weight >= 0) || !std::isfinite(lateral_weight))
    throw InputError("local quadric option lateral_weight must be finite and >= 0");
  if (!(edge_deg >= 0 && edge_deg < 180))
    throw InputError("local quadric option edge_deg = " + std::to_string(edge_deg) + " must lie in [0, 180)");
  if (!(free_support_mm >= 0) || !std::isfinite(free_support_mm))
    throw InputError("local quadric option free_support_mm must be finite and >= 0");
  if (!(free_margin_mm >= 0) || !std::isfinite(free_margin_mm))
    throw InputError("local quadric option free_margin_mm must be finite and >= 0");
}

struct LocalQuadricSurface::Impl {
  LocalQuadricOptions options;
  std::vector<Patch> patches;
  std::unique_ptr<Tree> centres;
  double across_edge(const Eigen::Vector3d& p, std::uint32_t best, double d,
                     const std::vector<std::pair<std::uint32_t, double>>& reached, double cos_edge) const;
};

LocalQuadricSurface::LocalQuadricSurface(const Eigen::MatrixX3d& points_mm, const Eigen::MatrixX3d& outward,
                                         LocalQuadricOptions options)
    : impl_(std::make_unique<Impl>()) {
  options.validate();
  impl_->options = options;
  const Eigen::Index n = points_mm.rows();
  if (n == 0) throw InputError("local quadric surface: no touched points");
  if (outward.rows() != n)
    throw InputError("local quadric surface: " + std::to_string(outward.rows()) + " outward vectors for " +
                     std::to_string(n) + " points");
  if (!points_mm.allFinite() || !outward.allFinite())
    throw InputError("local quadric surface: a point or outward vector is not finite");
  const Tree points(points_mm);

  // Each point's normal: the least spread direction of its nearest points
  // touched from the same side (a touch on the other face of a thin wall,
  // a few mm away, is not its neighbourhood), turned outward.
  const auto k = static_cast<std::size_t>(options.normal_neighbours);
  const auto candidates = static_cast<std::size_t>(std::min<Eigen::Index>(3 * options.normal_neighbours, n));
  Eigen::MatrixX3d normals(n, 3);
  std::vector<std::uint32_t> index(candidates);
  std::vector<double> squared(candidates);
  for (Eigen::Index i = 0; i < n; ++i) {
    const Eigen::Vector3d p = points_mm.row(i).transpose(), side = outward.row(i).transpose();
    const std::size_t found = points.index.knnSearch(p.data(), candidates, index.data(), squared.data());
    Eigen::MatrixX3d nb(static_cast<Eigen::Index>(k), 3);
    Eigen::Index rows = 0;
    for (std::size_t j = 0; j < found && rows < nb.rows(); ++j)
      if (outward.row(index[j]).dot(side) > 0) nb.row(rows++) = points_mm.row(index[j]);
    Eigen::Vector3d normal = side;
    if (rows >= 3) {
      const Eigen::MatrixX3d c = nb.topRows(rows).rowwise() - nb.topRows(rows).colwise().mean();
      Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(c.transpose() * c);
      if (eig.eigenvalues()[1] > 1e-12) normal = eig.eigenvectors().col(0);
    }
    if (normal.dot(side) < 0) normal = -normal;
    normals.row(i) = normal.normalized().transpose();
  }

  // One patch per cube of patch_spacing_mm: its first point in the input's order.
  std::map<std::tuple<long, long, long>, Eigen::Index> cells;
  for (Eigen::Index i = 0; i < n; ++i) {
    const Eigen::Vector3d c = (points_mm.row(i) / options.patch_spacing_mm).array().floor();
    cells.emplace(std::make_tuple(static_cast<long>(c.x()), static_cast<long>(c.y()), static_cast<long>(c.z())), i);
  }
  std::vector<Eigen::Index> seeds;
  for (const auto& cell : cells) seeds.push_back(cell.second);
  std::sort(seeds.begin(), seeds.end());

  const double cos_fit = std::cos(options.fit_normal_deg * M_PI / 180.0);
  Eigen::MatrixX3d centre_rows(static_cast<Eigen::Index>(seeds.size()), 3);
  for (const Eigen::Index s : seeds) {
    Patch patch;
    patch.centre = points_mm.row(s).transpose();
    patch.n = normals.row(s).transpose();
    patch.u = patch.n.unitOrthogonal();
    patch.v = patch.n.cross(patch.u);
    std::vector<Eigen::Index> fit;
    for (const auto& [j, d2] : points.within(patch.centre, options.fit_radius_mm))
      if (normals.row(j).dot(patch.n) >= cos_fit) fit.push_back(j);
    const bool quadric = static_cast<int>(fit.size()) >= options.min_fit_points;
    Eigen::MatrixXd a(static_cast<Eigen::Index>(fit.size()), quadric ? 6 : 3);
    Eigen::VectorXd w(a.rows());
    for (Eigen::Index r = 0; r < a.rows(); ++r) {
      const Eigen::Vector3d d = points_mm.row(fit[static_cast<std::size_t>(r)]).transpose() - patch.centre;
      const double x = d.dot(patch.u), y = d.dot(patch.v);
      if (quadric)
        a.row(r) << x * x, x * y, y * y, x, y, 1;
      else
        a.row(r) << x, y, 1;
      w[r] = d.dot(patch.n);
    }
    patch.h.setZero();
    const Eigen::VectorXd h = a.colPivHouseholderQr().solve(w);
    if (quadric)
      patch.h = h;
    else
      patch.h.tail<3>() = h;
    if (!patch.h.allFinite()) patch.h.setZero();  // a degenerate fit: the tangent plane
    centre_rows.row(static_cast<Eigen::Index>(impl_->patches.size())) = patch.centre.transpose();
    impl_->patches.push_back(patch);
  }
  impl_->centres = std::make_unique<Tree>(std::move(centre_rows));
}

LocalQuadricSurface::LocalQuadricSurface(LocalQuadricSurface&&) noexcept = default;
LocalQuadricSurface& LocalQuadricSurface::operator=(LocalQuadricSurface&&) noexcept = default;
LocalQuadricSurface::~LocalQuadricSurface() = default;

std::size_t LocalQuadricSurface::patches() const { return impl_->patches.size(); }

// The best patch's distance `d`, or, where the best of the patches turned
// from it by more than the edge angle says the other side, the pair's solid:
// see the header. `reached`: each patch within reach and its score.
double LocalQuadricSurface::Impl::across_edge(const Eigen::Vector3d& p, std::uint32_t best, double d,
                                              const std::vector<std::pair<std::uint32_t, double>>& reached,
                                              double cos_edge) const {
  const Patch& a = patches[best];
  double other_score = std::numeric_limits<double>::infinity();
  std::uint32_t other = 0;
  for (const auto& [j, score] : reached)
    if (patches[j].n.dot(a.n) < cos_edge && (score < other_score || (score == other_score && j < other))) {
      other_score = score;
      other = j;
    }
  if (!std::isfinite(other_score)) return d;
  const Patch& b = patches[other];
  const double e = b.at(p).first;
  if ((d > 0) == (e > 0)) return d;
  const double a_sees_b = a.n.dot(b.centre - a.centre), b_sees_a = b.n.dot(a.centre - b.centre);
  if (a_sees_b < 0 && b_sees_a < 0) return std::max(d, e);  // convex: inside both
  if (a_sees_b > 0 && b_sees_a > 0) return std::min(d, e);  // concave: inside either
  return d;
}

Eigen::VectorXd LocalQuadricSurface::value(const Eigen::Ref<const Eigen::MatrixX3d>& q, std::vector<bool>& covered,
                                           int threads) const {
  const LocalQuadricOptions& o = impl_->options;
  Eigen::VectorXd out = Eigen::VectorXd::Zero(q.rows());
  std::vector<char> flags(static_cast<std::size_t>(q.rows()), 0);
  const double search_mm = o.reach_mm;  // patches whose centre lies within reach
  const double cos_edge = std::cos(o.edge_deg * M_PI / 180.0);
  for_each_block(static_cast<std::size_t>(q.rows()), resolve_threads(threads), 256, [&](std::size_t begin, std::size_t end) {
    std::vector<std::pair<std::uint32_t, double>> reached;  // patch, its score
    for (auto i = static_cast<Eigen::Index>(begin); i < static_cast<Eigen::Index>(end); ++i) {
      const Eigen::Vector3d p = q.row(i).transpose();
      double best = std::numeric_limits<double>::infinity();
      std::uint32_t best_index = 0;  // ties go to the lowest index: the same for any thread count
      reached.clear();
      for (const auto& [j, d2] : impl_->centres->within(p, search_mm)) {
        const auto [d, lateral] = impl_->patches[j].at(p);
        if (lateral > o.reach_mm) continue;
        const double score = std::abs(d) + o.lateral_weight * lateral;
        if (o.edge_deg > 0) reached.emplace_back(j, score);
        if (score < best || (score == best && j < best_index)) {
          best = score;
          best_index = j;
          out[i] = d;
        }
      }
      flags[static_cast<std::size_t>(i)] = std::isfinite(best);
      if (o.edge_deg > 0 && std::isfinite(best)) out[i] = impl_->across_edge(p, best_index, out[i], reached, cos_edge);
    }
  });
  covered.assign(flags.begin(), flags.end());
  return out;
}

bool LocalQuadricSurface::in_free_space(const Eigen::Vector3d& p) const {
  const LocalQuadricOptions& o = impl_->options;
  bool in_front = false;
  for (const auto& [j, d2] : impl_->centres->within(p, std::hypot(o.free_radius_mm, o.free_depth_mm))) {
    const Patch& patch = impl_->patches[j];
    const auto [d, lateral] = patch.at(p);
    const double along = (p - patch.centre).dot(patch.n);
    if (lateral < o.free_radius_mm && d > o.free_margin_mm && along < o.free_depth_mm) {
      in_front = true;
      break;
    }
  }
  if (!in_front || !(o.free_support_mm > 0)) return in_front;
  for (const auto& [j, d2] : impl_->centres->within(p, std::hypot(o.free_support_mm, o.free_margin_mm))) {
    const auto [d, lateral] = impl_->patches[j].at(p);
    if (lateral < o.free_support_mm && std::abs(d) <= o.free_margin_mm) return false;  // on a touched patch
  }
  return true;
}

}  // namespace touchcloud::gp
