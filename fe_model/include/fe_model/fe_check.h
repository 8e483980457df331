// fe-check (docs/fe.md): element-level drained triaxial checks of any registered model. For each
// case (a confining pressure, or a DEM run's sigma_3, e_0 and initial state) it runs the model's
// material-point driver, one Q1 hexahedron and a 2x2x4 mesh to the same axial strain, writes one
// CSV per run (and VTU files of the mesh) and decides which checks pass: the FE runs against the
// driver and each other (verification) and against the DEM (calibration quality). ACST and the
// contact-network model start from DEM runs and are driven in their own ways; any other model
// runs through the model interface alone (model/point_driver.h).
//
// deal.II-free like acst_check.h (link fe_model_acst, which links no fit); `sffcal fe-check`
// parses its flags into FeCheckOptions and prints what run_fe_check reports.
#ifndef FE_MODEL_FE_CHECK_H_
#define FE_MODEL_FE_CHECK_H_

#include <functional>
#include <string>
#include <vector>

namespace fe_model {

struct FeCheckOptions {
  std::string parameters_path;         ///< a parameter file of any registered model
  std::vector<std::string> dem_runs;   ///< DEM run files (HDF5) to compare with
  std::vector<double> pressures = {100e3, 200e3, 300e3};  ///< sigma_3 of the plain cases [Pa]
  double void_ratio = 0.8;   ///< e_0 of the plain cases
  double max_strain = 0.3;   ///< final axial strain
  unsigned int steps = 100;  ///< equal axial strain increments
  std::string output_folder = "fe_check";
  /// Local error tolerance of the model's implicit substepping (model::acst::IntegrationOptions),
  /// the same for the driver and the FE runs; 0 (the FE default): one second-order step per
  /// increment, a smooth update, so both Newton iterations converge to round-off (docs/fe.md).
  double integration_tolerance = 0.0;
  double a_cs = 0.0;  ///< DEM fabric normalisation; 0: from the parameter file, else the default
  double dem_eta_tolerance = 0.10;         ///< pass: RMS error of q/p against the DEM
  double dem_volumetric_tolerance = 0.01;  ///< pass: RMS error of eps_v against the DEM
  /// Wall-clock budget of each FE run (the element, the mesh) [s]; 0: none. A model whose update
  /// needs thousands of substeps makes the mesh run for hours; past the budget the run stops
  /// with a message naming it.
  double time_limit = 600.0;
  bool mesh = true;      ///< run the 2x2x4 mesh (the slow part)
  bool verbose = false;  ///< Newton logs
};

/// One row of the table (and of summary.csv).
struct FeCheckRow {
  std::string case_name, check, quantity;
  double value = 0.0, tolerance = 0.0;
  bool pass = false;
  bool verification = true;  ///< false: FE vs DEM (a calibration-quality measure)
  std::string note;
};

struct FeCheckResult {
  std::vector<FeCheckRow> checks;
  bool runs_completed = true;
  /// 0 if every check passed, 2 if only FE-vs-DEM checks failed, 1 if a verification check
  /// failed or a run did not complete.
  int exit_code() const;
};

/// Receives each line of progress as it happens (the settings, each case and each run).
using FeCheckLog = std::function<void(const std::string&)>;

/// Checks the options (std::invalid_argument naming the flag), runs every case, writes
/// OUTPUT/<case>/{driver,element,mesh,dem,dem_fabric}.csv, OUTPUT/<case>/vtu/ and
/// OUTPUT/summary.csv. Throws for unreadable input files.
FeCheckResult run_fe_check(const FeCheckOptions& options, const FeCheckLog& log);

}  // namespace fe_model

#endif  // FE_MODEL_FE_CHECK_H_
