// A DEM element test as the fits and fe-check read it (docs/calibration.md, "Data"): its series,
// its SFF table and its loading path, from a run file or a reduced CSV pair. Needs no Ceres, so that
// fe-check reads DEM runs without linking a fit.
//
// Conventions: compression positive (strains, stresses); stresses in Pa; strains as fractions.
#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <vector>

namespace runfile {
struct DemTest;
}

namespace calibration {

/// The loading path of a DEM test as the fit's model path follows it (docs/dem.md, "Loading
/// paths"; the spellings are the run file's /loading path): z is driven, x and y are held alike.
enum class TestPath {
  kDrainedCompression,    ///< sigma_xx = sigma_yy = sigma_3, eps_zz rising
  kDrainedExtension,      ///< sigma_xx = sigma_yy = sigma_3, eps_zz falling
  kConstantPCompression,  ///< (sigma_xx + sigma_yy + sigma_zz)/3 = p0, eps_zz rising
  kUndrainedCompression,  ///< constant volume: eps_xx = eps_yy = -eps_zz/2, eps_zz rising
  kUndrainedExtension,    ///< constant volume, eps_zz falling
};
/// The path of a run file's /loading path name; throws std::runtime_error for a path the fit
/// cannot follow (true_triaxial: x and y differ) or an unknown name, naming it.
TestPath parse_test_path(const std::string& name);
const char* to_string(TestPath path);
/// +1 where eps_zz rises (compression), -1 where it falls (extension).
double axial_direction(TestPath path);
bool is_undrained(TestPath path);
/// sigma_xx = sigma_yy = sigma_3 held (drained compression or extension).
bool holds_lateral_stress(TestPath path);

/// Below this fraction of p0 the DEM specimen has liquefied: its q/p and fabric are the noise of
/// a few contacts (docs/dem.md), so rows and snapshots there carry no q/p or a_c residual.
inline constexpr double kLiquefiedMeanStress = 0.05;

/// One axisymmetric DEM element test (the paths of TestPath) as data for the fit.
struct TestData {
  std::string name;             ///< short name (the run file's stem)
  std::string source;           ///< the file(s) it was read from
  std::uint64_t seed = 0;       ///< the DEM run's seed (0 if unknown)
  std::string program_version;  ///< the program that wrote the run ("" if unknown)
  double p0 = 0.0;              ///< initial isotropic mean stress = sigma_3 [Pa]
  double e0 = 0.0;              ///< initial void ratio
  double a_c0 = 0.0;            ///< initial triaxial fabric anisotropy a_c (first snapshot)
  double friction = 0.0;        ///< interparticle friction mu (SFF relation; 0 if unknown)
  TestPath path = TestPath::kDrainedCompression;
  /// Series rows (walls): axial strain, q/p, volumetric strain, void ratio, mean stress [Pa].
  std::vector<double> axial_strain, eta, volumetric_strain, void_ratio, p;
  /// Snapshots (SFF table): axial strain, contact-normal anisotropy a_c, normal-force
  /// anisotropy a_n, mobilisation m, stress ratio eta from the contacts.
  std::vector<double> snapshot_axial_strain, a_c, a_n, mobilisation, snapshot_eta;
  /// What a_n holds: "measured" (sff's) or "closing" (the contact-network model's,
  /// network::with_closing_normal_anisotropy).
  std::string normal_anisotropy = "measured";
  /// Snapshots: coordination Z, mean normalised normal force Lambda, tangential-force anisotropy
  /// a_t (the contact-network model's state, network_fit.h); empty where the data lack them.
  std::vector<double> coordination, lambda, a_t;
};

/// Whether the DEM specimen of a test had liquefied at series row `row` (kLiquefiedMeanStress).
inline bool liquefied_at_row(const TestData& test, std::size_t row) {
  return test.p[row] < kLiquefiedMeanStress * test.p0;
}

/// Reads a run file: /series (axial_strain, eta, volumetric_strain, void_ratio, p) and the SFF
/// table /analysis/sff (axial_strain, a_c, a_n, m, eta), the friction from the stored config,
/// the loading path from /loading. Throws std::runtime_error naming the file and what is missing
/// (e.g. no /analysis/sff) or a path the fit cannot follow.
TestData read_run_file(const std::string& path);
/// The same from a run already read (runfile::read_dem_test) from `path` (named in errors).
TestData test_data(const runfile::DemTest& dem, const std::string& path);

/// Reads the reduced CSV pair (series columns and SFF columns, with headers, as
/// bench/reference/*_series.csv and *_sff.csv); friction and path as given.
TestData read_csv_pair(const std::string& series_csv, const std::string& sff_csv,
                       const std::string& name, double friction,
                       TestPath path = TestPath::kDrainedCompression);

/// A test from its columns, named as a run file's (series: axial_strain, eta, volumetric_strain,
/// void_ratio, p; sff: axial_strain, a_c, a_n, m, eta, and coordination, lambda, a_t together where
/// given), e.g. curves given from Python; `source` says where they came from in messages. Throws
/// std::runtime_error naming a missing column or what validate_test_data refuses.
TestData test_from_tables(const std::string& name, const std::string& source,
                          const std::map<std::string, std::vector<double>>& series,
                          const std::map<std::string, std::vector<double>>& sff, double friction,
                          TestPath path);

/// Throws std::runtime_error naming the name two of the tests share (a fit's output files would
/// overwrite each other): for a front end to call before a long fit.
void check_unique_names(const std::vector<TestData>& fitted, const std::vector<TestData>& held_back);

/// Throws std::runtime_error naming the test and the problem: empty or unequal curves, fewer
/// than 3 rows or no snapshot, non-finite values, an axial strain that does not move in the
/// path's direction (rising in compression, falling in extension), p0 or e0 out of range.
void validate_test_data(const TestData& test);

}  // namespace calibration
