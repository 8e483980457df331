#include "fe_model/fe_check.h"

#include <chrono>
#include <cmath>
#include <cstdarg>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <limits>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "model/acst_model.h"
#include "fe_model/acst_check.h"
#include "runfile/dem_test.h"

#ifdef SFFCAL_FE_CHECK_NETWORK
#include "calibration/network_fit.h"
#include "fe_model/network_material.h"
#endif

namespace fe_model {
namespace {

namespace fs = std::filesystem;

__attribute__((format(printf, 1, 2))) std::string format(const char* pattern, ...) {
  char buffer[512];
  va_list args;
  va_start(args, pattern);
  std::vsnprintf(buffer, sizeof buffer, pattern, args);
  va_end(args);
  return buffer;
}

constexpr double kVerificationTolerance = 1e-8;

struct DemRun {
  std::string path;
  std::string name;
  double confining_pressure = 0.0;  // /series/sigma_3 of the first row
  double void_ratio = 0.0;          // /series/void_ratio of the first row
  std::optional<double> initial_a_c;  // /analysis/sff/a_c at the smallest axial strain
  Curve curve;   // the series
  Curve fabric;  // the /analysis/sff rows (with the fabric invariant)
};

CurvePoint curve_point(double axial_strain, double volumetric_strain, double p, double q,
                       double void_ratio, double fabric_invariant) {
  CurvePoint point;
  point.axial_strain = axial_strain;
  point.volumetric_strain = volumetric_strain;
  point.p = p;
  point.q = q;
  point.void_ratio = void_ratio;
  point.fabric_invariant = fabric_invariant;
  return point;
}

// The DEM run as fe-check compares it, from the run file at `path` read once (runfile::DemTest).
DemRun dem_run(const runfile::DemTest& test, const std::string& path, double a_cs) {
  if (test.loading_path() != "drained_compression")
    throw std::runtime_error(path + ": loading path " + test.loading_path() +
                             ": fe-check compares drained compression only");
  const runfile::DemTestSeries& s = test.series;
  if (s.axial_strain.empty()) throw std::runtime_error(path + ": /series is empty");
  DemRun run;
  run.path = path;
  run.name = test.name;
  run.confining_pressure = s.sigma_3.front();
  run.void_ratio = s.void_ratio.front();
  run.curve.label = "dem";
  run.curve.completed = true;
  constexpr double kNone = std::numeric_limits<double>::quiet_NaN();
  for (std::size_t i = 0; i < s.axial_strain.size(); ++i)
    run.curve.points.push_back(
        curve_point(s.axial_strain[i], s.volumetric_strain[i], s.p[i], s.q[i], s.void_ratio[i], kNone));
  if (test.analysed && !test.sff.axial_strain.empty()) {
    const runfile::DemTestSff& f = test.sff;
    run.fabric.label = "dem_fabric";
    run.fabric.completed = true;
    std::size_t first = 0;
    for (std::size_t i = 0; i < f.axial_strain.size(); ++i) {
      const double fabric = model::acst::kSqrtTwoThirds * f.a_c[i] / a_cs;  // A_DEM : n_c / a_cs
      run.fabric.points.push_back(curve_point(f.axial_strain[i], kNone, f.p[i], f.q[i], f.void_ratio[i], fabric));
      if (f.axial_strain[i] < f.axial_strain[first]) first = i;
    }
    run.initial_a_c = f.a_c[first];
  }
  return run;
}

struct Case {
  std::string name;
  AcstSpecimen specimen;
  const DemRun* dem = nullptr;
  std::string fabric_source;
};

std::string pressure_name(double pressure) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "p%gkPa", pressure / 1e3);
  return buffer;
}

std::string run_line(const Curve& curve, unsigned int steps) {
  char buffer[256];
  std::snprintf(buffer, sizeof buffer, "%-8s %-9s %4zu/%-4u steps  %5d Newton  %3d cuts  %8.2f s",
                curve.label.c_str(), curve.completed ? "completed" : "STOPPED",
                curve.points.empty() ? std::size_t{0} : curve.points.size() - 1, steps,
                curve.newton_iterations, curve.cuts, curve.wall_seconds);
  std::string line = buffer;
  if (!curve.completed) line += "\n           " + curve.message;
  return line;
}

