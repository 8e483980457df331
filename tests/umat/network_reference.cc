// The contact-network driver behind C linkage for the network UMAT C test (network_reference.h).
#include "network_reference.h"

#include <cstdio>
#include <exception>
#include <stdexcept>

#include "calibration/network_fit.h"
#include "model/network_update.h"

namespace net = calibration::network;

extern "C" int network_reference_parameters(const char* parameter_file,
                                            double* youngs_and_parameters, char* message,
                                            int message_size) {
  try {
    const auto values =
        model::network::to_array(model::network::read_parameters_json(parameter_file, youngs_and_parameters));
    for (int i = 0; i < model::network::kNumParameters; ++i) youngs_and_parameters[1 + i] = values[i];
    return 0;
  } catch (const std::exception& e) {
    std::snprintf(message, static_cast<size_t>(message_size), "%s", e.what());
    return -1;
  }
}

extern "C" int network_reference_drained_triaxial(const double* youngs_and_parameters, double p0,
                                                  double e0, double z0, double a_c, double a_n,
                                                  double a_t, double axial_strain_end,
                                                  int increments, double* q,
                                                  double* volumetric_strain, char* message,
                                                  int message_size) {
  try {
    if (youngs_and_parameters[0] != net::kDemYoungsModulus)
      throw std::runtime_error("the driver takes E = 150 MPa, the DEM's");
    const model::network::Parameters<double> par = model::network::from_array(youngs_and_parameters + 1);
    model::network::State<double> network{e0, z0, 0.0, net::axisymmetric(a_c), net::axisymmetric(a_n),
                               net::axisymmetric(a_t)};
    calibration::TestData test;
    test.name = "umat reference";
    test.p0 = p0;
    test.e0 = e0;
    for (int k = 0; k <= increments; ++k) {
      test.axial_strain.push_back(axial_strain_end * k / increments);
      test.volumetric_strain.push_back(0.0);  // the DEM's, unused by the prediction
    }
    test.snapshot_axial_strain = {0.0};
    test.coordination = {z0};
    test.lambda = {model::network::lambda_for_mean_stress(network, p0, net::kDemYoungsModulus)};
    test.a_c = {a_c};
    test.a_n = {a_n};
    test.a_t = {a_t};
    net::FitOptions driver;  // the update's substeps, as the UMAT's
    driver.substep_size = model::network::kUpdateSubstepSize;
    const net::Curve c = net::predict(par, test, driver, p0);
    if (!c.complete) throw std::runtime_error(c.message);
    for (int k = 0; k < increments; ++k) {
      q[k] = c.q[static_cast<size_t>(k) + 1];
      volumetric_strain[k] = c.volumetric_strain[static_cast<size_t>(k) + 1];
    }
    return 0;
  } catch (const std::exception& e) {
    std::snprintf(message, static_cast<size_t>(message_size), "%s", e.what());
    return -1;
  }
}
