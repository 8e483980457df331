#include "sff/analysis.h"

#include <algorithm>
#include <cmath>

#include "force_moments.h"
#include "sff/invariants.h"
#include "sff/sff_equation.h"
#include "sff/statistics.h"
#include "sff/tensors.h"
#include "sffcal/constants.h"

namespace sff {

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

DirectionalTensors directional_tensors(ContactSpan contacts, const ForceScale& scale, double friction) {
  if (!(friction > 0.0)) throw StatisticsError("directional_tensors: the friction coefficient must be positive");
  DirectionalTensors t;
  t.fabric = fabric_anisotropy(fabric_tensor(contacts));
  const DirectionWeight weight(contacts, t.fabric);
  t.min_density = weight.min_density();
  t.binned_weights = weight.binned();
  // One pass for every force moment (the bootstrap repeats this per resample).
  const internal::ForceMoments moments = internal::accumulate_force_moments(contacts, weight, scale, friction);
  const NormalForceStatistics nf = normal_force_statistics(moments);
  t.lambda = nf.lambda;
  t.normal = nf.anisotropy;
  t.tangential = tangential_force_tensor(moments, nf.lambda);
  const Mobilisation mob = mobilisation(moments, nf.lambda);
  t.weighted_mobilisation = mob.weighted;
  t.mobilisation = mob.tensor;
  t.sliding_fraction = mob.sliding_fraction;
  return t;
}

PrincipalAxis principal_axis(const Eigen::Matrix3d& t) {
  PrincipalAxis p;
  p.axis = major_direction(t);
  if (p.axis.z() < 0.0) p.axis = -p.axis;
  p.major = p.axis.dot(t * p.axis);
  p.tilt_deg = axis_angle_deg(p.axis, Eigen::Vector3d::UnitZ());
  return p;
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
  Eigen::Matrix3d boundary_stress = a.stress;
  if (!in.centroids.empty()) {
    const Eigen::Matrix3d wall_terms = wall_contact_stress(in.contacts, in.centroids, in.volume);
    boundary_stress += wall_terms;
    a.wall_layer_ratio = wall_terms.norm() / a.stress.norm();
  }
  const double wall_p = in.wall_stress.sum() / 3.0;
  if (wall_p > 0.0) {
    a.wall_eta = (in.wall_stress.z() - 0.5 * (in.wall_stress.x() + in.wall_stress.y())) / wall_p;
    a.wall_stress_error = (boundary_stress.diagonal() - in.wall_stress).cwiseAbs().maxCoeff() / wall_p;
  }

  const ForceScale scale{in.youngs_modulus, in.solid_volume / in.num_bodies};
  const DirectionalTensors t = directional_tensors(in.contacts, scale, in.friction);
  a.lambda = t.lambda;
  a.fabric = t.fabric;
  a.normal = t.normal;
  a.tangential = t.tangential;
  a.weighted_mobilisation = t.weighted_mobilisation;
  a.mobilisation = t.mobilisation;
  a.sliding_fraction = t.sliding_fraction;
  a.min_density = t.min_density;
  a.binned_weights = t.binned_weights;
  a.guo_zhao = guo_zhao_anisotropy(in.contacts, DirectionWeight(in.contacts, a.fabric));
  a.a_n_gz = triaxial(a.guo_zhao.normal);
  a.a_t_gz = triaxial(a.guo_zhao.tangential);
  a.a_l = triaxial(a.guo_zhao.branch);
  a.eta_gz = triaxial_invariants(a.guo_zhao.bracket(a.fabric)).eta;
  a.a_c = triaxial(a.fabric);
  a.a_n = triaxial(a.normal);
  a.a_t = triaxial(a.tangential);
  a.m = triaxial(a.mobilisation);
  a.a_c_invariant = signed_invariant(a.fabric);
  a.a_n_invariant = signed_invariant(a.normal);
  a.a_t_invariant = signed_invariant(a.tangential);
  a.m_invariant = signed_invariant(a.mobilisation);
  a.stress_axis = principal_axis(a.stress);
  a.fabric_axis = principal_axis(a.fabric);
  a.normal_axis = principal_axis(a.normal);
  a.tangential_axis = principal_axis(a.tangential);
  a.mobilisation_axis = principal_axis(a.mobilisation);

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
  a.eta_exact = exact_decoupled_eta(in.contacts, in.friction, a.lambda, t.weighted_mobilisation, scale);
  const double norm = a.stress.norm();
  a.sff_error = (predicted - a.stress).norm() / norm;
  a.branch_ratio = branch_remainder(in.contacts, in.volume).norm() / norm;
  return a;
}

SnapshotChecks check_snapshot(const SnapshotInput& in, const SnapshotAnalysis& a,
                              const CheckOptions& options) {
  const ForceScale scale{in.youngs_modulus, in.solid_volume / in.num_bodies};
  SnapshotChecks c;
  c.branch = branch_check(in.contacts);
  // The cells about the stress's principal axes: the checks do not depend on the lab frame.
  const DirectionCells cells = DirectionCells::principal(options.cells, a.stress);
  c.truncation = truncation_check(in.contacts, scale, a.fabric, a.lambda, a.normal, cells);
  c.independence = independence_check(in.contacts, in.friction, scale, a.lambda, a.normal,
                                      a.weighted_mobilisation, a.mobilisation, cells);
  c.coaxiality = coaxiality_check(a.stress, a.fabric, a.normal, a.tangential, a.mobilisation);
  c.strong_weak = strong_weak_split(in.contacts, scale, in.volume);
  if (options.resamples > 0)
    c.bootstrap = bootstrap_coefficients(in.contacts, scale, in.friction, options.resamples, options.seed);
  return c;
}

const std::vector<std::string>& analysis_columns() {
  static const std::vector<std::string> names = [] {
    std::vector<std::string> n = {
        "p", "q", "eta", "wall_eta", "wall_stress_error", "wall_layer_ratio", "void_ratio", "coordination",
        "mechanical_coordination", "lambda", "a_c", "a_n", "a_t", "m", "a_c_invariant",
        "a_n_invariant", "a_t_invariant", "m_invariant", "eta_sff", "eta_concise", "eta_decoupled",
        "eta_exact", "sff_error", "branch_ratio", "sliding_fraction"};
    for (const char* t : {"stress", "fabric", "normal", "tangential", "mobilisation"})
      for (const char* f : {"_major", "_axis_x", "_axis_y", "_axis_z", "_tilt_deg"})
        n.push_back(std::string(t) + f);
    // The general form (issue 18): each tensor whole, its invariants, its principal values and
    // minor direction, its alignment with the stress and its triaxial scalar about the stress's
    // major principal axis (tensor_general_row).
    for (const char* t : {"stress", "fabric", "normal", "tangential", "mobilisation"})
      for (const char* f : {"_xx", "_yy", "_zz", "_yz", "_xz", "_xy", "_magnitude", "_lode_deg",
                            "_value_1", "_value_2", "_value_3", "_minor_axis_x", "_minor_axis_y",
                            "_minor_axis_z", "_alignment", "_about_stress_axis"})
        n.push_back(std::string(t) + f);
    // The weights' fallback (sff-theory.md §8) and the Guo & Zhao convention (guo_zhao.h).
    n.insert(n.end(), {"min_density", "binned_weights", "f_0", "l_0", "a_n_gz", "a_t_gz", "a_l",
                       "a_n_gz_invariant", "a_t_gz_invariant", "a_l_invariant", "eta_gz"});
    return n;
  }();
  return names;
}

namespace {

// The general-form columns of one tensor T (analysis_columns): T's components, sqrt(3/2 T':T'),
// its Lode angle, principal values, minor direction, alignment with the stress and the triaxial
// scalar about the stress's major principal direction `stress_axis`.
void append_general_form(std::vector<double>& row, const Eigen::Matrix3d& t,
                         const Eigen::Matrix3d& stress, const Eigen::Vector3d& stress_axis) {
  const TensorInvariants inv = tensor_invariants(t);
  Eigen::Vector3d minor = inv.directions.col(2);
  if (minor.z() < 0.0) minor = -minor;
  row.insert(row.end(), {t(0, 0), t(1, 1), t(2, 2), t(1, 2), t(0, 2), t(0, 1), inv.magnitude,
                         inv.lode_deg, inv.values[0], inv.values[1], inv.values[2], minor.x(),
                         minor.y(), minor.z(), alignment(t, stress),
                         triaxial_about(t, stress_axis)});
}

}  // namespace

std::vector<double> analysis_row(const SnapshotAnalysis& a) {
  std::vector<double> row = {
      a.p, a.q, a.eta, a.wall_eta, a.wall_stress_error, a.wall_layer_ratio, a.void_ratio, a.coordination,
      a.mechanical_coordination, a.lambda, a.a_c, a.a_n, a.a_t, a.m, a.a_c_invariant,
      a.a_n_invariant, a.a_t_invariant, a.m_invariant, a.eta_sff, a.eta_concise, a.eta_decoupled,
      a.eta_exact, a.sff_error, a.branch_ratio, a.sliding_fraction};
  for (const PrincipalAxis* p :
       {&a.stress_axis, &a.fabric_axis, &a.normal_axis, &a.tangential_axis, &a.mobilisation_axis})
    row.insert(row.end(), {p->major, p->axis.x(), p->axis.y(), p->axis.z(), p->tilt_deg});
  for (const Eigen::Matrix3d* t : {&a.stress, &a.fabric, &a.normal, &a.tangential, &a.mobilisation})
    append_general_form(row, *t, a.stress, a.stress_axis.axis);
  const GuoZhaoAnisotropy& g = a.guo_zhao;
  row.insert(row.end(), {a.min_density, a.binned_weights ? 1.0 : 0.0, g.mean_normal_force,
                         g.mean_branch_length, a.a_n_gz, a.a_t_gz, a.a_l, signed_invariant(g.normal),
                         signed_invariant(g.tangential), signed_invariant(g.branch), a.eta_gz});
  return row;
}

const std::vector<std::string>& check_columns() {
  static const std::vector<std::string> names = [] {
    std::vector<std::string> n = {
        "branch_mean_angle_deg", "branch_p95_angle_deg", "pearson_length_force",
        "spearman_length_force"};
    for (const char* q : {"density", "normal_force", "tangential_force"})
      for (const char* f : {"_r2", "_relative_l2", "_chi2_per_dof", "_fourth_order_ratio"})
        n.push_back(std::string(q) + f);
    n.insert(n.end(), {"mobilisation_force_spearman", "mobilisation_force_max_abs_spearman",
                       "mobilisation_coupling_error", "mobilisation_leading_order_error",
                       "coaxiality_fabric_deg", "coaxiality_normal_deg",
                       "coaxiality_tangential_deg", "coaxiality_mobilisation_deg",
                       "strong_fraction", "a_c_strong", "a_c_weak", "strong_q_share",
                       "weak_p_share"});
    for (const char* q : {"a_c", "a_n", "a_t", "m"})
      for (const char* f : {"_low", "_high"}) n.push_back(std::string(q) + f);
    return n;
  }();
  return names;
}

std::vector<double> check_row(const SnapshotChecks& c) {
  std::vector<double> row = {c.branch.mean_angle_deg, c.branch.p95_angle_deg,
                             c.branch.pearson_length_force, c.branch.spearman_length_force};
  for (const TruncationFit* f :
       {&c.truncation.density, &c.truncation.normal_force, &c.truncation.tangential_force})
    row.insert(row.end(), {f->r_squared, f->relative_l2, f->chi2_per_dof, f->fourth_order_ratio});
  row.insert(row.end(),
             {c.independence.mean_spearman, c.independence.max_abs_spearman,
              c.independence.coupling_error, c.independence.leading_order_error,
              c.coaxiality.fabric_deg, c.coaxiality.normal_deg, c.coaxiality.tangential_deg,
              c.coaxiality.mobilisation_deg, c.strong_weak.strong_fraction,
              c.strong_weak.a_c_strong, c.strong_weak.a_c_weak, c.strong_weak.strong_q_share,
              c.strong_weak.weak_p_share});
  for (const Interval* i : {&c.bootstrap.a_c, &c.bootstrap.a_n, &c.bootstrap.a_t, &c.bootstrap.m})
    row.insert(row.end(), {i->low, i->high});
  return row;
}

}  // namespace sff
