#include "fe_model/fe_check.h"

#include <chrono>
#include <cmath>
#include <cstdarg>
#include <cstdio>
#include <filesystem>
#include <iomanip>
#include <limits>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "fe_model/acst_check.h"
#include "fe_model/model_material.h"
#include "fe_model/model_start.h"
#include "fe_model/network_material.h"
#include "model/acst_model.h"
#include "model/network_path.h"
#include "model/point_driver.h"
#include "runfile/dem_test.h"
#include "sffcal/format_number.h"
#include "sffcal/output_file.h"

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
  // The run as data from outside: rows enough to compare with, finite, the strain rising.
  if (s.axial_strain.size() < 2)
    throw std::runtime_error(path + ": /series has " + std::to_string(s.axial_strain.size()) +
                             " rows: fe-check compares at least two");
  for (std::size_t i = 0; i < s.axial_strain.size(); ++i) {
    for (const auto* column : {&s.axial_strain, &s.volumetric_strain, &s.p, &s.q, &s.void_ratio,
                               &s.sigma_3})
      if (i >= column->size() || !std::isfinite((*column)[i]))
        throw std::runtime_error(path + ": /series row " + std::to_string(i) +
                                 " has a value that is not finite (or a column is short)");
    if (i > 0 && !(s.axial_strain[i] > s.axial_strain[i - 1]))
      throw std::runtime_error(path + ": /series axial_strain does not rise at row " +
                               std::to_string(i));
    if (!(s.p[i] > 0.0))
      throw std::runtime_error(path + ": /series p is not positive at row " + std::to_string(i));
  }
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
    for (std::size_t i = 0; i < f.axial_strain.size(); ++i) {
      const double fabric = model::acst::kSqrtTwoThirds * f.a_c[i] / a_cs;  // A_DEM : n_c / a_cs
      run.fabric.points.push_back(curve_point(f.axial_strain[i], kNone, f.p[i], f.q[i], f.void_ratio[i], fabric));
    }
  }
  return run;
}

// One case of the check: a specimen, its runs and the DEM run it came from (if any). The model's
// own setup (acst_check, network_check, any_model_check) says how each run is made.
struct Case {
  std::string name;
  double confining_pressure = 0.0;  // sigma_3 [Pa]
  std::string description;          // logged after the case's name
  std::function<Curve()> driver;    // the material point on the element's path
  std::function<Curve(const TriaxialMeshOptions&)> fe;  // the element or the mesh
  const DemRun* dem = nullptr;
};

