#include "touchcloud/simulation/scene/effects.hpp"

namespace touchcloud::simulation {

const std::array<Effect, kEffectCount>& all_effects() {
  static const std::array<Effect, kEffectCount> effects{
      Effect::Contact, Effect::ElasticSpread, Effect::Refraction,    Effect::LensDistortion, Effect::Render,
      Effect::PixelNoise, Effect::Blur,       Effect::MarkerDropout, Effect::PoseNoise,
      Effect::Vignetting, Effect::ExposureDrift};
  return effects;
}

const char* to_string(Effect effect) {
  switch (effect) {
    case Effect::Contact: return "contact";
    case Effect::ElasticSpread: return "elastic_spread";
    case Effect::Refraction: return "refraction";
    case Effect::LensDistortion: return "lens_distortion";
    case Effect::Render: return "render";
    case Effect::PixelNoise: return "pixel_noise";
    case Effect::Blur: return "blur";
    case Effect::MarkerDropout: return "marker_dropout";
    case Effect::PoseNoise: return "pose_noise";
    case Effect::Vignetting: return "vignetting";
    case Effect::ExposureDrift: return "exposure_drift";
  }
  return "?";
}

std::optional<Effect> effect_from_name(std::string_view name) {
  for (Effect e : all_effects())
    if (name == to_string(e)) return e;
  return std::nullopt;
}

std::string effect_names() {
  std::string out;
  for (Effect e : all_effects()) out += (out.empty() ? "" : ", ") + std::string(to_string(e));
  return out;
}

std::string EffectSet::str() const {
  std::string out;
  for (Effect e : all_effects())
    if (has(e)) out += (out.empty() ? "" : ", ") + std::string(to_string(e));
  return out.empty() ? "none" : out;
}

}  // namespace touchcloud::simulation
