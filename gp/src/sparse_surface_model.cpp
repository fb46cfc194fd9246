#include "touchcloud/gp/sparse_surface_model.hpp"

namespace touchcloud::gp {

std::map<std::string, double> SparseSurfaceModel::hyperparameters() const {
  auto named = gp_->hyperparameters().named();
  named["jitter_mm2"] = gp_->inducing_factorisation().jitter_mm2;
  named["inducing_points"] = static_cast<double>(gp_->inducing_size());
  return named;
}

}  // namespace touchcloud::gp
