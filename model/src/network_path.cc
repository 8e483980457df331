// The contact-network model along a triaxial path (network_path.h).
#include "model/network_path.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace model::network {
namespace {

void record(Curve& c, const PathState<double>& s, double axial, double volumetric,
            const PathNode& node, double youngs_modulus) {
  const DiagonalTensor<double> sigma = stress(s, youngs_modulus);
  const double p = trace(sigma) / 3.0;
  const double q = triaxial_part(sigma);
  c.axial_strain.push_back(axial);
  c.volumetric_strain.push_back(volumetric);
  c.void_ratio.push_back(s.void_ratio);
  c.p.push_back(p);
  c.q.push_back(q);
  c.eta.push_back(q / p);
  c.lateral_stress.push_back(lateral_component(sigma));
  c.coordination.push_back(s.coordination);
  c.lambda.push_back(s.lambda);
  c.a_c.push_back(triaxial_part(s.fabric));
  c.a_n.push_back(triaxial_part(s.normal));
  c.a_t.push_back(triaxial_part(s.tangential));
  c.row.push_back(node.row);
  c.snapshot.push_back(node.snapshot);
}

Curve stopped(Curve c, std::string message) {
  c.complete = false;
  c.message = std::move(message);
  return c;
}

std::string inadmissible_message(double axial) {
  return "the state left its admissible range at axial strain " + std::to_string(axial);
}

}  // namespace

PathState<double> diagonal_state(const State<double>& s) {
  auto diagonal = [](const Tensor<double>& x) {
    return DiagonalTensor<double>{{x(0, 0), x(1, 1), x(2, 2)}};
  };
  return {s.void_ratio,       s.coordination,     s.lambda,
          diagonal(s.fabric), diagonal(s.normal), diagonal(s.tangential),
          diagonal(s.inherent)};
}

int checked_substeps(const Parameters<double>& par, const PathState<double>& start,
                     double strain_norm, const PathOptions& options) {
  const int n = substeps_for(par, start, strain_norm, options.substep_size);
  return n > options.max_substeps ? 0 : n;
}

int drained_substeps(const Parameters<double>& par, const PathState<double>& start, double da,
                     const PathOptions& options) {
  return checked_substeps(par, start, std::abs(da) * std::sqrt(1.5), options);
}

std::string too_stiff_message(double axial, const PathOptions& options) {
  return "the increment to axial strain " + std::to_string(axial) + " needs more than " +
         std::to_string(options.max_substeps) + " RK4 substeps (rates too fast for the step)";
}

bool drained_increment(const Parameters<double>& par, const PathState<double>& start, double da,
                       double target, double youngs_modulus, double& lateral,
                       PathState<double>& end, const PathOptions& options) {
  using Dual = ceres::Jet<double, 1>;
  const Parameters<Dual> par_dual = lift_parameters<Dual>(par);
  const PathState<Dual> s0 = cast_state<Dual>(start);
  const int substeps = drained_substeps(par, start, da, options);
  if (substeps == 0) return false;
  for (int it = 0; it < 50; ++it) {
    const PathState<Dual> s = integrate(par_dual, s0,
                                        strain_increment(Dual(da), Dual(lateral, 0)), substeps);
    if (!admissible_values(s)) return false;
    const Dual g = lateral_component(stress(s, youngs_modulus)) / target - Dual(1.0);
    if (std::abs(g.a) < 1e-11) {
      end = integrate(par, start, strain_increment(da, lateral), substeps);
      return true;
    }
    if (!(std::abs(g.v[0]) > 0.0)) return false;
    double step = -g.a / g.v[0];
    const double cap = 2.0 * std::abs(da) + 1e-12;  // no wild first steps
    step = std::clamp(step, -cap, cap);
    lateral += step;
  }
  return false;
}

Curve follow_strain_path(const Parameters<double>& par, const PathState<double>& start,
                         const std::vector<PathNode>& nodes, double youngs_modulus,
                         const PathOptions& options) {
  validate(par);
  Curve c;
  if (nodes.empty()) return c;
  PathState<double> s = start;
  record(c, s, nodes.front().axial, nodes.front().volumetric, nodes.front(), youngs_modulus);
  for (std::size_t k = 1; k < nodes.size(); ++k) {
    const double da = nodes[k].axial - nodes[k - 1].axial;
    const double dr = 0.5 * ((nodes[k].volumetric - nodes[k - 1].volumetric) - da);
    const int substeps = checked_substeps(par, s, std::sqrt(da * da + 2.0 * dr * dr), options);
    if (substeps == 0) return stopped(c, too_stiff_message(nodes[k].axial, options));
    s = integrate(par, s, strain_increment(da, dr), substeps);
    if (!admissible(s)) return stopped(c, inadmissible_message(nodes[k].axial));
    record(c, s, nodes[k].axial, nodes[k].volumetric, nodes[k], youngs_modulus);
  }
  return c;
}

Curve predict(const Parameters<double>& par, const PathState<double>& start,
              const std::vector<PathNode>& nodes, Lateral lateral, double lateral_stress,
              double youngs_modulus, const PathOptions& options) {
  validate(par);
  Curve c;
  if (nodes.empty()) return c;
  PathState<double> s = start;
  double volumetric = 0.0, lateral_ratio = -0.3;
  record(c, s, nodes.front().axial, volumetric, nodes.front(), youngs_modulus);
  for (std::size_t k = 1; k < nodes.size(); ++k) {
    const double da = nodes[k].axial - nodes[k - 1].axial;
    double dr = -0.5 * da;
    PathState<double> end;
    if (lateral == Lateral::kStressHeld) {
      dr = lateral_ratio * da;
      if (!drained_increment(par, s, da, lateral_stress, youngs_modulus, dr, end, options))
        return stopped(c, drained_substeps(par, s, da, options) == 0
                              ? too_stiff_message(nodes[k].axial, options)
                              : "no lateral strain holds the lateral stress at axial strain " +
                                    std::to_string(nodes[k].axial));
      lateral_ratio = dr / da;
    } else {
      const int substeps = checked_substeps(par, s, std::abs(da) * std::sqrt(1.5), options);
      if (substeps == 0) return stopped(c, too_stiff_message(nodes[k].axial, options));
      end = integrate(par, s, strain_increment(da, dr), substeps);
    }
    if (!admissible(end)) return stopped(c, inadmissible_message(nodes[k].axial));
    s = end;
    volumetric += da + 2.0 * dr;
    record(c, s, nodes[k].axial, volumetric, nodes[k], youngs_modulus);
  }
  return c;
}

}  // namespace model::network
