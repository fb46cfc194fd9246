// Hyperparameter selection for the implicit surface: the exact log marginal
// likelihood of residuals r (signed distance minus the prior mean) at points
// p, with its analytic gradient in (log s2, log scale, log noise), maximised
// by gp's L-BFGS restarts (maximise_lml) from one start inside bounds that
// follow the data: the scale between the offset and a few times the data's
// diameter (thin_plate: at least the diameter, as its kernel asks), the
// signal variance around the residuals' spread, the noise within the options'.
#pragma once

#include <Eigen/Core>

#include "touchcloud/gp/hyperparameter_search.hpp"
#include "touchcloud/gp/implicit_surface.hpp"

namespace touchcloud::gp {

// `diameter_mm`: of all the training points, which the subset may not span.
SearchResult select_implicit_hyperparameters(const Eigen::MatrixX3d& points_mm, const Eigen::VectorXd& residual_mm,
                                             double diameter_mm, const ImplicitSurfaceOptions& options);

// The same on an even stride of at most options.selection_points of the
// training points (contacts and signed points of every touch), residuals
// against the prior sphere (centre, radius); `subset_size` set to its size.
// `scale_floor`: the data's diameter counts this many times (thin_plate's R
// at least that much).
SearchResult select_implicit_on_training(const ImplicitTraining& data, const Eigen::Vector3d& centre_mm, double radius_mm,
                                         const ImplicitSurfaceOptions& options, double scale_floor,
                                         Eigen::Index& subset_size);

}  // namespace touchcloud::gp
