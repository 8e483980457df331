// The material interface of fe_model: what a constitutive law must provide at a quadrature point.
//
// Sign convention: everything that crosses this interface is in deal.II's convention, tension
// positive (stress, strain, strain increment). A material whose own convention is compression
// positive (the models of model/) converts inside its adapter. The triaxial driver
// converts its *output* to compression positive (soil mechanics); see docs/fe.md.
//
// Design (after MGIS): the state at the start of a step (`start`, MGIS s0) is read only; the
// material writes the state at the end of the step (`end`, MGIS s1) and returns a status. The
// finite-element code owns both copies per quadrature point, commits end -> start when a load
// step has converged and reverts end <- start when the step is cut.
#ifndef FE_MODEL_MATERIAL_H_
#define FE_MODEL_MATERIAL_H_

#include <deal.II/base/symmetric_tensor.h>

#include <optional>
#include <string>
#include <vector>

#include "model/update_status.h"

namespace fe_model {

using SymmetricTensor2 = dealii::SymmetricTensor<2, 3>;
using SymmetricTensor4 = dealii::SymmetricTensor<4, 3>;

/// State of one material point. `stress` and `strain` are kept for every material; anything else
/// the law needs (void ratio, back-stress, fabric, ...) is packed by the material into
/// `internal_variables`; the FE code copies it and never interprets it.
struct PointState {
  SymmetricTensor2 stress;  ///< Cauchy stress [Pa], tension positive.
  SymmetricTensor2 strain;  ///< Total small strain from the reference (consolidated) state.
  std::vector<double> internal_variables;
};

/// Outcome of a material update: the models' own status (model/update_status.h). kOk: converged to
/// the law's tolerance; kUnreliable: a result whose accuracy is doubtful (accepted, counted,
/// logged, or the step cut: SolverOptions::cut_on_unreliable); kFailed: no usable result, the FE
/// code cuts the load step.
using MaterialStatus = model::UpdateStatus;
using model::to_string;
using model::worst;

/// Result of Material::update. The stress is in `end.stress`.
struct MaterialUpdate {
  MaterialStatus status = MaterialStatus::kOk;
  /// Consistent (algorithmic) tangent d(end.stress)/d(strain_increment). Minor symmetries only:
  /// major symmetry is not assumed (non-associated plasticity), so the FE system is solved with
  /// an unsymmetric direct solver.
  SymmetricTensor4 tangent;
  std::string message;  ///< Why the status is not kOk (empty otherwise).
};

/// A constitutive law at a quadrature point. Implementations must be stateless apart from their
/// parameters (the state lives in PointState), so one object serves every quadrature point and
/// update() may be called concurrently.
class Material {
 public:
  virtual ~Material() = default;

  /// Short name for logs and output files.
  virtual std::string name() const = 0;

  /// The state of a point carrying `initial_stress` (tension positive) at zero strain.
  virtual PointState initial_state(const SymmetricTensor2& initial_stress) const = 0;

  /// Integrates the law over a strain increment (tension positive) from `start`; writes the whole
  /// end state (stress, strain = start.strain + strain_increment, internal variables) into `end`
  /// and returns the status and the consistent tangent. On kFailed `end` is unspecified but must
  /// not be read by the caller; implementations should still avoid NaN in it.
  virtual MaterialUpdate update(const PointState& start, const SymmetricTensor2& strain_increment,
                                PointState& end) const = 0;

  /// A scalar fabric invariant of the state, for materials that carry a fabric tensor;
  /// std::nullopt (the default) for those that do not. Its definition is the material's (documented
  /// with it); the triaxial driver averages it over the specimen and writes it to the CSV.
  virtual std::optional<double> fabric_invariant(const PointState& /*state*/) const {
    return std::nullopt;
  }
};

/// Isotropic linear elasticity (Lamé): stress = start.stress + lambda tr(de) I + 2 mu de.
/// Stress-free or pre-stressed: the initial stress is kept and the increment is added.
class LinearElasticMaterial final : public Material {
 public:
  /// Young's modulus [Pa] and Poisson's ratio, -1 < nu < 0.5; throws std::invalid_argument
  /// naming the bad parameter otherwise.
  LinearElasticMaterial(double youngs_modulus, double poissons_ratio);

  std::string name() const override { return "linear_elastic"; }
  PointState initial_state(const SymmetricTensor2& initial_stress) const override;
  MaterialUpdate update(const PointState& start, const SymmetricTensor2& strain_increment,
                        PointState& end) const override;

  double youngs_modulus() const { return youngs_modulus_; }
  double poissons_ratio() const { return poissons_ratio_; }
  double lambda() const { return lambda_; }
  double mu() const { return mu_; }
  const SymmetricTensor4& stiffness() const { return stiffness_; }

 private:
  double youngs_modulus_;
  double poissons_ratio_;
  double lambda_;
  double mu_;
  SymmetricTensor4 stiffness_;
};

}  // namespace fe_model

#endif  // FE_MODEL_MATERIAL_H_
