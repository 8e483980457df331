// The ACST adapter: model::acst::update_with_tangent behind fe_model::Material.
#include "fe_model/acst_material.h"

#include "tensor_conversion.h"

#include <cmath>
#include <iomanip>
#include <sstream>
#include <stdexcept>
#include <string>

namespace fe_model {
namespace {

using internal::pack;
using internal::to_deal;
using internal::to_eigen;
using internal::unpack;

// The strain increment and the start state, for failure messages.
std::string describe(const SymmetricTensor2& increment, const model::acst::State<double>& s) {
  std::ostringstream out;
  out << std::setprecision(6) << "strain increment (tension positive; 11 22 33 12 13 23) ["
      << increment[0][0] << ' ' << increment[1][1] << ' ' << increment[2][2] << ' '
      << increment[0][1] << ' ' << increment[0][2] << ' ' << increment[1][2]
      << "]; start state (compression positive): stress [" << s.stress(0, 0) << ' '
      << s.stress(1, 1) << ' ' << s.stress(2, 2) << ' ' << s.stress(0, 1) << ' ' << s.stress(0, 2)
      << ' ' << s.stress(1, 2) << "] Pa, void ratio " << s.void_ratio << ", |alpha| "
      << s.alpha.norm() << ", |F| " << s.fabric.norm();
  return out.str();
}

MaterialStatus convert(model::acst::UpdateStatus status) {
  switch (status) {
    case model::acst::UpdateStatus::kOk:
      return MaterialStatus::kOk;
    case model::acst::UpdateStatus::kUnreliable:
      return MaterialStatus::kUnreliable;
    case model::acst::UpdateStatus::kFailed:
      return MaterialStatus::kFailed;
  }
  return MaterialStatus::kFailed;
}

}  // namespace

AcstMaterial::AcstMaterial(const model::acst::Parameters<double>& parameters,
                           const AcstInitialState& initial_state,
                           const model::acst::IntegrationOptions& options)
    : parameters_(parameters), initial_(initial_state), options_(options) {
  model::acst::validate_parameters(parameters);  // throws, naming the parameter
  if (!model::acst::is_admissible_void_ratio(initial_state.void_ratio))
    throw std::invalid_argument("AcstMaterial: initial void ratio " +
                                std::to_string(initial_state.void_ratio) +
                                " is not physical: it must be in (0, 2.97)");
  if (!initial_state.fabric.allFinite())
    throw std::invalid_argument("AcstMaterial: the initial fabric is not finite");
}

model::acst::State<double> AcstMaterial::to_model(const PointState& state) {
  if (state.internal_variables.size() != kNumInternalVariables) {
    throw std::logic_error("AcstMaterial: point state has " +
                           std::to_string(state.internal_variables.size()) +
                           " internal variables, expected 28 (not an ACST state?)");
  }
  model::acst::State<double> model;
  model.stress = -to_eigen(state.stress);  // tension positive -> compression positive
  model.void_ratio = state.internal_variables[0];
  model.alpha = unpack(state.internal_variables, 1);
  model.alpha_in = unpack(state.internal_variables, 10);
  model.fabric = unpack(state.internal_variables, 19);
  return model;
}

void AcstMaterial::from_model(const model::acst::State<double>& model,
                              const SymmetricTensor2& strain, PointState& state) {
  state.stress = -to_deal(model.stress);  // compression positive -> tension positive
  state.strain = strain;
  state.internal_variables.resize(kNumInternalVariables);
  state.internal_variables[0] = model.void_ratio;
  pack(model.alpha, state.internal_variables, 1);
  pack(model.alpha_in, state.internal_variables, 10);
  pack(model.fabric, state.internal_variables, 19);
}

PointState AcstMaterial::initial_state(const SymmetricTensor2& initial_stress) const {
  model::acst::State<double> model;
  model.stress = -to_eigen(initial_stress);
  model.void_ratio = initial_.void_ratio;
  const double p = model.stress.trace() / 3.0;
  const Eigen::Matrix3d deviator = model.stress - p * Eigen::Matrix3d::Identity();
  model.alpha = p > 0.0 ? Eigen::Matrix3d(deviator / p) : Eigen::Matrix3d::Zero();
  model.alpha_in = model.alpha;
  model.fabric = initial_.fabric;
  PointState state;
  from_model(model, SymmetricTensor2(), state);
  return state;
}

MaterialUpdate AcstMaterial::update(const PointState& start,
                                    const SymmetricTensor2& strain_increment,
                                    PointState& end) const {
  const model::acst::State<double> model_start = to_model(start);
  model::acst::State<double> model_end = model_start;
  Eigen::Matrix<double, 9, 9> D;
  const Eigen::Matrix3d increment = -to_eigen(strain_increment);  // -> compression positive
  model::acst::UpdateReport report;
  const model::acst::UpdateStatus status = model::acst::update_with_tangent(
      parameters_, model_start, increment, model_end, D, options_, &report);

  MaterialUpdate result;
  result.status = convert(status);
  if (result.status == MaterialStatus::kFailed) {
    result.message = "ACST update failed: " + report.message + "; " +
                     describe(strain_increment, model_start);
    end = start;  // never hand NaN to the caller
    return result;
  }
  from_model(model_end, start.strain + strain_increment, end);
  // D(3i+j, 3k+l) = d sigma_ij / d eps_kl, already symmetrised (contract); both signs flip, so
  // the tension-positive tangent is the same. Average the minor-symmetric pairs for safety.
  for (unsigned int i = 0; i < 3; ++i)
    for (unsigned int j = i; j < 3; ++j)
      for (unsigned int k = 0; k < 3; ++k)
        for (unsigned int l = k; l < 3; ++l) {
          const auto row_ij = static_cast<Eigen::Index>(3 * i + j);
          const auto row_ji = static_cast<Eigen::Index>(3 * j + i);
          const auto col_kl = static_cast<Eigen::Index>(3 * k + l);
          const auto col_lk = static_cast<Eigen::Index>(3 * l + k);
          result.tangent[i][j][k][l] = 0.25 * (D(row_ij, col_kl) + D(row_ij, col_lk) +
                                               D(row_ji, col_kl) + D(row_ji, col_lk));
        }
  if (result.status == MaterialStatus::kUnreliable)
    result.message = "ACST update unreliable: " + report.message;
  return result;
}

std::optional<double> AcstMaterial::fabric_invariant(const PointState& state) const {
  if (state.internal_variables.size() != kNumInternalVariables) return std::nullopt;
  const Eigen::Matrix3d F = unpack(state.internal_variables, 19);
  const double c = std::sqrt(2.0 / 3.0);
  return c * (F(2, 2) - 0.5 * (F(0, 0) + F(1, 1)));
}

}  // namespace fe_model