void add_path_checks(std::vector<FeCheckRow>& rows, const std::string& case_name,
                     const std::string& check, const Curve& curve, const Curve& reference,
                     double tolerance = kVerificationTolerance) {
  const PathError error = compare_paths(curve, reference);
  const bool complete = curve.completed && reference.completed;
  const bool aligned = error.axial_strain_mismatch <= 1e-12;
  std::string note;
  if (!complete) note = "a run stopped early: compared over " + std::to_string(error.points) +
                        " common points";
  if (!aligned) note += (note.empty() ? "" : "; ") + std::string("axial strains differ");
  for (int k = 0; k < 2; ++k) {
    FeCheckRow row;
    row.case_name = case_name;
    row.check = check;
    row.quantity = k == 0 ? "q (max rel.)" : "eps_v (max rel.)";
    row.value = k == 0 ? error.q : error.volumetric_strain;
    row.tolerance = tolerance;
    row.pass = complete && aligned && std::isfinite(row.value) && row.value <= row.tolerance;
    row.note = note;
    rows.push_back(row);
  }
}

std::string format_value(double v) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.3g", v);
  return buffer;
}

// The 2x2x4 mesh of every case, its VTU files in <folder>/vtu/.
AcstMeshOptions check_mesh_options(const fs::path& folder, bool verbose) {
  AcstMeshOptions mesh;
  mesh.cells_x = mesh.cells_y = 2;
  mesh.cells_z = 4;
  mesh.verbose = verbose;
  fs::create_directories(folder / "vtu");
  mesh.vtu_prefix = (folder / "vtu" / "mesh").string();
  return mesh;
}

// The DEM run's curves beside the case's, and the FE-vs-DEM rows (calibration quality).
void add_dem_checks(std::vector<FeCheckRow>& checks, const std::string& case_name,
                    const fs::path& folder, const Curve& element, const DemRun& dem,
                    const FeCheckOptions& options) {
  write_curve_csv((folder / "dem.csv").string(), dem.curve);
  if (!dem.fabric.points.empty()) write_curve_csv((folder / "dem_fabric.csv").string(), dem.fabric);
  const DemError error = compare_with_dem(element, dem.curve);
  const std::string note =
      std::to_string(error.points) + " DEM points to eps_a = " +
      format_value(element.points.empty() ? 0.0 : element.points.back().axial_strain);
  FeCheckRow eta{case_name, "FE vs DEM", "q/p (RMS)", error.eta_rms, options.dem_eta_tolerance,
                 error.points > 0 && error.eta_rms <= options.dem_eta_tolerance, false, note};
  FeCheckRow ev{case_name,
                "FE vs DEM",
                "eps_v (RMS)",
                error.volumetric_strain_rms,
                options.dem_volumetric_tolerance,
                error.points > 0 && error.volumetric_strain_rms <= options.dem_volumetric_tolerance,
                false,
                note};
  checks.push_back(eta);
  checks.push_back(ev);
}

void write_summary(const fs::path& out_folder, const std::vector<FeCheckRow>& checks) {
  std::ofstream summary(out_folder / "summary.csv");
  summary << "case,check,quantity,value,tolerance,result,note\n" << std::setprecision(6);
  for (const FeCheckRow& row : checks)
    summary << row.case_name << ',' << row.check << ',' << row.quantity << ',' << row.value << ','
            << row.tolerance << ',' << (row.pass ? "pass" : "fail") << ",\"" << row.note << "\"\n";
  if (!summary) throw std::runtime_error("cannot write " + (out_folder / "summary.csv").string());
}

