#include "sff/analysis.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "contact_stress_pass.h"
#include "force_moments.h"
#include "sff/invariants.h"
#include "sff/sff_equation.h"
#include "sff/statistics.h"
#include "sff/tensors.h"
#include "sffcal/constants.h"
#include "sffcal/format_number.h"

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

namespace {

// Whether one contact of the input is valid (analyse_snapshot): arithmetic on the record without
// branches, cheap beside the stress that the same pass sums.
inline bool contact_is_valid(const ContactRecord& c, int num_bodies) {
  // v * 0 is 0 for a finite v and NaN otherwise; the sum of these tests every number at once
  // (summing the values themselves could overflow), added as a tree to keep the chain short.
  const auto z = [](double v) { return v * 0.0; };
  const double zero =
      ((z(c.point[0]) + z(c.point[1])) + (z(c.point[2]) + z(c.branch[0]))) +
      ((z(c.branch[1]) + z(c.branch[2])) + (z(c.overlap) + z(c.normal_force))) +
      (z(c.tangential_force[0]) + (z(c.tangential_force[1]) + z(c.tangential_force[2])));
  const double length_squared =
      c.normal[0] * c.normal[0] + c.normal[1] * c.normal[1] + c.normal[2] * c.normal[2];
  const bool wall = c.wall >= 0;
  const bool a_ok = wall ? c.body_a == -1
                         : (c.body_a >= 0) & (c.body_a < num_bodies) & (c.body_a != c.body_b);
  return (zero == 0.0) & (std::abs(length_squared - 1.0) <= 2e-6) & (c.body_b >= 0) &
         (c.body_b < num_bodies) & a_ok;
}

// What is wrong with a contact that contact_is_valid refused, in words.
std::string contact_problem(const ContactRecord& c, int num_bodies) {
  const double values[] = {c.point[0], c.point[1], c.point[2], c.branch[0], c.branch[1],
                           c.branch[2], c.overlap, c.normal_force, c.tangential_force[0],
                           c.tangential_force[1], c.tangential_force[2]};
  for (double v : values)
    if (!std::isfinite(v)) return "a number is not finite";
  const double length_squared = normal_of(c).squaredNorm();  // |n| within 1e-6 of 1
  if (!(std::abs(length_squared - 1.0) <= 2e-6))
    return "the normal is not a unit vector (length " +
           sffcal::format_number(std::sqrt(length_squared)) + ")";
  if (c.body_b < 0 || c.body_b >= num_bodies)
    return "body_b " + std::to_string(c.body_b) + " is not in [0, num_bodies)";
  if (c.wall >= 0) return "a wall contact's body_a must be -1";
  if (c.body_a < 0 || c.body_a >= num_bodies || c.body_a == c.body_b)
    return "body_a " + std::to_string(c.body_a) +
           " is not another body in [0, num_bodies) (or give the wall's index)";
  return {};
}

}  // namespace

namespace {

// The input's checks but the contacts' (analyse_snapshot).
void check_snapshot_scalars(const SnapshotInput& in) {
  const auto number = sffcal::format_number;
  const auto require = [](bool ok, const std::string& what) {
    if (!ok) throw std::invalid_argument(what);
  };
  require(in.volume > 0.0 && std::isfinite(in.volume),
          "the volume must be positive [m^3], not " + number(in.volume));
  require(in.solid_volume > 0.0 && in.solid_volume <= in.volume,
          "the solid volume must be positive and at most the volume [m^3], not " +
              number(in.solid_volume));
  require(in.num_bodies > 0, "the number of bodies must be positive");
  require(in.youngs_modulus > 0.0 && std::isfinite(in.youngs_modulus),
          "Young's modulus must be positive [Pa], not " + number(in.youngs_modulus));
  require(in.friction > 0.0 && std::isfinite(in.friction),
          "the friction coefficient must be positive, not " + number(in.friction));
  require(in.wall_stress.allFinite(), "the wall stress must be finite");
  require(in.centroids.empty() || in.centroids.size() == static_cast<std::size_t>(in.num_bodies),
          "give one centroid per body (" + std::to_string(in.num_bodies) + "), not " +
              std::to_string(in.centroids.size()));
  for (const Eigen::Vector3d& x : in.centroids) require(x.allFinite(), "a centroid is not finite");
}

[[noreturn]] void refuse_contact(const SnapshotInput& in, std::size_t k) {
  throw std::invalid_argument("contact " + std::to_string(k) + ": " +
                              contact_problem(in.contacts[k], in.num_bodies));
}

}  // namespace

