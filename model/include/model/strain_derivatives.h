// The ACST update with every state variable differentiated w.r.t. the strain increment, in Jets:
// what the material-point driver needs for its Newton matrix and for the chain rule of parameter
// derivatives. Needs Ceres (ceres/jet.h); the installed sffcal::model interface does not.
#pragma once

#include <ceres/jet.h>

#include "model/acst_model.h"

namespace model::acst {

/// Jet seeded on the 6 independent strain components (Voigt xx, yy, zz, xy, yz, xz; each shear
/// seed moves eps_ij and eps_ji together).
using StrainJet = ceres::Jet<double, 6>;

/// The update with every state variable differentiated w.r.t. the 6 strain components (the raw
/// form of update_with_tangent). end.x.a are the values, end.x.v[k] = d x / d eps_k.
UpdateStatus update_with_strain_derivatives(const Parameters<double>& par,
                                            const State<double>& start,
                                            const Tensor<double>& strain_increment,
                                            State<StrainJet>& end,
                                            const IntegrationOptions& options = {});

}  // namespace model::acst