#ifdef SFFCAL_FE_CHECK_NETWORK
// The contact-network model (docs/network-model.md) on the DEM runs' cases: its network starts
// from each run's first snapshot, so there are no plain pressure cases. The driver holds the
// lateral stress at sigma_3, as the element's confining traction does (the initial SFF stress
// differs from it by the initial anisotropies). Element and driver solve the same increments with
// RK4 substeps chosen from different strain norms (the FE update's whole increment, the driver's
// axial one), so they agree to the integration error, not to round-off: kNetworkDriverTolerance.
constexpr double kNetworkDriverTolerance = 1e-6;

FeCheckResult run_network_fe_check(const FeCheckOptions& options,
                                   const model::ParameterValues& values, const FeCheckLog& log) {
  namespace net = calibration::network;
  if (options.dem_runs.empty())
    throw std::invalid_argument("the contact-network model starts from a DEM run's network (Z, "
                                "Lambda, anisotropies): give it with --dem RUN.h5");
  const double youngs_modulus = values.constants.at(0);
  const model::network::Parameters<double> parameters =
      model::network::from_array(values.parameters.data());
  const fs::path out_folder(options.output_folder);
  fs::create_directories(out_folder);
  AcstLoading loading;
  loading.axial_strain_end = options.max_strain;
  loading.n_steps = options.steps;
  log(format("sffcal fe-check: contact-network parameters %s, E = %.4g Pa",
             options.parameters_path.c_str(), youngs_modulus));
  log(format("drained triaxial compression to axial strain %.3g in %u steps; output in %s/ "
             "(the plain pressure cases need an initial network: not run)",
             options.max_strain, options.steps, out_folder.string().c_str()));
  FeCheckResult result;
  for (const std::string& path : options.dem_runs) {
    // The network's fabric invariant is a_c itself: A:n_c / a_cs with a_cs = sqrt(2/3).
    const runfile::DemTest run = runfile::read_dem_test(path);  // read once for both uses
    const DemRun dem = dem_run(run, path, model::acst::kSqrtTwoThirds);
    const calibration::TestData test =
        net::with_closing_normal_anisotropy(calibration::test_data(run, path));
    const model::network::State<double> start = net::initial_state(test);
    NetworkInitialState initial;
    initial.void_ratio = start.void_ratio;
    initial.coordination = start.coordination;
    initial.fabric = start.fabric;
    initial.normal = start.normal;
    initial.tangential = start.tangential;
    const NetworkMaterial material(parameters, initial, youngs_modulus);
    const fs::path folder = out_folder / dem.name;
    fs::create_directories(folder);
    log(format("\ncase %s: sigma_3 = %.4g kPa, e_0 = %.4g, Z_0 = %.4g, a_c0 = %.3g, a_n0 = %.3g",
               dem.name.c_str(), dem.confining_pressure / 1e3, initial.void_ratio,
               initial.coordination, model::network::triaxial_part(start.fabric),
               model::network::triaxial_part(start.normal)));

    // The material point on the element's axial strains, from the element's initial state.
    const auto t0 = std::chrono::steady_clock::now();
    const model::network::State<double> point0 = material.to_model(
        material.initial_state(-dem.confining_pressure * dealii::unit_symmetric_tensor<3>()));
    calibration::TestData path_test = test;
    path_test.axial_strain.clear();
    for (unsigned int k = 0; k <= options.steps; ++k)
      path_test.axial_strain.push_back(options.max_strain * k / options.steps);
    const std::size_t n = path_test.axial_strain.size();
    path_test.volumetric_strain.assign(n, 0.0);
    path_test.eta.assign(n, 0.0);
    path_test.void_ratio.assign(n, initial.void_ratio);
    path_test.p.assign(n, dem.confining_pressure);
    path_test.snapshot_axial_strain = {0.0};
    path_test.coordination = {point0.coordination};
    path_test.lambda = {point0.lambda};
    path_test.a_c = {test.a_c.front()};
    path_test.a_n = {test.a_n.front()};
    path_test.a_t = {test.a_t.front()};
    path_test.mobilisation = path_test.snapshot_eta = {0.0};
    net::FitOptions driver_options;  // the element's substeps (network_update.h)
    driver_options.substep_size = model::network::kUpdateSubstepSize;
    const net::Curve point = net::predict(parameters, path_test, driver_options,
                                          dem.confining_pressure);  // the FE's traction
    Curve driver;
    driver.label = "driver";
    driver.completed = point.complete;
    driver.message = point.message;
    for (std::size_t k = 0; k < point.axial_strain.size(); ++k)
      driver.points.push_back(curve_point(point.axial_strain[k], point.volumetric_strain[k],
                                          point.p[k], point.q[k], point.void_ratio[k],
                                          point.a_c[k]));
    driver.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    write_curve_csv((folder / "driver.csv").string(), driver);
    log("  " + run_line(driver, options.steps));

    AcstMeshOptions element_options;
    element_options.verbose = options.verbose;
    const Curve element = run_fe_triaxial(material, dem.confining_pressure, loading, element_options);
    write_curve_csv((folder / "element.csv").string(), element);
    log("  " + run_line(element, options.steps));
    result.runs_completed = result.runs_completed && driver.completed && element.completed;
    add_path_checks(result.checks, dem.name, "element vs driver", element, driver,
                    kNetworkDriverTolerance);
    if (options.mesh) {
      const Curve mesh = run_fe_triaxial(material, dem.confining_pressure, loading,
                                         check_mesh_options(folder, options.verbose));
      write_curve_csv((folder / "mesh.csv").string(), mesh);
      log("  " + run_line(mesh, options.steps));
      result.runs_completed = result.runs_completed && mesh.completed;
      add_path_checks(result.checks, dem.name, "mesh vs element", mesh, element);
    }
    add_dem_checks(result.checks, dem.name, folder, element, dem, options);
  }
  write_summary(out_folder, result.checks);
  return result;
}

