// The deal.II-free facade of acst_check.h: the material-point driver, the FE triaxial runs with the
// ACST adapter, and the curve comparisons.
#include "fe_model/acst_check.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <iomanip>
#include <limits>
#include <sstream>
#include <nlohmann/json.hpp>
#include <stdexcept>

#include "model/material_point.h"
#include "fe_model/acst_material.h"
#include "fe_model/triaxial.h"
#include "sffcal/output_file.h"

namespace fe_model {
namespace {


double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// Linear interpolation of a curve's member at axial strain x (points sorted by axial strain).
double interpolate(const std::vector<CurvePoint>& points, double x, double CurvePoint::*member) {
  if (x <= points.front().axial_strain) return points.front().*member;
  for (std::size_t i = 1; i < points.size(); ++i) {
    const CurvePoint& a = points[i - 1];
    const CurvePoint& b = points[i];
    if (x <= b.axial_strain) {
      const double span = b.axial_strain - a.axial_strain;
      const double w = span > 0.0 ? (x - a.axial_strain) / span : 1.0;
      return (1.0 - w) * (a.*member) + w * (b.*member);
    }
  }
  return points.back().*member;
}

// The model integrates no state below its minimum mean stress, so a specimen confined below it is
// refused before the first step (the FE solver would otherwise cut that step to nothing).
std::string refused_confinement(const AcstSpecimen& specimen, const TriaxialLoading& loading) {
  if (specimen.confining_pressure >= loading.integration.min_pressure) return "";
  std::ostringstream message;
  message << "confining pressure " << specimen.confining_pressure
          << " Pa is below the model's minimum mean stress " << loading.integration.min_pressure
          << " Pa (model::acst::IntegrationOptions::min_pressure)";
  return message.str();
}

}  // namespace

Curve run_acst_driver_triaxial(const model::acst::Parameters<double>& parameters,
                               const AcstSpecimen& specimen, const TriaxialLoading& loading) {
  const auto t0 = std::chrono::steady_clock::now();
  // model::acst::drained_triaxial's path, increment by increment through the public
  // model::acst::mixed_increment, so that an increment whose Newton iterate keeps changing one of
  // the integrator's discrete substep choices can be retried with a looser stress tolerance:
  // 1e-9 p first (above the integration noise, about 1e-10 |sigma| at the tight tolerance), then
  // 1e-8 p (the driver's default). The lateral stresses are held at sigma_3, no shear strain.
  model::acst::DriverOptions options;
  options.integration = loading.integration;
  options.max_newton_iterations = 50;
  const model::acst::State<double> initial = model::acst::isotropic_state(
      specimen.confining_pressure, specimen.void_ratio, Eigen::Matrix3d(specimen.fabric));
  const double sigma_3 = specimen.confining_pressure;
  const double d_axial = loading.axial_strain_end / std::max(loading.n_steps, 1u);
  const std::array<model::acst::Control, 6> control = {
      {model::acst::Control::kStress, model::acst::Control::kStress, model::acst::Control::kStrain,
       model::acst::Control::kStrain, model::acst::Control::kStrain, model::acst::Control::kStrain}};
  const std::array<double, 6> value = {{sigma_3, sigma_3, d_axial, 0.0, 0.0, 0.0}};

  Curve curve;
  curve.label = "driver";
  curve.message = refused_confinement(specimen, loading);
  if (!curve.message.empty()) return curve;
  model::acst::State<double> state = initial;
  Eigen::Matrix3d strain = Eigen::Matrix3d::Zero();
  Eigen::Matrix3d guess = Eigen::Matrix3d::Zero();
  auto record = [&](model::acst::UpdateStatus status) {
    const model::acst::PointRecord<double> row =
        model::acst::make_record(parameters, state, strain, status);
    CurvePoint point;
    point.axial_strain = row.axial_strain;
    point.volumetric_strain = row.volumetric_strain;
    point.p = row.p;
    point.q = row.q;
    point.void_ratio = row.void_ratio;
    point.fabric_invariant = model::acst::kSqrtTwoThirds * row.fabric_triaxial;  // F : n_c
    point.status = model::acst::to_string(status);
    curve.points.push_back(point);
  };
  record(model::acst::UpdateStatus::kOk);
  // An increment that fails at both tolerances is halved (as the FE solver cuts its step), down
  // to kMaxHalvings; the curve still gets one point per step, so that it lines up with the FE's.
  constexpr int kMaxHalvings = 6;
  for (unsigned int k = 0; k < loading.n_steps && curve.message.empty(); ++k) {
    model::acst::UpdateStatus worst = model::acst::UpdateStatus::kOk;
    double remaining = 1.0;  // fraction of the step still to apply
    double fraction = 1.0;   // fraction tried next
    while (remaining > 0.0) {
      fraction = std::min(fraction, remaining);
      std::array<double, 6> part = value;
      part[2] = fraction * d_axial;
      model::acst::UpdateStatus status = model::acst::UpdateStatus::kFailed;
      Eigen::Matrix3d deps;
      model::acst::State<double> next;
      for (const double tolerance : {1e-9, 1e-8}) {
        options.stress_tolerance = tolerance;
        deps = fraction * guess;
        status = model::acst::mixed_increment(parameters, state, control, part, deps, next, options);
        if (status != model::acst::UpdateStatus::kFailed) break;
        ++curve.cuts;  // counted as a retry
      }
      if (status == model::acst::UpdateStatus::kFailed) {
        if (fraction > std::ldexp(1.0, -kMaxHalvings)) {
          fraction *= 0.5;
          ++curve.cuts;
          continue;
        }
        curve.message = "material-point driver: increment " + std::to_string(k + 1) +
                        " failed at axial strain " + std::to_string(strain(2, 2)) + " after " +
                        std::to_string(kMaxHalvings) +
                        " halvings (model update failure, or no Newton convergence to 1e-8 p)";
        break;
      }
      if (status == model::acst::UpdateStatus::kUnreliable) worst = status;
      state = next;
      strain += deps;
      guess = deps / fraction;
      remaining -= fraction;
    }
    if (curve.message.empty()) record(worst);
  }
  curve.completed = curve.message.empty();
  curve.wall_seconds = seconds_since(t0);
  return curve;
}

Curve run_acst_fe_triaxial(const model::acst::Parameters<double>& parameters,
                           const AcstSpecimen& specimen, const TriaxialLoading& loading,
                           const TriaxialMeshOptions& mesh) {
  const std::string refused = refused_confinement(specimen, loading);
  if (!refused.empty()) {
    Curve curve;
    curve.label = mesh.cells_x * mesh.cells_y * mesh.cells_z == 1 ? "element" : "mesh";
    curve.message = refused;
    return curve;
  }
  AcstInitialState initial;
  initial.void_ratio = specimen.void_ratio;
  initial.fabric = specimen.fabric;
  const AcstMaterial material(parameters, initial, loading.integration);
  return run_fe_triaxial(material, specimen.confining_pressure, loading, mesh);
}

Curve run_fe_triaxial(const Material& material, double confining_pressure,
                      const TriaxialLoading& loading, const TriaxialMeshOptions& mesh) {
  const auto t0 = std::chrono::steady_clock::now();
  TriaxialOptions options;
  options.width = mesh.width;
  options.height = mesh.height;
  options.cells_x = mesh.cells_x;
  options.cells_y = mesh.cells_y;
  options.cells_z = mesh.cells_z;
  options.confining_pressure = confining_pressure;
  options.axial_strain_end = loading.axial_strain_end;
  options.n_steps = loading.n_steps;
  options.solver.residual_rtol = mesh.residual_rtol;
  options.solver.residual_atol = mesh.residual_atol;
  options.solver.max_newton_iterations = mesh.max_newton_iterations;
  options.solver.max_cuts = mesh.max_cuts;
  options.solver.wall_time_limit = mesh.wall_time_limit;
  options.solver.verbose = mesh.verbose;
  options.vtu_prefix = mesh.vtu_prefix;
  const TriaxialResult result = run_triaxial(material, options);

  Curve curve;
  curve.label = mesh.cells_x * mesh.cells_y * mesh.cells_z == 1 ? "element" : "mesh";
  curve.completed = result.completed;
  curve.message = result.message;
  for (const TriaxialStep& step : result.steps) {
    CurvePoint point;
    point.axial_strain = step.axial_strain;
    point.volumetric_strain = step.volumetric_strain;
    point.p = step.p;
    point.q = step.q;
    // Internal variable 0 of both adapters is the void ratio (acst_material.h,
    // network_material.h).
    point.void_ratio = step.internal_variables.empty()
                           ? std::numeric_limits<double>::quiet_NaN()
                           : step.internal_variables[0];
    point.fabric_invariant = step.fabric_invariant.value_or(0.0);
    point.newton_iterations = step.newton_iterations;
    point.cuts = step.cuts;
    point.status = to_string(step.worst_status);
    point.residual_norms = step.residual_norms;
    curve.newton_iterations += step.newton_iterations;
    curve.cuts += step.cuts;
    curve.points.push_back(point);
  }
  // Cuts of a failed last step count too (they were work done).
  if (!result.completed && !result.reports.empty()) curve.cuts += result.reports.back().cuts;
  curve.wall_seconds = seconds_since(t0);
  return curve;
}

PathError compare_paths(const Curve& curve, const Curve& reference) {
  PathError error;
  const std::size_t n = std::min(curve.points.size(), reference.points.size());
  double dq = 0.0, dv = 0.0, q_scale = 0.0, v_scale = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    const CurvePoint& a = curve.points[i];
    const CurvePoint& r = reference.points[i];
    dq = std::max(dq, std::abs(a.q - r.q));
    dv = std::max(dv, std::abs(a.volumetric_strain - r.volumetric_strain));
    q_scale = std::max(q_scale, std::abs(r.q));
    v_scale = std::max(v_scale, std::abs(r.volumetric_strain));
    error.axial_strain_mismatch =
        std::max(error.axial_strain_mismatch, std::abs(a.axial_strain - r.axial_strain));
  }
  error.points = n;
  error.q = q_scale > 0.0 ? dq / q_scale : dq;
  error.volumetric_strain = v_scale > 0.0 ? dv / v_scale : dv;
  return error;
}

