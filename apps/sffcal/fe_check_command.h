// The fe-check subcommand: element-level drained triaxial checks of the ACST model (issue 6).
// For each case (a confining pressure, or a DEM run's sigma_3, e_0 and initial fabric) it runs the
// material-point driver, one Q1 hexahedron and a 2x2x4 mesh to the same axial strain, writes one
// CSV per run (and VTU files of the mesh), and prints a pass/fail table. docs/fe.md.
//
// No CLI11 and no deal.II here: main.cc parses the options, fe_model/acst_check.h runs the models.
#ifndef SFFCAL_FE_CHECK_COMMAND_H_
#define SFFCAL_FE_CHECK_COMMAND_H_

#include <string>
#include <vector>

namespace sffcal {

struct FeCheckOptions {
  std::string parameters_path;         ///< ACST parameter file (calibration's JSON)
  std::vector<std::string> dem_runs;   ///< DEM run files (HDF5) to compare with
  std::vector<double> pressures = {100e3, 200e3, 300e3};  ///< sigma_3 of the plain cases [Pa]
  double void_ratio = 0.8;   ///< e_0 of the plain cases
  double max_strain = 0.3;   ///< final axial strain
  unsigned int steps = 100;  ///< equal axial strain increments
  std::string output_folder = "fe_check";
  /// Local error tolerance of the model's implicit substepping (calibration::IntegrationOptions),
  /// the same for the driver and the FE runs; 0 (the FE default): one second-order step per
  /// increment, a smooth update, so both Newton iterations converge to round-off (docs/fe.md).
  double integration_tolerance = 0.0;
  double a_cs = 0.0;  ///< DEM fabric normalisation; 0: from the parameter file, else the default
  double dem_eta_tolerance = 0.10;         ///< pass: RMS error of q/p against the DEM
  double dem_volumetric_tolerance = 0.01;  ///< pass: RMS error of eps_v against the DEM
  bool mesh = true;      ///< run the 2x2x4 mesh (the slow part)
  bool verbose = false;  ///< Newton logs
};

/// Runs the checks; returns 0 if every check passed, 2 if only FE-vs-DEM checks failed, 1 if a
/// verification check failed or a run did not complete. Throws for unreadable input files.
int fe_check_command(const FeCheckOptions& options);

}  // namespace sffcal

#endif  // SFFCAL_FE_CHECK_COMMAND_H_
