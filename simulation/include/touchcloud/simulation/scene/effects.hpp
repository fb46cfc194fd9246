// The effects a scene may ask for. Each is opt-in and independent: one the
// scene does not name costs nothing and changes nothing.
#pragma once

#include <array>
#include <bitset>
#include <optional>
#include <string>
#include <string_view>

namespace touchcloud::simulation {

enum class Effect {
  Contact,         // the gel conforms to the object where they overlap
  ElasticSpread,   // markers around the contact follow it, with a Gaussian fall-off
  Refraction,      // marker pixels through the plate (air, acrylic, silicone); else straight rays
  LensDistortion,  // the cameras' Brown-Conrady coefficients; else none
  Render,          // marker dots drawn into left and right images
  PixelNoise,      // Gaussian noise on grey levels and on marker centres
  Blur,            // Gaussian blur of the images
  MarkerDropout,   // markers missing from a view
  PoseNoise,       // the reported sensor pose is perturbed (the truth is not)
  Vignetting,      // GelSight: the lens darkens the whole image, contact shading included, towards the corners
  ExposureDrift,   // GelSight: frames are taken at another gain and offset than the no-contact reference
};
inline constexpr std::size_t kEffectCount = 11;

const std::array<Effect, kEffectCount>& all_effects();
const char* to_string(Effect effect);               // "elastic_spread"
std::optional<Effect> effect_from_name(std::string_view name);
std::string effect_names();                         // "contact, elastic_spread, ..."

class EffectSet {
 public:
  bool has(Effect e) const { return bits_.test(static_cast<std::size_t>(e)); }
  void add(Effect e) { bits_.set(static_cast<std::size_t>(e)); }
  bool empty() const { return bits_.none(); }
  std::string str() const;  // the names, comma-separated, or "none"

 private:
  std::bitset<kEffectCount> bits_;
};

// The parameters of the effects, with the defaults a scene gets when it names
// an effect without them. Used only when the effect is on.
struct EffectParameters {
  // elastic_spread: a non-contact marker rises by max_i u_i exp(-d_i^2 / (2 sigma^2)),
  // u_i the lift of contact marker i and d_i their distance at rest.
  double spread_sigma_mm = 3.0;
  // pixel_noise: on rendered grey levels, and on marker centres in the marker set.
  double noise_sigma_grey = 2.0;
  double noise_sigma_px = 0.1;
  // blur
  double blur_sigma_px = 0.8;
  // marker_dropout: each marker is missing from each view with this probability.
  double dropout_probability = 0.05;
  // pose_noise: per frame, on the reported base_from_sensor.
  double pose_sigma_mm = 0.1;
  double pose_sigma_deg = 0.05;
  // render
  double background_grey = 200.0;  // at the image centre
  double vignetting = 0.35;        // relative fall-off of the background at the corners
  double marker_grey = 40.0;       // a marker dot's centre
  // vignetting (gelsight): every pixel, reference and frames alike, times
  // 1 - fall_off (r / r_corner)^2, r its distance from the image centre. The
  // sensor's own `vignetting` shapes only the background's light; this is
  // the lens's, so a contact's colour difference shrinks towards the corners.
  double lens_fall_off = 0.15;
  // exposure_drift (gelsight): a frame is gain I + offset_grey of what the
  // reference's exposure gives it (auto-exposure or LED warm-up between the
  // no-contact image and the presses); the reference keeps its own.
  double exposure_gain = 1.01;
  double exposure_offset_grey = 1.0;
};

}  // namespace touchcloud::simulation