// What fe-check runs for the model of a parameter file.
struct Check {
  std::vector<std::string> header;  // logged before the cases
  std::vector<DemRun> dem_runs;     // the cases point into it: filled before the cases
  std::vector<Case> cases;
  // Element vs driver: both solve the same discrete equations to round-off, unless the model's
  // driver integrates differently from its update (network_check).
  double driver_tolerance = 1e-8;
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
TriaxialMeshOptions check_mesh_options(const fs::path& folder, const FeCheckOptions& options) {
  TriaxialMeshOptions mesh;
  mesh.cells_x = mesh.cells_y = 2;
  mesh.cells_z = 4;
  mesh.verbose = options.verbose;
  mesh.wall_time_limit = options.time_limit;
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
  sffcal::OutputFile file((out_folder / "summary.csv").string());
  std::ostream& summary = file.stream();
  summary << "case,check,quantity,value,tolerance,result,note\n" << std::setprecision(6);
  for (const FeCheckRow& row : checks)
    summary << row.case_name << ',' << row.check << ',' << row.quantity << ',' << row.value << ','
            << row.tolerance << ',' << (row.pass ? "pass" : "fail") << ",\"" << row.note << "\"\n";
  file.commit();
}

// The loading of every run: drained compression to --max-strain in --steps equal increments.
TriaxialLoading triaxial_loading(const FeCheckOptions& options) {
  TriaxialLoading loading;
  loading.axial_strain_end = options.max_strain;
  loading.n_steps = options.steps;
  return loading;
}

// Each --dem run read once: its curves into check.dem_runs (the DEM fabric normalised by ACST's
// a_cs, or taken as a_c itself, A:n_c / sqrt(2/3), where a_cs is 0) and its start for the model.
std::vector<ModelStart> read_dem_runs(const FeCheckOptions& options,
                                      const model::ParameterValues& values, double a_cs,
                                      Check& check) {
  std::vector<ModelStart> starts;
  for (const std::string& path : options.dem_runs) {
    const runfile::DemTest run = runfile::read_dem_test(path);
    check.dem_runs.push_back(dem_run(run, path, a_cs > 0.0 ? a_cs : model::acst::kSqrtTwoThirds));
    starts.push_back(dem_start(values, a_cs, run, path));
  }
  return starts;
}

// The plain pressure cases, then one case per DEM run (check.dem_runs, starts), through add_case.
template <typename AddCase>
void add_plain_and_dem_cases(const FeCheckOptions& options, const model::ParameterValues& values,
                             const std::vector<ModelStart>& starts, const Check& check,
                             AddCase add_case) {
  for (double p : options.pressures)
    add_case(pressure_name(p), plain_start(values, p, options.void_ratio), nullptr);
  for (std::size_t r = 0; r < starts.size(); ++r)
    add_case(check.dem_runs[r].name, starts[r], &check.dem_runs[r]);
}

// ACST (docs/fe.md): the plain pressure cases with an isotropic fabric and the DEM runs' cases
// with the fabric of their first SFF row, F_0 = A_DEM / a_cs; ACST's own driver, whose integration
// options are the element's, so that both agree to round-off.
Check acst_check(const FeCheckOptions& options, const model::ParameterValues& values) {
  // Parameters: calibration's reader only; a_cs is not a model parameter (acst-model.md).
  const model::acst::Parameters<double> parameters = model::acst::parameters_of(values);
  const auto [a_cs, a_cs_source] =
      acst_fabric_normalisation(values, options.parameters_path, options.a_cs);
  TriaxialLoading loading = triaxial_loading(options);
  loading.integration.tolerance = options.integration_tolerance;

  Check check;
  check.header = {
      format("sffcal fe-check: parameters %s, a_cs = %.4g (%s)", options.parameters_path.c_str(),
             a_cs, a_cs_source.c_str()),
      format("drained triaxial compression to axial strain %.3g in %u steps; model integration "
             "tolerance %.1e; output in %s/",
             options.max_strain, options.steps, loading.integration.tolerance,
             options.output_folder.c_str())};
  const std::vector<ModelStart> starts = read_dem_runs(options, values, a_cs, check);

  auto add_case = [&](const std::string& name, const ModelStart& start, const DemRun* dem) {
    AcstSpecimen specimen;
    specimen.confining_pressure = start.confining_pressure;
    specimen.void_ratio = start.void_ratio;
    specimen.fabric = model::tensor_from_slot(start.inputs.data() + 1);  // after void_ratio
    const std::string& fabric_source = start.source;
    const double f0 = specimen.fabric(2, 2) - 0.5 * (specimen.fabric(0, 0) + specimen.fabric(1, 1));
    Case c;
    c.name = name;
    c.confining_pressure = specimen.confining_pressure;
    c.description = format("sigma_3 = %.4g kPa, e_0 = %.4g, F_0:n_c = %.4g (%s)",
                           specimen.confining_pressure / 1e3, specimen.void_ratio,
                           model::acst::kSqrtTwoThirds * f0, fabric_source.c_str());
    c.driver = [=] { return run_acst_driver_triaxial(parameters, specimen, loading); };
    c.fe = [=](const TriaxialMeshOptions& mesh) {
      return run_acst_fe_triaxial(parameters, specimen, loading, mesh);
    };
    c.dem = dem;
    check.cases.push_back(c);
  };
  add_plain_and_dem_cases(options, values, starts, check, add_case);
  return check;
}

// The contact-network model (docs/network-model.md) on the DEM runs' cases: its network starts
// from each run's first snapshot, so there are no plain pressure cases. The driver holds the
// lateral stress at sigma_3, as the element's confining traction does (the initial SFF stress
// differs from it by the initial anisotropies). Element and driver solve the same increments with
// RK4 substeps chosen from different strain norms (the FE update's whole increment, the driver's
// axial one), so they agree to the integration error, not to round-off: 1e-6.
Check network_check(const FeCheckOptions& options, const model::ParameterValues& values) {
  namespace net = model::network;
  if (options.dem_runs.empty())
    throw std::invalid_argument("the contact-network model starts from a DEM run's network (Z, "
                                "Lambda, anisotropies): give it with --dem RUN.h5");
  const double youngs_modulus = values.constants.at(0);
  const net::Parameters<double> parameters = net::from_array(values.parameters.data());
  Check check;
  check.driver_tolerance = 1e-6;
  check.header = {
      format("sffcal fe-check: contact-network parameters %s, E = %.4g Pa",
             options.parameters_path.c_str(), youngs_modulus),
      format("drained triaxial compression to axial strain %.3g in %u steps; output in %s/ "
             "(the plain pressure cases need an initial network: not run)",
             options.max_strain, options.steps, options.output_folder.c_str())};
  const TriaxialLoading loading = triaxial_loading(options);
  // The network's fabric invariant is a_c itself (a_cs 0: A:n_c / sqrt(2/3)).
  const std::vector<ModelStart> starts = read_dem_runs(options, values, 0.0, check);
  for (std::size_t r = 0; r < starts.size(); ++r) {
    const DemRun& dem = check.dem_runs[r];
    // The inputs: void_ratio, coordination, fabric, normal, tangential (the model's layout).
    const double* inputs = starts[r].inputs.data();
    NetworkInitialState initial;
    initial.void_ratio = inputs[0];
    initial.coordination = inputs[1];
    initial.fabric = model::tensor_from_slot(inputs + 2);
    initial.normal = model::tensor_from_slot(inputs + 8);
    initial.tangential = model::tensor_from_slot(inputs + 14);
    // The state of the run's network (Lambda set from the initial stress below); the initial
    // fabric is all inherent (Eq. N2d).
    net::State<double> start;
    start.lambda = 0.0;  // set from the element's initial stress by the driver
    start.void_ratio = initial.void_ratio;
    start.coordination = initial.coordination;
    start.fabric = start.inherent = initial.fabric;
    start.normal = initial.normal;
    start.tangential = initial.tangential;
    const auto material = std::make_shared<const NetworkMaterial>(parameters, initial,
                                                                  youngs_modulus);
    Case c;
    c.name = dem.name;
    c.confining_pressure = dem.confining_pressure;
    c.description = format("sigma_3 = %.4g kPa, e_0 = %.4g, Z_0 = %.4g, a_c0 = %.3g, a_n0 = %.3g",
                           dem.confining_pressure / 1e3, initial.void_ratio, initial.coordination,
                           net::triaxial_part(start.fabric), net::triaxial_part(start.normal));
    c.dem = &dem;
    const double sigma_3 = dem.confining_pressure;
    // The material point on the element's axial strains, from the element's initial state: the
    // run's network with the Z and Lambda that the element's initial stress gives.
    c.driver = [material, start, sigma_3, parameters, youngs_modulus, &options] {
      const auto t0 = std::chrono::steady_clock::now();
      const net::State<double> point0 = material->to_model(
          material->initial_state(-sigma_3 * dealii::unit_symmetric_tensor<3>()));
      net::State<double> path_start = start;
      path_start.coordination = point0.coordination;
      path_start.lambda = point0.lambda;
      std::vector<net::PathNode> nodes;
      for (unsigned int k = 0; k <= options.steps; ++k)
        nodes.push_back({options.max_strain * k / options.steps, 0.0, static_cast<int>(k),
                         k == 0 ? 0 : -1});
      net::PathOptions driver_options;  // the element's substeps and budget (network_update.h)
      driver_options.substep_size = net::kUpdateSubstepSize;
      driver_options.max_substeps = net::kMaxUpdateSubsteps;
      const net::Curve point = net::predict(parameters, net::diagonal_state(path_start), nodes,
                                            net::Lateral::kStressHeld, sigma_3, youngs_modulus,
                                            driver_options);
      Curve driver;
      driver.label = "driver";
      driver.completed = point.complete;
      driver.message = point.message;
      for (std::size_t k = 0; k < point.axial_strain.size(); ++k)
        driver.points.push_back(curve_point(point.axial_strain[k], point.volumetric_strain[k],
                                            point.p[k], point.q[k], point.void_ratio[k],
                                            point.a_c[k]));
      driver.wall_seconds =
          std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      return driver;
    };
    c.fe = [material, sigma_3, loading](const TriaxialMeshOptions& mesh) {
      return run_fe_triaxial(*material, sigma_3, loading, mesh);
    };
    check.cases.push_back(c);
  }
  return check;
}

// The material point of any model through its Behaviour (model/point_driver.h), as a curve.
Curve drive_point(const model::Behaviour& behaviour, const std::vector<double>& inputs,
                  double confining_pressure, const FeCheckOptions& options) {
  const auto t0 = std::chrono::steady_clock::now();
  model::TriaxialPath path;
  path.lateral_stress = confining_pressure;
  path.axial_strain_end = options.max_strain;
  path.steps = static_cast<int>(options.steps);
  const model::DriverPath point = model::drive_triaxial(behaviour, inputs, path);
  const int void_ratio = model::slot_offset(behaviour.description().state(), "void_ratio");
  Curve driver;
  driver.label = "driver";
  driver.completed = point.completed;
  driver.message = point.message;
  for (const model::DriverPoint& x : point.points) {
    const model::TriaxialStress stress = model::triaxial_stress(x.stress);
    CurvePoint row = curve_point(
        x.strain(2, 2), x.strain.trace(), stress.p, stress.q,
        void_ratio < 0 ? std::numeric_limits<double>::quiet_NaN()
                       : x.state[static_cast<std::size_t>(void_ratio)],
        0.0);  // as the element writes a fabric invariant it does not know
    row.newton_iterations = x.newton_iterations;
    row.status = model::to_string(x.status);
    driver.newton_iterations += x.newton_iterations;
    driver.points.push_back(row);
  }
  driver.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return driver;
}

// Any other registered model (model/descriptor.h), through the model interface alone: each case's
// initial inputs are the void ratio (where the model takes one: --void-ratio, or the DEM run's
// e_0) and zero for every other slot (an isotropic specimen); its driver is the driver of any model
// (model/point_driver.h).
Check any_model_check(const FeCheckOptions& options, const model::ParameterValues& values) {
  const model::ModelDescription& description = model::find_model(values.model);
  const std::shared_ptr<const model::Behaviour> behaviour =
      description.make(values.constants, values.parameters);
  const bool void_ratio = model::slot_offset(description.initial_inputs(), "void_ratio") >= 0;
  Check check;
  check.header = {
      format("sffcal fe-check: %s parameters %s", description.name().c_str(),
             options.parameters_path.c_str()),
      format("drained triaxial compression to axial strain %.3g in %u steps; output in %s/",
             options.max_strain, options.steps, options.output_folder.c_str())};
  const TriaxialLoading loading = triaxial_loading(options);
  const std::vector<ModelStart> starts = read_dem_runs(options, values, 0.0, check);
  auto add_case = [&](const std::string& name, const ModelStart& start, const DemRun* dem) {
    const double pressure = start.confining_pressure;
    const std::vector<double> inputs = start.inputs;
    const auto material = std::make_shared<const ModelMaterial>(behaviour, inputs);
    Case c;
    c.name = name;
    c.confining_pressure = pressure;
    c.description = void_ratio ? format("sigma_3 = %.4g kPa, e_0 = %.4g, %s", pressure / 1e3,
                                        start.void_ratio, start.source.c_str())
                               : format("sigma_3 = %.4g kPa", pressure / 1e3);
    c.driver = [=, &options] { return drive_point(*behaviour, inputs, pressure, options); };
    c.fe = [=](const TriaxialMeshOptions& mesh) {
      return run_fe_triaxial(*material, pressure, loading, mesh);
    };
    c.dem = dem;
    check.cases.push_back(c);
  };
  add_plain_and_dem_cases(options, values, starts, check, add_case);
  return check;
}

}  // namespace

