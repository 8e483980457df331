#include "dem/triaxial.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>

#include "sffcal/final_window.h"
#include "specimen_fixture.h"

namespace dem {
namespace {

TriaxialOptions fast_options() {
  TriaxialOptions options;
  options.strain_rate = 100.0;  // inertial number ~1e-3 at this size: still quasi-static
  options.max_axial_strain = 0.25;
  options.output_strain_interval = 0.005;
  options.critical_min_strain = 1.0;  // run to the maximum: the assertions need the whole curve
  return options;
}

struct Curve {
  std::vector<double> strain, eta, volumetric;
  TriaxialSummary summary;
};

// At 50 /s: the servo's error in a row is the wall force's change over one step, which grows with
// the step and the rate. With the step at 0.7 of leapfrog's limit the worst row of these 150
// clumps is 3.6 % (dense) and 1.7 % (loose) of sigma_3 at 50 /s, 5.4 % and 6.9 % at 100 /s
// (bench/RESULTS.md, "The stability limit").
Curve shear(double compaction_friction) {
  const Simulation specimen = testing::compacted_specimen(150, compaction_friction, 11);
  Simulation sim = testing::shearing_copy(specimen);
  TriaxialOptions options = fast_options();
  options.strain_rate = 50.0;
  TriaxialTest test(sim, options);
  Curve curve;
  curve.summary = test.run(nullptr, [&](const TriaxialProgress&) {
    const std::vector<double> row = test.series_row();
    const auto& names = triaxial_series_names();
    auto at = [&](const char* name) {
      return row[std::find(names.begin(), names.end(), name) - names.begin()];
    };
    curve.strain.push_back(at("axial_strain"));
    curve.eta.push_back(at("eta"));
    curve.volumetric.push_back(at("volumetric_strain"));
  });
  return curve;
}

TEST(Triaxial, DenseDilatesWithAPeakLooseContracts) {
  const Curve dense = shear(0.0);
  const Curve loose = shear(0.5);
  ASSERT_LT(dense.summary.initial_void_ratio, loose.summary.initial_void_ratio - 0.05);
  // Dense: a peak well above the final (critical-like) stress ratio, then dilation.
  EXPECT_GT(dense.summary.peak_eta, 1.15 * dense.summary.critical_eta) << dense.summary.describe();
  EXPECT_LT(dense.volumetric.back(), -0.03);  // eps_v < 0: dilation
  EXPECT_GT(dense.summary.final_void_ratio, dense.summary.initial_void_ratio);
  // Loose: contracts, and peaks far lower than the dense specimen.
  EXPECT_GT(*std::max_element(loose.volumetric.begin(), loose.volumetric.end()), 0.005);
  EXPECT_LT(loose.summary.peak_eta, dense.summary.peak_eta - 0.2) << loose.summary.describe();
  // Lateral stress held by the servo throughout, quasi-static loading.
  EXPECT_LT(dense.summary.worst_lateral_error, 0.05);
  EXPECT_LT(loose.summary.worst_lateral_error, 0.05);
  EXPECT_LT(dense.summary.max_inertial_number, 2e-3);
  // Both approach one critical stress ratio, whatever the initial density.
  EXPECT_NEAR(dense.summary.critical_eta, loose.summary.critical_eta, 0.25);
}

TEST(Triaxial, RejectsBadOptions) {
  Simulation sim = testing::shearing_copy(testing::compacted_specimen(40, 0.3, 2));
  TriaxialOptions options;
  options.strain_rate = -1.0;
  try {
    TriaxialTest test(sim, options);
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("strain_rate"), std::string::npos);
  }
  // An interval the strain's rounding cannot advance looped for ever on one row (issue 17).
  options = TriaxialOptions{};
  options.checkpoint_strain_interval = 1e-320;
  EXPECT_NE(options.validate().find("checkpoint_strain_interval must lie in"), std::string::npos);
  options.checkpoint_strain_interval = 0.01;
  options.output_strain_interval = 2.0;
  EXPECT_NE(options.validate().find("output_strain_interval must lie in"), std::string::npos);
  options.output_strain_interval = kMinStrainInterval;
  EXPECT_EQ(options.validate(), "");
  // A strain rate that would need more than kMaxTestSteps steps is refused with the count.
  options = TriaxialOptions{};
  options.strain_rate = 1e-300;
  try {
    TriaxialTest test(sim, options);
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("steps to reach axial strain"), std::string::npos)
        << e.what();
  }
}

