#include "sff/analysis.h"

#include <algorithm>
#include <cmath>

#include "sff/sff_equation.h"
#include "sff/statistics.h"
#include "sff/tensors.h"

namespace sff {

double clump_volume(double radius, double centre_distance) {
  constexpr double kPi = 3.14159265358979323846;
  const double r = radius, s = centre_distance;
  return 8.0 * kPi * r * r * r / 3.0 - kPi * (4.0 * r + s) * (2.0 * r - s) * (2.0 * r - s) / 12.0;
}

double mechanical_coordination(ContactSpan contacts, int num_bodies) {
  std::vector<char> rattler(static_cast<std::size_t>(num_bodies), 0);
  std::vector<int> count(static_cast<std::size_t>(num_bodies), 0);
  auto in_range = [&](std::int64_t id) { return id >= 0 && id < num_bodies; };
  for (bool changed = true; changed;) {
    std::fill(count.begin(), count.end(), 0);
    for (const ContactRecord& c : contacts) {
      if (is_wall_contact(c) || !in_range(c.body_a) || !in_range(c.body_b)) continue;
      if (rattler[c.body_a] || rattler[c.body_b]) continue;
      ++count[c.body_a];
      ++count[c.body_b];
    }
    changed = false;
    for (int b = 0; b < num_bodies; ++b)
      if (!rattler[b] && count[b] < 2) rattler[b] = 1, changed = true;
  }
  long long pairs = 0, bodies = 0;
  for (int b = 0; b < num_bodies; ++b) {
    bodies += !rattler[b];
    pairs += count[b];
  }
  return bodies > 0 ? static_cast<double>(pairs) / static_cast<double>(bodies) : 0.0;
}

SnapshotAnalysis analyse_snapshot(const SnapshotInput& in) {
  if (!(in.volume > 0.0 && in.solid_volume > 0.0 && in.num_bodies > 0))
    throw StatisticsError("analyse_snapshot: volume, solid volume and body count must be positive");
  SnapshotAnalysis a;
  a.stress = contact_stress(in.contacts, in.volume);
  const StressInvariants inv = triaxial_invariants(a.stress);
  a.p = inv.p;
  a.q = inv.q;
  a.eta = inv.eta;
  a.void_ratio = in.volume / in.solid_volume - 1.0;
  const std::size_t nc = count_body_contacts(in.contacts);
  a.coordination = 2.0 * static_cast<double>(nc) / in.num_bodies;
  a.mechanical_coordination = mechanical_coordination(in.contacts, in.num_bodies);

  const ForceScale scale{in.youngs_modulus, in.solid_volume / in.num_bodies};
  a.fabric = fabric_anisotropy(fabric_tensor(in.contacts));
  const NormalForceStatistics nf = normal_force_statistics(in.contacts, a.fabric, scale);
  a.lambda = nf.lambda;
  a.normal = nf.anisotropy;
  a.tangential = tangential_force_tensor(in.contacts, nf.lambda, scale);
  const Mobilisation mob = mobilisation(in.contacts, a.fabric, nf.lambda, in.friction, scale);
  a.mobilisation = mob.tensor;
  a.sliding_fraction = mob.sliding_fraction;
  a.a_c = triaxial(a.fabric);
  a.a_n = triaxial(a.normal);
  a.a_t = triaxial(a.tangential);
  a.m = triaxial(a.mobilisation);

  SffState state;
  state.youngs_modulus = in.youngs_modulus;
  state.coordination = a.coordination;
  state.void_ratio = a.void_ratio;
  state.lambda = a.lambda;
  state.fabric = a.fabric;
  state.normal = a.normal;
  state.tangential = a.tangential;
  const Eigen::Matrix3d predicted = sff_stress(state);
  a.eta_sff = triaxial_invariants(predicted).eta;
  a.eta_concise = concise_eta(a.a_c, a.a_n, a.a_t);
  a.eta_decoupled = decoupled_eta(a.a_c, a.a_n, in.friction, a.m);
  a.eta_exact = exact_decoupled_eta(in.contacts, in.friction, a.lambda, mob.weighted, scale);
  const double norm = a.stress.norm();
  a.sff_error = (predicted - a.stress).norm() / norm;
  a.branch_ratio = branch_remainder(in.contacts, in.volume).norm() / norm;
  return a;
}

const std::vector<std::string>& analysis_columns() {
  static const std::vector<std::string> names = {
      "p", "q", "eta", "void_ratio", "coordination", "mechanical_coordination", "lambda",
      "a_c", "a_n", "a_t", "m", "eta_sff", "eta_concise", "eta_decoupled", "eta_exact",
      "sff_error", "branch_ratio", "sliding_fraction"};
  return names;
}

std::vector<double> analysis_row(const SnapshotAnalysis& a) {
  return {a.p, a.q, a.eta, a.void_ratio, a.coordination, a.mechanical_coordination, a.lambda,
          a.a_c, a.a_n, a.a_t, a.m, a.eta_sff, a.eta_concise, a.eta_decoupled, a.eta_exact,
          a.sff_error, a.branch_ratio, a.sliding_fraction};
}

}  // namespace sff
