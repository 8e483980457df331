// One DEM element test as the continuum stages read it (calibration, fe-check): its metadata,
// its scalar series and, once `sffcal sff` has analysed it, the per-snapshot SFF values.
#pragma once

#include <string>
#include <vector>

#include "runfile/run_file.h"

namespace runfile {

/// The /series columns the continuum stages use; one value per output row, compression positive.
struct DemTestSeries {
  std::vector<double> axial_strain, volumetric_strain;
  std::vector<double> p, q, eta;  ///< [Pa], [Pa], q/p
  std::vector<double> void_ratio;
  std::vector<double> sigma_3;    ///< lateral (confining) stress [Pa]
};

/// The /analysis/sff columns the continuum stages use; one value per analysed snapshot.
struct DemTestSff {
  std::vector<double> axial_strain;
  std::vector<double> p, q, eta;  ///< contact stress [Pa], [Pa], q/p
  std::vector<double> void_ratio;
  std::vector<double> a_c, a_n, m;  ///< fabric, normal-force and mobilisation anisotropies
  /// The rest of the SFF state (sff-theory.md §1, §3): coordination Z, mean normalised normal
  /// force Lambda, tangential-force anisotropy a_t. Empty when the table lacks them (reduced
  /// files of older versions); the contact-network model needs them.
  std::vector<double> coordination, lambda, a_t;
};

struct DemTest {
  std::string path;
  std::string name;  ///< the file name without its extensions
  RunMetadata metadata;
  DemTestSeries series;
  bool analysed = false;  ///< true when the file has an SFF table (then `sff` is filled)
  DemTestSff sff;

  /// The loading path's name; files without /loading are drained compression.
  std::string loading_path() const {
    return metadata.loading.path.empty() ? "drained_compression" : metadata.loading.path;
  }
};

/// Reads a triaxial run file. Throws std::runtime_error naming the file and the dataset when a
/// series or an SFF column is missing or the columns differ in length.
DemTest read_dem_test(const std::string& path);

}  // namespace runfile
