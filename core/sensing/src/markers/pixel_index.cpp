#include "markers/pixel_index.hpp"

#include <cmath>

#include <nanoflann.hpp>

namespace touchcloud::markers {

namespace {

struct Centres {
  const std::vector<Eigen::Vector2d>* points = nullptr;
  std::size_t kdtree_get_point_count() const { return points->size(); }
  double kdtree_get_pt(std::size_t i, std::size_t dim) const { return (*points)[i][static_cast<Eigen::Index>(dim)]; }
  template <class BoundingBox>
  bool kdtree_get_bbox(BoundingBox&) const { return false; }
};

using KdTree = nanoflann::KDTreeSingleIndexAdaptor<nanoflann::L2_Simple_Adaptor<double, Centres, double>, Centres, 2,
                                                   std::uint32_t>;

}  // namespace

struct PixelIndex::Tree {
  Centres adaptor;
  KdTree tree;
  explicit Tree(const std::vector<Eigen::Vector2d>& points)
      : adaptor{&points}, tree(2, adaptor, nanoflann::KDTreeSingleIndexAdaptorParams(10)) {
    tree.buildIndex();
  }
};

PixelIndex::PixelIndex(const std::vector<Marker>& markers) {
  centres_.reserve(markers.size());
  for (const auto& m : markers) centres_.push_back(m.centre_px);
  if (!centres_.empty()) tree_ = std::make_unique<Tree>(centres_);
}

PixelIndex::~PixelIndex() = default;

Nearest PixelIndex::nearest(const Eigen::Vector2d& pixel, double gate_px) const {
  if (!tree_) return {};
  std::uint32_t index = 0;
  double squared = 0;
  tree_->tree.knnSearch(pixel.data(), 1, &index, &squared);
  if (!(squared <= gate_px * gate_px)) return {};
  return {static_cast<int>(index), std::sqrt(squared)};
}

}  // namespace touchcloud::markers