#endif  // SFFCAL_FE_CHECK_NETWORK

}  // namespace

FeCheckResult run_fe_check(const FeCheckOptions& options, const FeCheckLog& log) {
  if (options.parameters_path.empty()) throw std::invalid_argument("fe-check needs --parameters");
  if (!(options.max_strain > 0.0) || options.max_strain > 0.6)
    throw std::invalid_argument("--max-strain must be in (0, 0.6]");
  if (options.steps == 0) throw std::invalid_argument("--steps must be >= 1");
  if (!(options.integration_tolerance >= 0.0) || options.integration_tolerance > 1e-2)
    throw std::invalid_argument("--model-tol must be in [0, 1e-2] (0: no substep error control)");
  for (double p : options.pressures)
    if (!(p > 0.0)) throw std::invalid_argument("--pressures must be positive [Pa]");
  if (!model::acst::is_admissible_void_ratio(options.void_ratio))
    throw std::invalid_argument("--void-ratio " + format_value(options.void_ratio) +
                                " is not a void ratio the model can carry: it must be in (0, 2.97)");

  // The parameter file, read once: the model, its values and the rest (a_cs).
  const model::ParameterValues values = model::read_parameter_file(options.parameters_path);
  const std::string& model = values.model;
  if (model == "contact_network") {
#ifdef SFFCAL_FE_CHECK_NETWORK
    return run_network_fe_check(options, values, log);
#else
    throw std::invalid_argument("the contact-network fe-check needs the fits' library: this "
                                "sffcal was configured with SFFCAL_BUILD_CALIBRATION=OFF");
#endif
  }
  if (model != "acst")
    throw std::invalid_argument("parameter file '" + options.parameters_path + "': model '" +
                                model + "' (fe-check reads \"acst\" and \"contact_network\")");

  // Parameters: calibration's reader only; a_cs is not a model parameter (acst-model.md).
  const model::acst::Parameters<double> parameters = model::acst::parameters_of(values);
  double a_cs = kDefaultAcs;
  std::string a_cs_source = "default (dense_100kPa_2000 critical state, docs/fe.md)";
  if (options.a_cs > 0.0) {
    a_cs = options.a_cs;
    a_cs_source = "--a-cs";
  } else if (const std::optional<double> from_file =
                 fabric_normalisation(values, options.parameters_path)) {
    a_cs = *from_file;
    a_cs_source = "parameter file";
  }

  std::vector<DemRun> dem_runs;
  for (const std::string& path : options.dem_runs)
    dem_runs.push_back(dem_run(runfile::read_dem_test(path), path, a_cs));

  std::vector<Case> cases;
  for (double p : options.pressures) {
    Case c;
    c.name = pressure_name(p);
    c.specimen.confining_pressure = p;
    c.specimen.void_ratio = options.void_ratio;
    c.fabric_source = "isotropic";
    cases.push_back(c);
  }
  for (const DemRun& run : dem_runs) {
    Case c;
    c.name = run.name;
    c.dem = &run;
    c.specimen.confining_pressure = run.confining_pressure;
    c.specimen.void_ratio = run.void_ratio;
    if (run.initial_a_c) {
      c.specimen.fabric = fabric_from_dem_anisotropy(*run.initial_a_c, a_cs);
      c.fabric_source = "/analysis/sff a_c = " + format_value(*run.initial_a_c);
    } else {
      c.fabric_source = "isotropic (no /analysis/sff: run 'sffcal sff' on the file first)";
    }
    cases.push_back(c);
  }

  const fs::path out_folder(options.output_folder);
  fs::create_directories(out_folder);
  AcstLoading loading;
  loading.axial_strain_end = options.max_strain;
  loading.n_steps = options.steps;
  loading.integration.tolerance = options.integration_tolerance;

  log(format("sffcal fe-check: parameters %s, a_cs = %.4g (%s)", options.parameters_path.c_str(),
             a_cs, a_cs_source.c_str()));
  log(format("drained triaxial compression to axial strain %.3g in %u steps; model integration "
             "tolerance %.1e; output in %s/",
             options.max_strain, options.steps, loading.integration.tolerance,
             out_folder.string().c_str()));

  FeCheckResult result;
  std::vector<FeCheckRow>& checks = result.checks;
  bool& runs_completed = result.runs_completed;
  for (const Case& c : cases) {
    const fs::path folder = out_folder / c.name;
    fs::create_directories(folder);
    const double f0 = c.specimen.fabric(2, 2) - 0.5 * (c.specimen.fabric(0, 0) +
                                                        c.specimen.fabric(1, 1));
    log(format("\ncase %s: sigma_3 = %.4g kPa, e_0 = %.4g, F_0:n_c = %.4g (%s)", c.name.c_str(),
               c.specimen.confining_pressure / 1e3, c.specimen.void_ratio,
               model::acst::kSqrtTwoThirds * f0, c.fabric_source.c_str()));

    const Curve driver = run_acst_driver_triaxial(parameters, c.specimen, loading);
    write_curve_csv((folder / "driver.csv").string(), driver);
    log("  " + run_line(driver, options.steps));

    AcstMeshOptions element_options;
    element_options.verbose = options.verbose;
    const Curve element =
        run_acst_fe_triaxial(parameters, c.specimen, loading, element_options);
    write_curve_csv((folder / "element.csv").string(), element);
    log("  " + run_line(element, options.steps));
    runs_completed = runs_completed && driver.completed && element.completed;
    add_path_checks(checks, c.name, "element vs driver", element, driver);

    if (options.mesh) {
      const Curve mesh = run_acst_fe_triaxial(parameters, c.specimen, loading,
                                              check_mesh_options(folder, options.verbose));
      write_curve_csv((folder / "mesh.csv").string(), mesh);
      log("  " + run_line(mesh, options.steps));
      runs_completed = runs_completed && mesh.completed;
      add_path_checks(checks, c.name, "mesh vs element", mesh, element);
    }

    if (c.dem) add_dem_checks(checks, c.name, folder, element, *c.dem, options);
  }

  write_summary(out_folder, checks);
  return result;
}

int FeCheckResult::exit_code() const {
  bool verification_ok = true, dem_ok = true;
  for (const FeCheckRow& row : checks)
    if (!row.pass) (row.verification ? verification_ok : dem_ok) = false;
  if (!runs_completed || !verification_ok) return 1;
  return dem_ok ? 0 : 2;
}

}  // namespace fe_model