SnapshotAnalysis analyse_snapshot(const SnapshotInput& in) {
  check_snapshot_scalars(in);
  SnapshotAnalysis a;
  // The contacts are checked in the stress's pass, before anything indexes by their body ids.
  std::size_t first_bad = in.contacts.size();
  a.stress = internal::contact_stress_pass(
      in.contacts, in.volume, [&](std::size_t k, const ContactRecord& c) {
        if (!contact_is_valid(c, in.num_bodies) && first_bad == in.contacts.size()) first_bad = k;
      });
  if (first_bad < in.contacts.size()) refuse_contact(in, first_bad);
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

namespace {

// The general-form columns of one tensor T: T's components, sqrt(3/2 T':T'), its Lode angle,
// principal values, minor direction, alignment with the stress and the triaxial scalar about the
// stress's major principal direction `stress_axis`.
template <typename Column>
void general_form_columns(const std::string& name, const Eigen::Matrix3d& t,
                          const Eigen::Matrix3d& stress, const Eigen::Vector3d& stress_axis,
                          Column&& column) {
  const TensorInvariants inv = tensor_invariants(t);
  Eigen::Vector3d minor = inv.directions.col(2);
  if (minor.z() < 0.0) minor = -minor;
  column(name + "_xx", t(0, 0));
  column(name + "_yy", t(1, 1));
  column(name + "_zz", t(2, 2));
  column(name + "_yz", t(1, 2));
  column(name + "_xz", t(0, 2));
  column(name + "_xy", t(0, 1));
  column(name + "_magnitude", inv.magnitude);
  column(name + "_lode_deg", inv.lode_deg);
  column(name + "_value_1", inv.values[0]);
  column(name + "_value_2", inv.values[1]);
  column(name + "_value_3", inv.values[2]);
  column(name + "_minor_axis_x", minor.x());
  column(name + "_minor_axis_y", minor.y());
  column(name + "_minor_axis_z", minor.z());
  column(name + "_alignment", alignment(t, stress));
  column(name + "_about_stress_axis", triaxial_about(t, stress_axis));
}

// The columns of the per-snapshot SFF table, each declared once with its value: column(name,
// value) in the table's order. analysis_columns() keeps the names (of a default analysis),
// analysis_row() the values.
template <typename Column>
void analysis_table_columns(const SnapshotAnalysis& a, Column&& column) {
  const std::pair<const char*, double> scalars[] = {
      {"p", a.p}, {"q", a.q}, {"eta", a.eta}, {"wall_eta", a.wall_eta},
      {"wall_stress_error", a.wall_stress_error}, {"wall_layer_ratio", a.wall_layer_ratio},
      {"void_ratio", a.void_ratio}, {"coordination", a.coordination},
      {"mechanical_coordination", a.mechanical_coordination}, {"lambda", a.lambda},
      {"a_c", a.a_c}, {"a_n", a.a_n}, {"a_t", a.a_t}, {"m", a.m},
      {"a_c_invariant", a.a_c_invariant}, {"a_n_invariant", a.a_n_invariant},
      {"a_t_invariant", a.a_t_invariant}, {"m_invariant", a.m_invariant},
      {"eta_sff", a.eta_sff}, {"eta_concise", a.eta_concise}, {"eta_decoupled", a.eta_decoupled},
      {"eta_exact", a.eta_exact}, {"sff_error", a.sff_error}, {"branch_ratio", a.branch_ratio},
      {"sliding_fraction", a.sliding_fraction}};
  for (const auto& [name, value] : scalars) column(name, value);
  const std::pair<const char*, const PrincipalAxis*> axes[] = {
      {"stress", &a.stress_axis}, {"fabric", &a.fabric_axis}, {"normal", &a.normal_axis},
      {"tangential", &a.tangential_axis}, {"mobilisation", &a.mobilisation_axis}};
  for (const auto& [name, axis] : axes) {
    const std::string t = name;
    column(t + "_major", axis->major);
    column(t + "_axis_x", axis->axis.x());
    column(t + "_axis_y", axis->axis.y());
    column(t + "_axis_z", axis->axis.z());
    column(t + "_tilt_deg", axis->tilt_deg);
  }
  // The general form (issue 18): each tensor whole, its invariants, its principal values and
  // minor direction, its alignment with the stress and its triaxial scalar about the stress's
  // major principal axis.
  const std::pair<const char*, const Eigen::Matrix3d*> tensors[] = {
      {"stress", &a.stress}, {"fabric", &a.fabric}, {"normal", &a.normal},
      {"tangential", &a.tangential}, {"mobilisation", &a.mobilisation}};
  for (const auto& [name, tensor] : tensors)
    general_form_columns(name, *tensor, a.stress, a.stress_axis.axis, column);
  // The weights' fallback (sff-theory.md §8) and the Guo & Zhao convention (guo_zhao.h).
  const GuoZhaoAnisotropy& g = a.guo_zhao;
  const std::pair<const char*, double> tail[] = {
      {"min_density", a.min_density}, {"binned_weights", a.binned_weights ? 1.0 : 0.0},
      {"f_0", g.mean_normal_force}, {"l_0", g.mean_branch_length}, {"a_n_gz", a.a_n_gz},
      {"a_t_gz", a.a_t_gz}, {"a_l", a.a_l}, {"a_n_gz_invariant", signed_invariant(g.normal)},
      {"a_t_gz_invariant", signed_invariant(g.tangential)},
      {"a_l_invariant", signed_invariant(g.branch)}, {"eta_gz", a.eta_gz}};
  for (const auto& [name, value] : tail) column(name, value);
}

// The columns of the per-snapshot table of checks, declared once (as analysis_table_columns).
template <typename Column>
void check_table_columns(const SnapshotChecks& c, Column&& column) {
  column("branch_mean_angle_deg", c.branch.mean_angle_deg);
  column("branch_p95_angle_deg", c.branch.p95_angle_deg);
  column("pearson_length_force", c.branch.pearson_length_force);
  column("spearman_length_force", c.branch.spearman_length_force);
  const std::pair<const char*, const TruncationFit*> fits[] = {
      {"density", &c.truncation.density}, {"normal_force", &c.truncation.normal_force},
      {"tangential_force", &c.truncation.tangential_force}};
  for (const auto& [name, fit] : fits) {
    const std::string q = name;
    column(q + "_r2", fit->r_squared);
    column(q + "_relative_l2", fit->relative_l2);
    column(q + "_chi2_per_dof", fit->chi2_per_dof);
    column(q + "_fourth_order_ratio", fit->fourth_order_ratio);
  }
  const std::pair<const char*, double> scalars[] = {
      {"mobilisation_force_spearman", c.independence.mean_spearman},
      {"mobilisation_force_max_abs_spearman", c.independence.max_abs_spearman},
      {"mobilisation_coupling_error", c.independence.coupling_error},
      {"mobilisation_leading_order_error", c.independence.leading_order_error},
      {"coaxiality_fabric_deg", c.coaxiality.fabric_deg},
      {"coaxiality_normal_deg", c.coaxiality.normal_deg},
      {"coaxiality_tangential_deg", c.coaxiality.tangential_deg},
      {"coaxiality_mobilisation_deg", c.coaxiality.mobilisation_deg},
      {"strong_fraction", c.strong_weak.strong_fraction},
      {"a_c_strong", c.strong_weak.a_c_strong}, {"a_c_weak", c.strong_weak.a_c_weak},
      {"strong_q_share", c.strong_weak.strong_q_share},
      {"weak_p_share", c.strong_weak.weak_p_share}};
  for (const auto& [name, value] : scalars) column(name, value);
  const std::pair<const char*, const Interval*> intervals[] = {
      {"a_c", &c.bootstrap.a_c}, {"a_n", &c.bootstrap.a_n}, {"a_t", &c.bootstrap.a_t},
      {"m", &c.bootstrap.m}};
  for (const auto& [name, interval] : intervals) {
    column(std::string(name) + "_low", interval->low);
    column(std::string(name) + "_high", interval->high);
  }
}

template <typename Visit>
std::vector<std::string> names_of(Visit&& visit) {
  std::vector<std::string> names;
  visit([&](const std::string& name, double) { names.push_back(name); });
  return names;
}

}  // namespace

const std::vector<std::string>& analysis_columns() {
  static const std::vector<std::string> names = names_of(
      [](auto&& column) { analysis_table_columns(SnapshotAnalysis(), column); });
  return names;
}

std::vector<double> analysis_row(const SnapshotAnalysis& a) {
  std::vector<double> row;
  analysis_table_columns(a, [&](const std::string&, double value) { row.push_back(value); });
  return row;
}

const std::vector<std::string>& check_columns() {
  static const std::vector<std::string> names =
      names_of([](auto&& column) { check_table_columns(SnapshotChecks(), column); });
  return names;
}

std::vector<double> check_row(const SnapshotChecks& c) {
  std::vector<double> row;
  check_table_columns(c, [&](const std::string&, double value) { row.push_back(value); });
  return row;
}

}  // namespace sff
