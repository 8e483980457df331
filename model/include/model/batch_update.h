// Many material points of one model updated in one call: the loop behind the Python API's batch
// update (python/bindings/models.cc) and its C++ benchmark (bench/model_batch.cc), one place for
// both so that the benchmark times what Python calls. Conventions as descriptor.h: compression
// positive, stress in Pa, tensor shear components; arrays are C-ordered, point by point.
#pragma once

#include <cstddef>
#include <string>
#include <utility>
#include <vector>

#include "model/descriptor.h"

namespace model {

/// The arrays of n points (m = slot_components(description.state())).
struct PointBatch {
  std::size_t points = 0;
  const double* stress = nullptr;     ///< n x 3 x 3, at the start [Pa]
  const double* state = nullptr;      ///< n x m, at the start
  const double* increment = nullptr;  ///< n x 3 x 3 strain increments
  double* stress_end = nullptr;       ///< n x 3 x 3 [Pa]
  double* state_end = nullptr;        ///< n x m
  double* tangent = nullptr;          ///< n x 9 x 9 (PointUpdate::tangent, row-major); may be null
  int* status = nullptr;              ///< n UpdateStatus values, as int
  double* step_ratio = nullptr;       ///< n (PointUpdate::step_ratio); may be null
};

/// Updates every point of `batch` in order, one Behaviour::update each; returns the messages of
/// the points whose status is not kOk, as (index, message) pairs. The input and output arrays may
/// not overlap.
std::vector<std::pair<std::size_t, std::string>> update_points(const Behaviour& behaviour,
                                                               const PointBatch& batch);

}  // namespace model
