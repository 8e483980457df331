// A specimen's start as a model's initial inputs (model/descriptor.h, ModelDescription::
// initial_inputs): from a DEM run, as fe-check, the UMAT cards and `sffcal point` take it, or a
// plain specimen.
// deal.II-free (fe_model_acst), like fe_check.h.
#ifndef FE_MODEL_MODEL_START_H_
#define FE_MODEL_MODEL_START_H_

#include <string>
#include <utility>
#include <vector>

#include "model/parameter_file.h"

namespace runfile {
struct DemTest;
}

namespace fe_model {

struct ModelStart {
  double confining_pressure = 0.0;  ///< sigma_3 [Pa]: the isotropic initial stress
  double void_ratio = 0.0;          ///< e_0
  std::vector<double> inputs;       ///< laid out as the model's initial_inputs()
  std::string source;               ///< where the inputs came from, in words
};

/// ACST's DEM fabric normalisation a_cs and where it came from: `given` where positive, else the
/// parameter file's (fabric_normalisation), else kDefaultAcs (acst_check.h).
std::pair<double, std::string> acst_fabric_normalisation(const model::ParameterValues& values,
                                                         const std::string& parameters_path,
                                                         double given);

/// The start of a DEM run (drained, from /series' first row) for the model of `values`:
///  - ACST: e_0 and F_0 = A_DEM / a_cs from the first SFF row's a_c (fabric_from_dem_anisotropy;
///    isotropic, said in `source`, where the file has no /analysis/sff);
///  - the contact-network model: its first snapshot's network, e_0, Z, A, F (the closing a_n) and
///    F^t (calibration/network_test_data.h; throws std::runtime_error naming a run without Z,
///    Lambda or a_t);
///  - any other model: e_0 where it takes a void ratio, every other input zero (isotropic).
ModelStart dem_start(const model::ParameterValues& values, double a_cs,
                     const runfile::DemTest& run, const std::string& path);

/// A plain specimen: sigma_3, e_0 where the model takes a void ratio, every other input zero (an
/// isotropic specimen). Throws std::invalid_argument for the contact-network model, whose network
/// (Z, Lambda, anisotropies) comes from a DEM run.
ModelStart plain_start(const model::ParameterValues& values, double confining_pressure,
                       double void_ratio);

/// Where the start of umat-cards and `sffcal point` comes from (their --dem, --pressure,
/// --void-ratio, --a-cs).
struct StartOptions {
  std::string dem_run;                ///< the start of this DEM run; empty: a plain specimen
  double confining_pressure = 100e3;  ///< plain specimen: sigma_3 [Pa]
  double void_ratio = 0.8;            ///< plain specimen: e_0
  double a_cs = 0.0;  ///< ACST's DEM fabric normalisation; 0: the parameter file's, else the default
};

/// The start of `options` for the model of `values` (read from `parameters_path`), checked as the
/// model will take it: its initial_state refuses an input it cannot carry (a void ratio of 5, a
/// coordination of 0), naming it. Throws std::invalid_argument for a start that is not physical,
/// std::runtime_error for an unreadable run.
ModelStart specimen_start(const model::ParameterValues& values, const std::string& parameters_path,
                          const StartOptions& options);

}  // namespace fe_model

#endif  // FE_MODEL_MODEL_START_H_
