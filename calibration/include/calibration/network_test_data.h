// A DEM test as the contact-network model reads it (docs/network-model.md, "State and stress"):
// the closing normal-force anisotropy and the initial state of its first snapshot. Needs no Ceres,
// so that fe-check starts the model from a DEM run without linking a fit.
#pragma once

#include "calibration/test_data.h"
#include "model/network_model.h"

namespace calibration::network {

/// The grain modulus E of the DEM (architecture.md), the normalisation of Lambda [Pa].
inline constexpr double kDemYoungsModulus = 150e6;

/// The test as the contact-network model reads it: each snapshot's a_n replaced by the
/// normal-force anisotropy with which the SFF equation of the snapshot's a_c and a_t gives its
/// contacts' stress ratio (sff::concise_normal_anisotropy). The model's stress is the SFF equation
/// of its state, whose truncation puts the measured anisotropies' stress ratio 6-10 % below the
/// contacts' at a 500-clump dense specimen's peak; with the measured a_n the fit had to lift a_c
/// to reach the DEM's q/p (docs/network-model.md, "State and stress"). Every front end that fits
/// or checks the model against DEM runs reads them through this. Throws std::runtime_error naming
/// the test and snapshot where no a_n gives its stress ratio.
TestData with_closing_normal_anisotropy(TestData test);

/// The state of the test's first snapshot (axisymmetric about z) with the void ratio of its first
/// series row; the initial fabric is all inherent (Eq. N2d). Throws std::runtime_error naming the
/// test when its data lack Z, Lambda or a_t.
model::network::State<double> initial_state(const TestData& test);

}  // namespace calibration::network
