// The contact-network update with its exact tangent (model/network_update.h).
#include "model/network_update.h"

#include <ceres/jet.h>

#include <array>
#include <cmath>
#include <sstream>

namespace model::network {
namespace {

// The six independent strain components seeded in the dual numbers.
constexpr int kI[6] = {0, 1, 2, 0, 1, 0};
constexpr int kJ[6] = {0, 1, 2, 1, 2, 2};

}  // namespace

double lambda_for_mean_stress(const State<double>& network, double p, double youngs_modulus) {
  const double bracket_trace = 1.0 + 2.0 / 15.0 * (network.normal * network.fabric).trace();
  return 3.0 * p * (1.0 + network.void_ratio) /
         (youngs_modulus * network.coordination * bracket_trace);
}

UpdateResult update_with_tangent(const Parameters<double>& par, const State<double>& start,
                                 const Tensor<double>& increment, double youngs_modulus,
                                 int max_substeps) {
  using Dual = ceres::Jet<double, 6>;
  UpdateResult result;
  result.end = start;
  result.substeps = substeps_for(par, start, increment.norm());
  if (!increment.allFinite() || result.substeps > max_substeps) {
    std::ostringstream why;
    if (!increment.allFinite())
      why << "the strain increment is not finite";
    else
      why << "the strain increment of norm " << increment.norm() << " needs " << result.substeps
          << " RK4 substeps, more than " << max_substeps << " (cut it)";
    result.message = "contact-network update: " + why.str();
    return result;
  }
  // eps_kl and eps_lk move together under a shear seed.
  Tensor<Dual> d;
  for (int a = 0; a < 6; ++a) d(kI[a], kJ[a]) = d(kJ[a], kI[a]) = Dual(increment(kI[a], kJ[a]), a);
  auto lift = [](double x) { return Dual(x); };
  const State<Dual> s0{lift(start.void_ratio),       lift(start.coordination),
                       lift(start.lambda),           start.fabric.unaryExpr(lift),
                       start.normal.unaryExpr(lift), start.tangential.unaryExpr(lift),
                       start.inherent.unaryExpr(lift)};
  const auto values = to_array(par);
  std::array<Dual, kNumParameters> par_dual;
  for (int i = 0; i < kNumParameters; ++i) par_dual[i] = Dual(values[i]);
  const State<Dual> s1 = integrate(from_array(par_dual.data()), s0, d, result.substeps);
  auto value = [](const Dual& x) { return x.a; };
  const State<double> end{s1.void_ratio.a,           s1.coordination.a,
                          s1.lambda.a,               s1.fabric.unaryExpr(value),
                          s1.normal.unaryExpr(value), s1.tangential.unaryExpr(value),
                          s1.inherent.unaryExpr(value)};
  if (!admissible(end)) {
    std::ostringstream why;
    why << "contact-network update: the state left its admissible range (e " << end.void_ratio
        << ", Z " << end.coordination << ", Lambda " << end.lambda
        << ") over the strain increment of norm " << increment.norm();
    result.message = why.str();
    return result;
  }
  // A shear seed's derivative is d sigma / d eps_kl + d sigma / d eps_lk, twice the symmetric
  // tangent's component.
  const Tensor<Dual> sigma = stress(s1, youngs_modulus);
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      for (int a = 0; a < 6; ++a) {
        const double dij = 0.5 * (sigma(i, j).v[a] + sigma(j, i).v[a]);
        const double component = kI[a] == kJ[a] ? dij : 0.5 * dij;
        result.tangent(3 * i + j, 3 * kI[a] + kJ[a]) = component;
        result.tangent(3 * i + j, 3 * kJ[a] + kI[a]) = component;
      }
  result.end = end;
  result.status = UpdateStatus::kOk;
  return result;
}

}  // namespace model::network
