// The third model behind the model interface (descriptor.h): isotropic linear elasticity about the
// point's initial stress, sigma = sigma_0 + lambda tr(eps) I + 2 mu eps (Lame). Small enough to
// show what a model must give the interface, and the analytic check of every consumer: the
// parameter file, the UMAT, the FE material and the material-point driver.
#include <algorithm>
#include <memory>
#include <string>
#include <vector>

#include "model/descriptor.h"

namespace model {

namespace {

class LinearElasticBehaviour final : public Behaviour {
 public:
  LinearElasticBehaviour(const ModelDescription& description, double youngs_modulus,
                         double poissons_ratio)
      : description_(description),
        lambda_(youngs_modulus * poissons_ratio /
                ((1.0 + poissons_ratio) * (1.0 - 2.0 * poissons_ratio))),
        mu_(youngs_modulus / (2.0 * (1.0 + poissons_ratio))) {
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j)
        for (int k = 0; k < 3; ++k)
          for (int l = 0; l < 3; ++l)
            tangent_(3 * i + j, 3 * k + l) = (i == j && k == l ? lambda_ : 0.0) +
                                             (i == k && j == l ? mu_ : 0.0) +
                                             (i == l && j == k ? mu_ : 0.0);
  }

  const ModelDescription& description() const override { return description_; }

  Eigen::Matrix3d initial_state(const Eigen::Matrix3d& stress, const double* /*inputs*/,
                                double* /*state*/) const override {
    return stress;
  }

  PointUpdate update(const Eigen::Matrix3d& stress, const double* /*state_start*/,
                     const Eigen::Matrix3d& strain_increment,
                     double* /*state_end*/) const override {
    PointUpdate result;
    result.status = UpdateStatus::kOk;
    result.stress = stress + lambda_ * strain_increment.trace() * Eigen::Matrix3d::Identity() +
                    2.0 * mu_ * strain_increment;
    result.tangent = tangent_;
    return result;
  }

 private:
  const ModelDescription& description_;
  double lambda_, mu_;  // Lame's constants [Pa]
  Eigen::Matrix<double, 9, 9> tangent_;
};

class LinearElasticDescription final : public ModelDescription {
 public:
  std::string name() const override { return "linear_elastic"; }
  std::string umat_name() const override { return "LINEAR_ELASTIC"; }
  const std::vector<ParameterInfo>& constants() const override {
    static const std::vector<ParameterInfo> none;
    return none;
  }
  const std::vector<ParameterInfo>& parameters() const override {
    static const std::vector<ParameterInfo> table = {
        {"youngs_modulus", "Pa", {0.0, kUnbounded, false, false}, 1e5, 1e10},
        {"poissons_ratio", "1", {-1.0, 0.5, false, false}, 0.0, 0.45},
    };
    return table;
  }
  const std::vector<Slot>& initial_inputs() const override {
    static const std::vector<Slot> none;
    return none;
  }
  const std::vector<Slot>& state() const override {
    static const std::vector<Slot> none;
    return none;
  }
  std::unique_ptr<Behaviour> make(const std::vector<double>& constants,
                                  const std::vector<double>& parameters) const override {
    validate(constants, parameters);
    return std::make_unique<LinearElasticBehaviour>(*this, parameters[0], parameters[1]);
  }
};

}  // namespace

const ModelDescription& linear_elastic_description() {
  static const LinearElasticDescription description;
  return description;
}

}  // namespace model
