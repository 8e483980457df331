// The material-point driver behind C linkage for the UMAT C test (reference.h).
#include "reference.h"

#include <cstdio>
#include <exception>

#include "calibration/material_point.h"

extern "C" int reference_parameters(const char* parameter_file, double* parameters,
                                    char* message, int message_size) {
  try {
    const calibration::Parameters<double> p = calibration::read_parameters_json(parameter_file);
    int i = 0;
    for (const auto& field : calibration::kParameterFields<double>) parameters[i++] = p.*field.member;
    return 0;
  } catch (const std::exception& e) {
    std::snprintf(message, static_cast<size_t>(message_size), "%s", e.what());
    return -1;
  }
}

extern "C" int reference_drained_triaxial(const double* parameters, double p0, double e0,
                                          double f, double axial_strain_end, int increments,
                                          double* q, double* volumetric_strain) {
  const double* v = parameters;
  calibration::Parameters<double> par;
  int k = 0;
  for (const auto& field : calibration::kParameterFields<double>) par.*field.member = v[k++];
  calibration::DriverOptions options;
  options.integration = calibration::IntegrationOptions();  // what the UMAT entry integrates with
  options.stress_tolerance = 1e-12;
  const calibration::PathResult<double> r = calibration::drained_triaxial(
      par, calibration::isotropic_state(p0, e0, calibration::triaxial_deviator(f)),
      axial_strain_end, increments, options);
  if (r.rows.size() != static_cast<size_t>(increments) + 1) return -1;
  for (int i = 0; i < increments; ++i) {
    q[i] = r.rows[static_cast<size_t>(i) + 1].q;
    volumetric_strain[i] = r.rows[static_cast<size_t>(i) + 1].volumetric_strain;
  }
  return 0;
}
