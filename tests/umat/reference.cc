// The material-point driver behind C linkage for the UMAT C test (reference.h).
#include "reference.h"

#include <cstdio>
#include <exception>

#include "calibration/material_point.h"

extern "C" int reference_parameters(const char* parameter_file, double* parameters,
                                    char* message, int message_size) {
  try {
    const calibration::Parameters<double> p = calibration::read_parameters_json(parameter_file);
    const double values[15] = {p.G0, p.nu,  p.M_c, p.c,  p.e_gamma, p.lambda_c, p.xi, p.m,
                               p.h0, p.c_h, p.n_b, p.A0, p.n_d,     p.e_A,      p.k_F};
    for (int i = 0; i < 15; ++i) parameters[i] = values[i];
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
  const calibration::Parameters<double> par{v[0], v[1], v[2],  v[3],  v[4],  v[5],  v[6], v[7],
                                            v[8], v[9], v[10], v[11], v[12], v[13], v[14],
                                            0.0, 0.5 /* n_b_loose, n_G: NPROPS = 22 */};
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