FeCheckResult run_fe_check(const FeCheckOptions& options, const FeCheckLog& log) {
  if (options.parameters_path.empty()) throw std::invalid_argument("fe-check needs --parameters");
  if (!(options.max_strain > 0.0) || options.max_strain > model::kMaxTriaxialStrain)
    throw std::invalid_argument("--max-strain must be in (0, " +
                                sffcal::format_number(model::kMaxTriaxialStrain) + "]");
  if (options.steps == 0) throw std::invalid_argument("--steps must be >= 1");
  if (!(options.integration_tolerance >= 0.0) || options.integration_tolerance > 1e-2)
    throw std::invalid_argument("--model-tol must be in [0, 1e-2] (0: no substep error control)");
  for (double p : options.pressures)
    if (!(p > 0.0)) throw std::invalid_argument("--pressures must be positive [Pa]");
  if (!(options.time_limit >= 0.0 && std::isfinite(options.time_limit)))
    throw std::invalid_argument("--time-limit must be >= 0 [s] (0: none)");
  if (!model::acst::is_admissible_void_ratio(options.void_ratio))
    throw std::invalid_argument("--void-ratio " + format_value(options.void_ratio) +
                                " is not a void ratio the model can carry: it must be in (0, 2.97)");

  // The parameter file, read once: the model, its values and the rest (ACST's a_cs).
  const model::ParameterValues values = model::read_parameter_file(options.parameters_path);
  const Check check = values.model == "acst"              ? acst_check(options, values)
                      : values.model == "contact_network" ? network_check(options, values)
                                                          : any_model_check(options, values);

  const fs::path out_folder(options.output_folder);
  fs::create_directories(out_folder);
  for (const std::string& line : check.header) log(line);
  FeCheckResult result;
  for (const Case& c : check.cases) {
    const fs::path folder = out_folder / c.name;
    fs::create_directories(folder);
    log(format("\ncase %s: %s", c.name.c_str(), c.description.c_str()));

    const Curve driver = c.driver();
    write_curve_csv((folder / "driver.csv").string(), driver);
    log("  " + run_line(driver, options.steps));

    TriaxialMeshOptions element_options;
    element_options.verbose = options.verbose;
    element_options.wall_time_limit = options.time_limit;
    const Curve element = c.fe(element_options);
    write_curve_csv((folder / "element.csv").string(), element);
    log("  " + run_line(element, options.steps));
    result.runs_completed = result.runs_completed && driver.completed && element.completed;
    add_path_checks(result.checks, c.name, "element vs driver", element, driver,
                    check.driver_tolerance);

    if (options.mesh) {
      const Curve mesh = c.fe(check_mesh_options(folder, options));
      write_curve_csv((folder / "mesh.csv").string(), mesh);
      log("  " + run_line(mesh, options.steps));
      result.runs_completed = result.runs_completed && mesh.completed;
      add_path_checks(result.checks, c.name, "mesh vs element", mesh, element);
    }

    if (c.dem) add_dem_checks(result.checks, c.name, folder, element, *c.dem, options);
  }
  write_summary(out_folder, result.checks);
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
