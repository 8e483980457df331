// Linear elasticity and the Newton log's ratios: the parts of fe_model that need
// only deal.II's tensor headers.
#include "fe_model/material.h"

#include <cmath>
#include <stdexcept>
#include <string>

#include "fe_model/solver_options.h"

namespace fe_model {

LinearElasticMaterial::LinearElasticMaterial(double youngs_modulus, double poissons_ratio)
    : youngs_modulus_(youngs_modulus), poissons_ratio_(poissons_ratio) {
  if (!(youngs_modulus > 0.0) || !std::isfinite(youngs_modulus)) {
    throw std::invalid_argument("LinearElasticMaterial: Young's modulus must be positive, got " +
                                std::to_string(youngs_modulus));
  }
  if (!(poissons_ratio > -1.0 && poissons_ratio < 0.5)) {
    throw std::invalid_argument(
        "LinearElasticMaterial: Poisson's ratio must lie in (-1, 0.5), got " +
        std::to_string(poissons_ratio));
  }
  // Lamé constants from E and nu.
  lambda_ =
      youngs_modulus * poissons_ratio / ((1.0 + poissons_ratio) * (1.0 - 2.0 * poissons_ratio));
  mu_ = youngs_modulus / (2.0 * (1.0 + poissons_ratio));
  const SymmetricTensor2 identity = dealii::unit_symmetric_tensor<3>();
  stiffness_ = lambda_ * dealii::outer_product(identity, identity) +
               2.0 * mu_ * dealii::identity_tensor<3>();
}

PointState LinearElasticMaterial::initial_state(const SymmetricTensor2& initial_stress) const {
  PointState state;
  state.stress = initial_stress;
  return state;
}

MaterialUpdate LinearElasticMaterial::update(const PointState& start,
                                             const SymmetricTensor2& strain_increment,
                                             PointState& end) const {
  end.strain = start.strain + strain_increment;
  end.stress = start.stress + stiffness_ * strain_increment;
  end.internal_variables = start.internal_variables;
  MaterialUpdate result;
  result.tangent = stiffness_;
  return result;
}

std::vector<double> NewtonLog::residual_ratios() const {
  std::vector<double> ratios;
  for (std::size_t k = 1; k < residual_norms.size(); ++k) {
    ratios.push_back(residual_norms[k - 1] > 0.0 ? residual_norms[k] / residual_norms[k - 1] : 0.0);
  }
  return ratios;
}

std::vector<double> NewtonLog::quadratic_ratios() const {
  std::vector<double> ratios;
  const double scale = force_scale > 0.0 ? force_scale : 1.0;
  for (std::size_t k = 1; k < residual_norms.size(); ++k) {
    const double previous = residual_norms[k - 1] / scale;
    const double current = residual_norms[k] / scale;
    ratios.push_back(previous > 0.0 ? current / (previous * previous) : 0.0);
  }
  return ratios;
}

int StepReport::total_iterations() const {
  int total = 0;
  for (const NewtonLog& attempt : attempts) {
    if (attempt.converged) total += attempt.iterations;
  }
  return total;
}

}  // namespace fe_model
