// `sffcal point` (docs/fe.md, "One material point"): one material point of any registered model
// along a triaxial path, drained or undrained, in compression or extension, from a DEM run's start
// or a plain specimen's (model_start.h), through the driver of any model (model/point_driver.h),
// written as a CSV. It is the reference of the CalculiX element decks
// (examples/calculix/single_element.py). deal.II-free (fe_model_acst), like umat_cards.h.
#ifndef FE_MODEL_POINT_PATH_H_
#define FE_MODEL_POINT_PATH_H_

#include <string>

#include "fe_model/model_start.h"
#include "model/point_driver.h"

namespace fe_model {

struct PointPathOptions {
  std::string parameters_path;  ///< a parameter file of any registered model
  StartOptions start;           ///< a DEM run's start, or a plain specimen's
  model::Drainage drainage = model::Drainage::kDrained;
  double axial_strain_end = 0.05;  ///< positive: compression, negative: extension
  int steps = 50;                  ///< equal axial strain increments
};

struct PointPathResult {
  std::string model;  ///< the model's registered name
  ModelStart start;
  model::DriverPath path;
  int void_ratio_offset = -1;  ///< of the void ratio in each point's state; -1: the model has none
};

/// Runs the path. Throws std::invalid_argument naming a bad option or a start the model cannot
/// carry, std::runtime_error for an unreadable file; an update that fails on the way ends the path
/// with completed = false and a message.
PointPathResult run_point_path(const PointPathOptions& options);

/// Writes one row per point (the start first), compression positive, SI units: a comment line
/// naming the model, the start and the path, then step, axial_strain, volumetric_strain,
/// void_ratio, p, q, eta, sigma_xx, sigma_yy, sigma_zz, newton_iterations, status. Written whole
/// or not at all (sffcal/output_file.h).
void write_point_path_csv(const std::string& path, const PointPathOptions& options,
                          const PointPathResult& result);

}  // namespace fe_model

#endif  // FE_MODEL_POINT_PATH_H_