// The grain totals a test divides by (void ratio, inertial number) do not depend on the order the
// engine's spatial re-sorts left the bodies in: a run resumed from a re-sorted checkpoint
// recomputes them to the same bit (issue 17).
TEST(Triaxial, GrainTotalsAreTheSameInAnyBodyOrder) {
  const Simulation specimen = testing::compacted_specimen(60, 0.3, 7);
  const Particles& original = specimen.particles();
  Particles resorted = original;
  const std::vector<int> new_to_old = resorted.sort_spatially(0.37 * 2.0 * original.sphere_radius[0]);
  bool moved = false;
  for (std::size_t k = 0; k < new_to_old.size(); ++k) moved |= new_to_old[k] != static_cast<int>(k);
  ASSERT_TRUE(moved) << "the re-sort must change the body order for this test to mean anything";
  const GrainTotals a = grain_totals(original), b = grain_totals(resorted);
  EXPECT_EQ(a.solid_volume, b.solid_volume);
  EXPECT_EQ(a.mass, b.mass);
  EXPECT_EQ(a.mean_diameter, b.mean_diameter);
  EXPECT_GT(a.solid_volume, 0.0);
  // Grains whose volumes underflow (a diameter of 1e-200 m) are refused, not divided by.
  Particles vanishing = original;
  std::fill(vanishing.volume.begin(), vanishing.volume.end(), 0.0);
  try {
    grain_totals(vanishing);
    FAIL() << "zero solid volume accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("solid volume"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace dem

namespace dem {
namespace {

// A history that reaches a plateau at 0.3 axial strain, with seeded noise of +-0.1 on q/p and
// +-0.1 % on the volumetric strain (the size of the fluctuations of 2000 clumps).
struct History {
  std::vector<double> strain, eta, volume;
};
History plateau_history(double noise_eta, double trend_after) {
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  History h;
  for (int k = 0; k <= 250; ++k) {
    const double e = 0.002 * k;
    h.strain.push_back(e);
    h.eta.push_back((e < 0.3 ? 1.8 - 2.5 * e : 1.05 + trend_after * (e - 0.3)) + noise_eta * u(rng));
    h.volume.push_back((e < 0.3 ? -0.5 * e : -0.15) + 0.001 * u(rng));
  }
  return h;
}

TEST(CriticalState, FoundThroughFluctuationsButNotOnATrend) {
  TriaxialOptions options;
  const History flat = plateau_history(0.1, 0.0);
  std::size_t first = 0;
  while (first < flat.strain.size() &&
         !is_critical_state({flat.strain.begin(), flat.strain.begin() + first + 1},
                            {flat.eta.begin(), flat.eta.begin() + first + 1},
                            {flat.volume.begin(), flat.volume.begin() + first + 1}, options)) {
    ++first;
  }
  ASSERT_LT(first, flat.strain.size());
  EXPECT_GE(flat.strain[first], 0.35);  // a full window past the end of the softening
  EXPECT_LE(flat.strain[first], 0.45);
  // Still softening at 1 per unit strain: never critical.
  const History falling = plateau_history(0.1, -1.0);
  EXPECT_FALSE(is_critical_state(falling.strain, falling.eta, falling.volume, options));
  // Not before critical_min_strain, whatever the data.
  options.critical_min_strain = 0.6;
  EXPECT_FALSE(is_critical_state(flat.strain, flat.eta, flat.volume, options));
}

// The one final-window rule of the DEM, calibration and the scripts: the rows within the width of
// the last strain, boundary included.
TEST(FinalWindow, HoldsTheRowsWithinTheWidthOfTheLastStrain) {
  const std::vector<double> strain = {0.0, 0.1, 0.2, 0.25, 0.3};
  EXPECT_EQ(sffcal::final_window_start(strain, 0.1), 2u);   // 0.3 - 0.2 <= 0.1
  EXPECT_EQ(sffcal::final_window_start(strain, 0.07), 3u);  // 0.2 is outside
  EXPECT_EQ(sffcal::final_window_start(strain, 0.0), 4u);   // the last row only
  EXPECT_EQ(sffcal::final_window_start(strain, 1.0), 0u);   // the whole test
  EXPECT_EQ(sffcal::final_window_start(std::vector<double>{}, 0.1), 0u);
  // Another series (snapshots) within the window of the series' last strain.
  const std::vector<double> snapshots = {0.0, 0.15, 0.22, 0.29};
  EXPECT_EQ(sffcal::final_window_start(snapshots, 0.3, 0.1), 2u);
  EXPECT_EQ(sffcal::final_window_start(snapshots, 0.5, 0.1), 4u);  // none within
}

TEST(Triaxial, InertialNumberUsesTheScaledDensity) {
  // I = rate d sqrt(rho s / p): the dynamics see the density times the scaling s, so the
  // reported inertial number of the first row grows by sqrt(s) over the unscaled run (at the
  // same p, which one step barely changes).
  const Simulation specimen = testing::compacted_specimen(40, 0.3, 5);
  auto first_row = [&](double scaling) {
    ContactParameters law = specimen.contact_parameters();
    SimulationOptions options = specimen.options();
    options.density_scaling = scaling;
    Simulation sim(specimen.state(), law, options);
    TriaxialTest test(sim, fast_options());
    sim.step();
    const std::vector<double> row = test.series_row();
    const auto& names = triaxial_series_names();
    auto at = [&](const char* name) {
      return row[std::find(names.begin(), names.end(), name) - names.begin()];
    };
    return std::make_pair(at("inertial_number"), at("p"));
  };
  const auto [i1, p1] = first_row(1.0);
  const auto [i100, p100] = first_row(100.0);
  ASSERT_GT(i1, 0.0);
  EXPECT_NEAR(i100 / i1 * std::sqrt(p100 / p1), 10.0, 1e-9);
}

// Past the quasi-static limit (I > 1e-3, here with the density scaled 100 times) the run says so
// once, with the progress row where I first passes it, and the summary line marks it; a slow run
// says nothing.
TEST(Triaxial, WarnsOnceWhenTheInertialNumberPassesTheQuasiStaticLimit) {
  const Simulation specimen = testing::compacted_specimen(40, 0.3, 5);
  auto run = [&](double scaling, double rate, std::vector<std::string>* warnings) {
    SimulationOptions options = specimen.options();
    options.density_scaling = scaling;
    Simulation sim(specimen.state(), specimen.contact_parameters(), options);
    TriaxialOptions triaxial = fast_options();
    triaxial.strain_rate = rate;
    triaxial.max_axial_strain = 0.004;
    triaxial.output_strain_interval = 0.001;
    TriaxialTest test(sim, triaxial);
    return test.run(nullptr, [&](const TriaxialProgress& p) {
      if (!p.warning.empty()) warnings->push_back(p.warning);
    });
  };
  std::vector<std::string> fast, slow;
  const TriaxialSummary scaled = run(100.0, 100.0, &fast);
  ASSERT_GT(scaled.max_inertial_number, runfile::kQuasiStaticInertialNumber);
  ASSERT_EQ(fast.size(), 1u);
  EXPECT_NE(fast[0].find("quasi-static limit"), std::string::npos) << fast[0];
  EXPECT_NE(scaled.describe().find("WARNING"), std::string::npos) << scaled.describe();
  const TriaxialSummary gentle = run(1.0, 10.0, &slow);
  ASSERT_LT(gentle.max_inertial_number, runfile::kQuasiStaticInertialNumber);
  EXPECT_TRUE(slow.empty());
  EXPECT_EQ(gentle.describe().find("WARNING"), std::string::npos) << gentle.describe();
}

// The strain limit holds whatever the output interval: an interval larger than the limit (1.0
// against 0.02) ends the test at the limit, with one row there, instead of shearing on to the
// next output row (eps_a = 1 crushed the specimen).
TEST(Triaxial, StopsAtTheStrainLimitWhateverTheOutputInterval) {
  const Simulation specimen = testing::compacted_specimen(40, 0.3, 5);
  Simulation sim = testing::shearing_copy(specimen);
  TriaxialOptions options = fast_options();
  options.max_axial_strain = 0.02;
  options.output_strain_interval = 1.0;
  TriaxialTest test(sim, options);
  int rows = 0;
  const TriaxialSummary summary = test.run(nullptr, [&](const TriaxialProgress&) { ++rows; });
  const double strain_per_step =
      options.strain_rate * sim.time_step();  // 2 * (rate H / 2) dt / H
  EXPECT_FALSE(summary.reached_critical_state);
  EXPECT_NEAR(summary.axial_strain, 0.02, strain_per_step);
  EXPECT_EQ(rows, 2);  // the first row at the start, the last at the limit
  EXPECT_GT(summary.final_void_ratio, 0.0);
}

}  // namespace
}  // namespace dem
