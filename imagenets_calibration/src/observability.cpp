#include "imagenets_calibration/observability.h"

#include <cmath>
#include <cstdio>
#include <stdexcept>

#include <Eigen/Eigenvalues>
#include <Eigen/SVD>

namespace imagenets_calibration {

bool ParameterUncertainty::observable() const { return posterior_std <= kObservableRatio * prior_std; }

std::string Observability::summary() const {
  if (!computed()) return "observability not computed";
  char b[64];
  if (std::isfinite(condition_number)) {
    std::snprintf(b, sizeof b, "condition number %.3g", condition_number);
  } else {
    std::snprintf(b, sizeof b, "condition number inf");
  }
  std::string s = b;
  if (unobservable.empty()) return s + "; every estimated parameter observable";
  s += "; not observable from these poses (posterior std > 0.5 x prior):";
  for (size_t i = 0; i < unobservable.size(); ++i) s += (i ? ", " : " ") + unobservable[i];
  return s;
}

Observability analyseObservability(const Eigen::MatrixXd& jacobian, int data_rows, const std::vector<std::string>& names,
                                   const std::vector<double>& prior_std, double variance_factor) {
  const Eigen::Index n = jacobian.cols();
  if (static_cast<Eigen::Index>(names.size()) != n || static_cast<Eigen::Index>(prior_std.size()) != n ||
      data_rows < 0 || data_rows > jacobian.rows()) {
    throw std::invalid_argument("analyseObservability: " + std::to_string(n) + " Jacobian columns, " +
                                std::to_string(names.size()) + " names, " + std::to_string(prior_std.size()) +
                                " prior std, " + std::to_string(data_rows) + " of " + std::to_string(jacobian.rows()) +
                                " rows data");
  }
  Observability o;
  // Posterior covariance: the inverse of the information J^T J over the directions it determines;
  // a parameter that moves along an undetermined direction has infinite uncertainty.
  const Eigen::MatrixXd information = jacobian.transpose() * jacobian;
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(information);
  const Eigen::VectorXd lambda = eig.eigenvalues();
  const double tol = 1e-14 * std::max(1e-300, lambda.cwiseAbs().maxCoeff());
  o.covariance = Eigen::MatrixXd::Zero(n, n);
  Eigen::VectorXd undetermined = Eigen::VectorXd::Zero(n);
  for (Eigen::Index k = 0; k < n; ++k) {
    const Eigen::VectorXd v = eig.eigenvectors().col(k);
    if (lambda[k] > tol) {
      o.covariance += v * v.transpose() / lambda[k];
    } else {
      undetermined += v.cwiseAbs2();
    }
  }
  o.covariance *= std::max(1.0, variance_factor);
  for (Eigen::Index i = 0; i < n; ++i) {
    ParameterUncertainty p;
    p.name = names[i];
    p.prior_std = prior_std[i];
    p.posterior_std = undetermined[i] > 1e-9 ? std::numeric_limits<double>::infinity()
                                             : std::sqrt(std::max(0.0, o.covariance(i, i)));
    if (!p.observable()) o.unobservable.push_back(p.name);
    o.parameters.push_back(p);
  }
  // Conditioning of what the measurements alone say, in units of the prior uncertainty.
  Eigen::MatrixXd scaled = jacobian.topRows(data_rows);
  for (Eigen::Index i = 0; i < n; ++i) scaled.col(i) *= prior_std[i];
  if (data_rows > 0) {
    const Eigen::JacobiSVD<Eigen::MatrixXd> svd(scaled);
    const Eigen::VectorXd s = svd.singularValues();
    const double smallest = s.size() ? s[s.size() - 1] : 0.0;
    const double largest = s.size() ? s[0] : 0.0;
    // Fewer measurement rows than parameters leaves directions unobserved, too.
    if (data_rows >= n && smallest > 1e-12 * largest) o.condition_number = largest / smallest;
  }
  return o;
}

}  // namespace imagenets_calibration
