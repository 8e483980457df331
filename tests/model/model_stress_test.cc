// Stress cases of the ACST update (issue 8, "FE and model"): states near zero mean stress and at
// the apex of the yield cone. Every update must either succeed with a finite state whose mean
// stress stays at or above options.min_pressure, or fail and hand back the start state; never NaN.
#include <gtest/gtest.h>

#include <cmath>

#include "model/acst_model.h"
#include "model/material_point.h"
#include "toyoura.h"

namespace model::acst {
namespace {

using testing::toyoura;

bool finite(const State<double>& s) {
  return s.stress.allFinite() && std::isfinite(s.void_ratio) && s.alpha.allFinite() &&
         s.alpha_in.allFinite() && s.fabric.allFinite();
}

bool unchanged(const State<double>& end, const State<double>& start) {
  return end.stress == start.stress && end.void_ratio == start.void_ratio && end.alpha == start.alpha &&
         end.fabric == start.fabric;
}

double mean_stress(const State<double>& s) { return s.stress.trace() / 3.0; }

Tensor<double> shear_xy(double gamma) {
  Tensor<double> t = Tensor<double>::Zero();
  t(0, 1) = t(1, 0) = 0.5 * gamma;
  return t;
}

// Checks the contract of one update and returns whether it succeeded.
bool check_update(const State<double>& start, const Tensor<double>& increment, State<double>& end) {
  const IntegrationOptions options;
  const UpdateStatus status = update_state(toyoura(), start, increment, end, options);
  EXPECT_TRUE(finite(end));
  if (status == UpdateStatus::kFailed) {
    EXPECT_TRUE(unchanged(end, start));
    return false;
  }
  EXPECT_GE(mean_stress(end), options.min_pressure);
  return true;
}

TEST(ModelStress, StatesBelowTheMinimumPressureAreRefusedUnchanged) {
  const IntegrationOptions options;
  for (double p : {0.5 * options.min_pressure, 0.0, -1e3}) {
    const State<double> start = isotropic_state(p, 0.8, triaxial_deviator(0.2));
    State<double> end;
    EXPECT_EQ(update_state(toyoura(), start, Tensor<double>(1e-5 * Tensor<double>::Identity()), end),
              UpdateStatus::kFailed)
        << "p = " << p;
    EXPECT_TRUE(unchanged(end, start));
  }
}

TEST(ModelStress, ShearNearZeroPressureStaysFiniteOrFailsCleanly) {
  // 1 kPa, 300 Pa and 150 Pa: just above the 100 Pa floor. Shear in compression, extension and
  // simple shear, each in 50 increments of 2e-5 (constant volume).
  for (double p : {1e3, 300.0, 150.0}) {
    for (const Tensor<double>& direction :
         {triaxial_deviator(1.0), Tensor<double>(-triaxial_deviator(1.0)), shear_xy(1.0)}) {
      State<double> s = isotropic_state(p, 0.8, triaxial_deviator(0.2));
      int succeeded = 0;
      for (int k = 0; k < 50; ++k) {
        State<double> next;
        if (!check_update(s, Tensor<double>(2e-5 * direction), next)) break;
        s = next;
        ++succeeded;
      }
      EXPECT_GT(succeeded, 0) << "p = " << p << ": not even the first small shear increment";
    }
  }
}

TEST(ModelStress, UnloadingToTheFloorEndsInAFailureNotInNaN) {
  // Volumetric extension from 1 kPa in increments of 1e-5: the pressure falls until an update
  // would cross the 100 Pa floor; that update fails and leaves the last good state.
  State<double> s = isotropic_state(1e3, 0.8, triaxial_deviator(0.2));
  const Tensor<double> extension = -1e-5 * Tensor<double>::Identity();
  int k = 0;
  for (; k < 10000; ++k) {
    State<double> next;
    if (!check_update(s, extension, next)) break;
    EXPECT_LT(mean_stress(next), mean_stress(s));
    s = next;
  }
  EXPECT_LT(k, 10000) << "the floor was never reached";
  EXPECT_LT(mean_stress(s), 1e3);
}

TEST(ModelStress, ApexShearInEveryDirectionAndItsTangentAreFinite) {
  // At the apex (isotropic stress, alpha = 0) the loading direction n is undefined: the update
  // must pick one from the increment, for compression, extension and simple shear alike.
  const State<double> apex = isotropic_state(100e3, 0.8, Tensor<double>(Tensor<double>::Zero()));
  ASSERT_TRUE(apex.alpha.isZero());
  for (const Tensor<double>& direction :
       {triaxial_deviator(1.0), Tensor<double>(-triaxial_deviator(1.0)), shear_xy(1.0)}) {
    for (double size : {1e-6, 1e-3, 3e-2}) {
      State<double> end;
      ASSERT_TRUE(check_update(apex, Tensor<double>(size * direction), end)) << "size " << size;
      EXPECT_GT((end.stress - apex.stress).norm(), 0.0);
      Eigen::Matrix<double, 9, 9> tangent;
      State<double> with_tangent;
      ASSERT_NE(update_with_tangent(toyoura(), apex, Tensor<double>(size * direction), with_tangent, tangent),
                UpdateStatus::kFailed);
      EXPECT_TRUE(tangent.allFinite()) << "size " << size;
    }
  }
  // No increment at all at the apex: the tangent is the elastic one, finite and positive definite
  // on symmetric strains (its diagonal terms).
  Eigen::Matrix<double, 9, 9> tangent;
  State<double> end;
  ASSERT_EQ(update_with_tangent(toyoura(), apex, Tensor<double>(Tensor<double>::Zero()), end, tangent),
            UpdateStatus::kOk);
  ASSERT_TRUE(tangent.allFinite());
  for (int i : {0, 4, 8}) EXPECT_GT(tangent(i, i), 0.0);
}

}  // namespace
}  // namespace model::acst