DemError compare_with_dem(const Curve& model, const Curve& dem) {
  DemError error;
  if (model.points.empty()) return error;
  const double end = model.points.back().axial_strain;
  double se = 0.0, sv = 0.0;
  for (const CurvePoint& d : dem.points) {
    if (d.axial_strain < 0.0 || d.axial_strain > end) continue;
    const double q = interpolate(model.points, d.axial_strain, &CurvePoint::q);
    const double p = interpolate(model.points, d.axial_strain, &CurvePoint::p);
    const double v = interpolate(model.points, d.axial_strain, &CurvePoint::volumetric_strain);
    se += std::pow(q / p - d.eta(), 2);
    sv += std::pow(v - d.volumetric_strain, 2);
    ++error.points;
  }
  if (error.points > 0) {
    error.eta_rms = std::sqrt(se / static_cast<double>(error.points));
    error.volumetric_strain_rms = std::sqrt(sv / static_cast<double>(error.points));
  }
  return error;
}

Eigen::Matrix3d fabric_from_dem_anisotropy(double a_c, double a_cs) {
  if (!(a_cs > 0.0) || !std::isfinite(a_cs))
    throw std::invalid_argument("a_cs must be positive (got " + std::to_string(a_cs) + ")");
  Eigen::Matrix3d A = Eigen::Matrix3d::Zero();
  A(0, 0) = A(1, 1) = -a_c / 3.0;
  A(2, 2) = 2.0 * a_c / 3.0;
  return A / a_cs;
}

