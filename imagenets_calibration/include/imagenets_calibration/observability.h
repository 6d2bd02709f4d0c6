// Which of the calibration's estimated parameters the poses given determine: the uncertainty of
// each parameter after the fit (posterior, from the fit's whitened Jacobian at the solution)
// against what was known before (prior). A parameter whose posterior standard deviation is not
// clearly below its prior one is "not observable from these poses": its value comes from the
// prior (the drawing, the encoder tolerance), not from the images. Plain Eigen: the bundle
// adjustment (bundle_adjustment.h) builds the Jacobian, this judges it.
#pragma once

#include <limits>
#include <string>
#include <vector>

#include <Eigen/Core>

namespace imagenets_calibration {

struct ParameterUncertainty {
  std::string name;          // e.g. "fixed point x", "marker offset rz", "arm_joint_3 offset"
  double prior_std = 0.0;    // m or rad: what was known before
  double posterior_std = 0.0;  // m or rad: after the fit (inf: the poses do not determine it at all)
  bool observable() const;   // posterior_std <= kObservableRatio * prior_std
};

// A parameter counts as observed when the images shrink its uncertainty to at most half the prior.
constexpr double kObservableRatio = 0.5;

struct Observability {
  std::vector<ParameterUncertainty> parameters;
  std::vector<std::string> unobservable;  // names of the parameters that are not observable
  // Of the data Jacobian with its columns scaled by the parameters' prior std (so metres and
  // radians compare): largest / smallest singular value; inf when a direction is not observed at all.
  double condition_number = std::numeric_limits<double>::infinity();
  Eigen::MatrixXd covariance;  // posterior, parameter order as `parameters`
  bool computed() const { return !parameters.empty(); }
  // "condition number 41.2; not observable from these poses: marker offset rx, fixed point z" or
  // "condition number 41.2; every estimated parameter observable".
  std::string summary() const;
};

// `jacobian`: the fit's residuals' derivatives, each residual divided by its standard deviation;
// its first `data_rows` rows are the measurements, the rest the priors of the fit (the fit's
// own weak priors, which keep its solution defined). `prior_std`: per column, the a-priori
// standard deviation the judgement uses (also for a parameter without a prior in the fit).
// `variance_factor`: the residuals' variance over the assumed one (>= 1 scales the posterior).
Observability analyseObservability(const Eigen::MatrixXd& jacobian, int data_rows, const std::vector<std::string>& names,
                                   const std::vector<double>& prior_std, double variance_factor = 1.0);

}  // namespace imagenets_calibration
