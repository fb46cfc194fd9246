#include "touchcloud/gp/hyperparameters.hpp"

#include <cmath>
#include <sstream>

#include "touchcloud/error.hpp"

namespace touchcloud::gp {

std::string to_string(KernelKind kind) { return kind == KernelKind::rbf ? "rbf" : "matern52"; }

KernelKind kernel_kind_from_string(const std::string& name) {
  if (name == "rbf") return KernelKind::rbf;
  if (name == "matern52") return KernelKind::matern52;
  throw InputError("unknown GP kernel '" + name + "' (expected rbf or matern52)");
}

std::map<std::string, double> Hyperparameters::named() const {
  return {{"signal_variance_mm2", signal_variance_mm2},
          {"lengthscale_mm", lengthscale_mm},
          {"noise_variance_mm2", noise_variance_mm2}};
}

void Hyperparameters::validate(const std::string& where) const {
  auto fail = [&](const char* name, double value, const char* rule) {
    std::ostringstream msg;
    msg << where << ": GP hyperparameter " << name << " = " << value << " must be " << rule;
    throw InputError(msg.str());
  };
  if (!std::isfinite(signal_variance_mm2) || signal_variance_mm2 <= 0)
    fail("signal_variance_mm2", signal_variance_mm2, "finite and > 0");
  if (!std::isfinite(lengthscale_mm) || lengthscale_mm <= 0) fail("lengthscale_mm", lengthscale_mm, "finite and > 0");
  if (!std::isfinite(noise_variance_mm2) || noise_variance_mm2 < 0)
    fail("noise_variance_mm2", noise_variance_mm2, "finite and >= 0");
}

LogHyperparameters to_log(const Hyperparameters& h) {
  return {std::log(h.signal_variance_mm2), std::log(h.lengthscale_mm), std::log(h.noise_variance_mm2)};
}

Hyperparameters from_log(const LogHyperparameters& theta) {
  return {std::exp(theta[0]), std::exp(theta[1]), std::exp(theta[2])};
}

}  // namespace touchcloud::gp
