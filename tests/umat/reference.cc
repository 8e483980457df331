// The material-point driver behind C linkage for the UMAT C test (reference.h).
#include "reference.h"

#include <cstdio>
#include <exception>

#include "model/material_point.h"

extern "C" int reference_parameters(const char* parameter_file, double* parameters,
                                    char* message, int message_size) {
  try {
    const model::acst::Parameters<double> p = model::acst::read_parameters_json(parameter_file);
    int i = 0;
    for (const auto& field : model::acst::kParameterFields<double>) parameters[i++] = p.*field.member;
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
  model::acst::Parameters<double> par;
  int k = 0;
  for (const auto& field : model::acst::kParameterFields<double>) par.*field.member = v[k++];
  model::acst::DriverOptions options;
  options.integration = model::acst::IntegrationOptions();  // what the UMAT entry integrates with
  options.stress_tolerance = 1e-12;
  const model::acst::PathResult<double> r = model::acst::drained_triaxial(
      par, model::acst::isotropic_state(p0, e0, model::acst::triaxial_deviator(f)),
      axial_strain_end, increments, options);
  if (r.rows.size() != static_cast<size_t>(increments) + 1) return -1;
  for (int i = 0; i < increments; ++i) {
    q[i] = r.rows[static_cast<size_t>(i) + 1].q;
    volumetric_strain[i] = r.rows[static_cast<size_t>(i) + 1].volumetric_strain;
  }
  return 0;
}