std::optional<double> fabric_normalisation(const model::ParameterValues& values,
                                           const std::string& parameter_path) {
  const nlohmann::json root = nlohmann::json::parse(values.rest);  // the reader's own dump
  auto value_of = [&](const nlohmann::json& entry, const std::string& key) -> std::optional<double> {
    double v = 0.0;
    if (entry.is_number()) {
      v = entry.get<double>();
    } else if (entry.is_object() && entry.contains("value") && entry["value"].is_number()) {
      v = entry["value"].get<double>();
    } else {
      throw std::runtime_error("parameter file '" + parameter_path + "': key '" + key +
                               "' must be a number or {\"value\": number}");
    }
    if (!(v > 0.0) || !std::isfinite(v))
      throw std::runtime_error("parameter file '" + parameter_path + "': '" + key +
                               "' must be positive");
    return v;
  };
  if (!root.is_object()) return std::nullopt;
  if (root.contains("a_cs")) return value_of(root["a_cs"], "a_cs");
  // `sffcal calibrate` writes it under fabric_normalisation; hand-written files may use either.
  for (const char* group : {"fabric_normalisation", "parameters"})
    if (root.contains(group) && root[group].is_object() && root[group].contains("a_cs"))
      return value_of(root[group]["a_cs"], std::string(group) + ".a_cs");
  return std::nullopt;
}

void write_curve_csv(const std::string& path, const Curve& curve) {
  sffcal::OutputFile file(path);
  std::ostream& out = file.stream();
  out << "# sffcal fe-check curve '" << curve.label
      << "'; compression positive; stresses in Pa; fabric_invariant = F:n_c\n";
  out << "axial_strain,volumetric_strain,p,q,eta,void_ratio,fabric_invariant,newton_iterations,"
         "cuts,status\n";
  out << std::setprecision(15);
  for (const CurvePoint& point : curve.points) {
    out << point.axial_strain << ',' << point.volumetric_strain << ',' << point.p << ','
        << point.q << ',' << point.eta() << ',' << point.void_ratio << ','
        << point.fabric_invariant << ',' << point.newton_iterations << ',' << point.cuts << ','
        << point.status << '\n';
  }
  file.commit();
}

}  // namespace fe_model
