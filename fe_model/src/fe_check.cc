#include "fe_model/fe_check.h"

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

#include "calibration/acst_model.h"
#include "fe_model/acst_check.h"
#include "runfile/dem_test.h"

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

DemRun read_dem_run(const std::string& path, double a_cs) {
  const runfile::DemTest test = runfile::read_dem_test(path);
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
      const double fabric = calibration::kSqrtTwoThirds * f.a_c[i] / a_cs;  // A_DEM : n_c / a_cs
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
                     const std::string& check, const Curve& curve,
                     const Curve& reference) {
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
    row.tolerance = kVerificationTolerance;
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
  if (!calibration::is_admissible_void_ratio(options.void_ratio))
    throw std::invalid_argument("--void-ratio " + format_value(options.void_ratio) +
                                " is not a void ratio the model can carry: it must be in (0, 2.97)");

  // Parameters: calibration's reader only; a_cs is not a model parameter (acst-model.md).
  const calibration::Parameters<double> parameters =
      calibration::read_parameters_json(options.parameters_path);
  double a_cs = kDefaultAcs;
  std::string a_cs_source = "default (dense_100kPa_2000 critical state, docs/fe.md)";
  if (options.a_cs > 0.0) {
    a_cs = options.a_cs;
    a_cs_source = "--a-cs";
  } else if (const std::optional<double> from_file =
                 read_fabric_normalisation(options.parameters_path)) {
    a_cs = *from_file;
    a_cs_source = "parameter file";
  }

  std::vector<DemRun> dem_runs;
  for (const std::string& path : options.dem_runs) dem_runs.push_back(read_dem_run(path, a_cs));

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
               calibration::kSqrtTwoThirds * f0, c.fabric_source.c_str()));

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
      AcstMeshOptions mesh_options;
      mesh_options.cells_x = mesh_options.cells_y = 2;
      mesh_options.cells_z = 4;
      mesh_options.verbose = options.verbose;
      fs::create_directories(folder / "vtu");
      mesh_options.vtu_prefix = (folder / "vtu" / "mesh").string();
      const Curve mesh =
          run_acst_fe_triaxial(parameters, c.specimen, loading, mesh_options);
      write_curve_csv((folder / "mesh.csv").string(), mesh);
      log("  " + run_line(mesh, options.steps));
      runs_completed = runs_completed && mesh.completed;
      add_path_checks(checks, c.name, "mesh vs element", mesh, element);
    }

    if (c.dem) {
      write_curve_csv((folder / "dem.csv").string(), c.dem->curve);
      if (!c.dem->fabric.points.empty())
        write_curve_csv((folder / "dem_fabric.csv").string(), c.dem->fabric);
      const DemError error = compare_with_dem(element, c.dem->curve);
      const std::string note = std::to_string(error.points) + " DEM points to eps_a = " +
                               format_value(element.points.empty()
                                                ? 0.0
                                                : element.points.back().axial_strain);
      FeCheckRow eta{c.name, "FE vs DEM", "q/p (RMS)", error.eta_rms, options.dem_eta_tolerance,
                   error.points > 0 && error.eta_rms <= options.dem_eta_tolerance, false, note};
      FeCheckRow ev{c.name,
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
  }

  std::ofstream summary(out_folder / "summary.csv");
  summary << "case,check,quantity,value,tolerance,result,note\n" << std::setprecision(6);
  for (const FeCheckRow& row : checks)
    summary << row.case_name << ',' << row.check << ',' << row.quantity << ',' << row.value << ','
            << row.tolerance << ',' << (row.pass ? "pass" : "fail") << ",\"" << row.note << "\"\n";
  if (!summary) throw std::runtime_error("cannot write " + (out_folder / "summary.csv").string());
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
