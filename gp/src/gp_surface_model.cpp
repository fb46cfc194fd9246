#include "touchcloud/gp/gp_surface_model.hpp"

namespace touchcloud::gp {

std::map<std::string, double> GpSurfaceModel::hyperparameters() const {
  auto named = gp_->hyperparameters().named();
  named["jitter_mm2"] = gp_->factorisation().jitter_mm2;
  return named;
}

}  // namespace touchcloud::gp
