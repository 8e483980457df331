// The wall servo as a control loop, against plants with a known answer (issue 16): a spring
// whose rest position moves at a constant speed (a specimen dilating against the wall), and the
// same spring backed by a mass (the grains behind the wall). The DEM servo runs are in
// stability_test.cc and bench/servo/.
#include <gtest/gtest.h>

#include <cmath>

#include "dem/wall.h"

namespace dem {
namespace {

constexpr double kTarget = 1.0;      // target force [N]
constexpr double kStiffness = 1e3;   // the wall's contact stiffness [N/m]
constexpr double kPush = 1e-3;       // speed at which the specimen pushes the wall out [m/s]

// The force error after `steps` steps of a wall against a spring whose rest position moves out
// at kPush: F = F_target + K (wall's inward travel + kPush t).
double spring_error(const ServoParameters& servo, double dt, double critical_step, int steps) {
  ServoState state;
  double inward = 0.0, error = 0.0;
  for (int n = 0; n < steps; ++n) {
    const double force = kTarget + kStiffness * (inward + kPush * n * dt);
    error = kTarget - force;
    inward += servo_displacement(servo, force, kTarget, kStiffness, dt, critical_step, state);
  }
  return error;
}

TEST(Servo, ProportionalLawLagsAMovingSpecimenByKvDtOverGain) {
  ServoParameters servo;
  servo.integral_time = 0.0;
  servo.max_speed = 1.0;
  for (double dt : {1e-3, 4e-3})
    for (double gain : {0.25, 0.5, 1.0}) {
      servo.gain = gain;
      const double expected = kStiffness * kPush * dt / gain;  // the steady lag, analytic
      EXPECT_NEAR(-spring_error(servo, dt, dt, 4000), expected, 1e-9 * expected)
          << "dt " << dt << " gain " << gain;
    }
}

TEST(Servo, IntegralActionRemovesTheLagBehindAMovingSpecimen) {
  ServoParameters servo;  // the defaults
  servo.max_speed = 1.0;
  for (double safety : {0.1, 0.5, 1.0}) {
    const double critical_step = 1e-3, dt = safety * critical_step;
    const double lag_p = kStiffness * kPush * dt / servo.gain;
    // 40 integral times: the error has decayed far below the proportional lag.
    const int steps = static_cast<int>(40.0 * servo.integral_time / safety);
    const double error = spring_error(servo, dt, critical_step, steps);
    EXPECT_LT(std::abs(error), 1e-6 * lag_p) << "safety " << safety;
  }
}

TEST(Servo, IntegralActionStaysStableWithTheGrainsBehindTheWall) {
  // The wall's spring K pushes a mass m that a second spring K connects to a support moving out
  // at kPush; leapfrog for the mass with the step a fraction of its critical step 2 sqrt(m / 2K).
  ServoParameters servo;
  servo.max_speed = 1.0;
  const double mass = 1e-3, critical_step = 2.0 * std::sqrt(mass / (2.0 * kStiffness));
  for (double safety : {0.05, 0.15, 0.5, 0.9}) {
    const double dt = safety * critical_step;
    ServoState state;
    double inward = 0.0, x = 0.0, v = 0.0, error = 0.0, worst_late = 0.0;
    const int steps = static_cast<int>(1000.0 * servo.integral_time / safety);
    for (int n = 0; n < steps; ++n) {
      const double force = kTarget + kStiffness * (inward + x);
      error = kTarget - force;
      if (n > steps / 2) worst_late = std::max(worst_late, std::abs(error));
      inward += servo_displacement(servo, force, kTarget, kStiffness, dt, critical_step, state);
      const double on_mass = -kStiffness * (inward + x) + kStiffness * (kPush * n * dt - x);
      v += dt * on_mass / mass;
      x += dt * v;
    }
    const double lag_p = kStiffness * kPush * dt / servo.gain;
    EXPECT_TRUE(std::isfinite(error));
    EXPECT_LT(worst_late, 1e-3 * lag_p) << "safety " << safety;
  }
}

TEST(Servo, NeverExceedsItsSpeedCap) {
  // Any force error, any stiffness (none included), any state within the cap.
  ServoParameters servo;
  servo.blend = 0.3;
  const double dt = 1e-8, cap = servo.max_speed * dt;
  for (double error : {-1e9, -1.0, 0.0, 1e-12, 1.0, 1e9})
    for (double stiffness : {0.0, 1e-9, 1e3, 1e12})
      for (double previous : {-cap, 0.0, cap})
        for (double integral : {-cap, 0.0, cap}) {
          ServoState state{previous, integral};
          for (int repeat = 0; repeat < 3; ++repeat) {
            const double move =
                servo_displacement(servo, 1.0, 1.0 + error, stiffness, dt, 5.0 * dt, state);
            EXPECT_LE(std::abs(move), cap * (1.0 + 1e-15)) << error << " " << stiffness;
            EXPECT_LE(std::abs(state.integral), cap * (1.0 + 1e-15));
          }
        }
}

TEST(Servo, IntegralTimeZeroDropsACarriedIntegral) {
  // A state carried from a run with the integral on (compaction into shearing, a resume with
  // the setting changed) must not leave a constant bias in the proportional servo.
  ServoParameters servo;
  servo.integral_time = 0.0;
  const double dt = 1e-3, cap = servo.max_speed * dt;
  ServoState state{0.0, 0.5 * cap};
  const double move = servo_displacement(servo, kTarget, kTarget, kStiffness, dt, dt, state);
  EXPECT_EQ(move, 0.0);  // no force error: the blend of zero and the last move (zero)
  EXPECT_EQ(state.integral, 0.0);
}

TEST(Servo, RefusesANonPhysicalIntegralTime) {
  ServoParameters servo;
  for (double bad : {-1.0, 0.5, std::nan(""), HUGE_VAL}) {
    servo.integral_time = bad;
    EXPECT_NE(servo.validate().find("integral_time"), std::string::npos) << bad;
  }
  servo.integral_time = 0.0;
  EXPECT_EQ(servo.validate(), "");
}

// The servo's validated range is its stable range: on a spring at rest with an initial force
// error, settings just inside the derived bound (blend 1.05 kappa / (1 + kappa)) settle and are
// accepted, settings just outside (0.95 of it) diverge and are refused, naming the blend; the
// defaults settle at any step up to the critical one.
TEST(Servo, TheValidatedRangeIsTheStableRangeOnASpring) {
  // The force error after `steps` steps from an error of 1 N, the spring's rest position fixed.
  auto settle = [](const ServoParameters& servo, double step_ratio, int steps) {
    const double critical_step = 1e-3, dt = step_ratio * critical_step;
    ServoState state;
    double inward = 0.0, error = 1.0;
    for (int n = 0; n < steps && std::isfinite(error); ++n) {
      const double force = kTarget - 1.0 + kStiffness * inward;
      error = kTarget - force;
      inward += servo_displacement(servo, force, kTarget, kStiffness, dt, critical_step, state);
    }
    return std::abs(error);
  };
  for (double gain : {0.3, 0.8, 1.0})
    for (double integral_time : {1.0, 10.0})
      for (double step_ratio : {0.5, 1.0}) {
        const double kappa = step_ratio / integral_time, bound = kappa / (1.0 + kappa);
        ServoParameters servo;
        servo.gain = gain;
        servo.integral_time = integral_time;
        servo.max_speed = 1e9;  // the cap never binds: the linear loop
        const std::string where = "gain " + std::to_string(gain) + " integral_time " +
                                  std::to_string(integral_time) + " ratio " +
                                  std::to_string(step_ratio);
        servo.blend = 1.05 * bound;
        EXPECT_EQ(servo.validate(step_ratio), "") << where;
        EXPECT_LT(settle(servo, step_ratio, 400000), 1e-6) << where;
        servo.blend = 0.95 * bound;
        EXPECT_NE(servo.validate(step_ratio).find("blend must exceed"), std::string::npos)
            << where;
        EXPECT_GT(settle(servo, step_ratio, 400000), 1e3) << where;  // diverging
      }
  const ServoParameters defaults;
  for (double step_ratio : {0.1, 0.7, 1.0}) {
    EXPECT_EQ(defaults.validate(step_ratio), "") << step_ratio;
    EXPECT_LT(settle(defaults, step_ratio, 20000), 1e-9) << step_ratio;
  }
  // The review's unstable settings: blend 0.05 (defaults otherwise), and T_i = 1 with blend 0.3.
  ServoParameters slow;
  slow.blend = 0.05;
  EXPECT_NE(slow.validate(0.7), "");
  slow.blend = 0.3;
  slow.integral_time = 1.0;
  EXPECT_NE(slow.validate(0.7), "");
}

}  // namespace
}  // namespace dem
