// The loading paths of the triaxial driver (issue 18): their controls against the analytic
// constraints each path imposes (constant volume, constant p, the b ratio, sigma_3), on a small
// specimen, and the names and contradictions refused.
#include "dem/loading_path.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <iterator>
#include <map>
#include <random>
#include <string>

#include "dem/run_config.h"
#include "dem/specimen.h"
#include "dem/triaxial.h"
#include "specimen_fixture.h"

namespace dem {
namespace {

TEST(LoadingPath, NamesRoundTripAndAnUnknownOneIsRefusedNamingTheOthers) {
  for (const std::string& name : loading_path_names())
    EXPECT_EQ(loading_path_name(parse_loading_path(name)), name);
  try {
    parse_loading_path("sideways");
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("\"sideways\""), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("\"undrained_extension\""), std::string::npos) << e.what();
  }
  std::string text = default_run_config_text();
  text.replace(text.find("path = \"drained_compression\""), 29, "path = \"sideways\"");
  try {
    parse_run_config(text, "t.toml");
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("t.toml: triaxial.path: unknown loading path"),
              std::string::npos)
        << e.what();
  }
}

TEST(LoadingPath, ContradictoryOrOutOfRangeBIsRefusedByName) {
  TriaxialOptions options;
  options.b = 0.3;  // drained compression does not read b
  EXPECT_NE(options.validate().find("read only by path = \"true_triaxial\""), std::string::npos)
      << options.validate();
  options.path = LoadingPath::kTrueTriaxial;
  EXPECT_EQ(options.validate(), "");
  options.b = 1.5;
  EXPECT_NE(options.validate().find("b must lie in [0, 1]"), std::string::npos);
}

// The targets keep p = p0 and (sigma_y - sigma_x) = b (sigma_z - sigma_x), for any axial stress.
TEST(LoadingPath, LateralTargetsKeepTheMeanStressAndB) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> axial(1e5, 3e5), ratio(0.0, 1.0);
  const double p0 = 1e5;
  for (int k = 0; k < 100; ++k) {
    const double sz = axial(rng), b = ratio(rng);
    const auto t = lateral_targets(LoadingPath::kTrueTriaxial, p0, b, sz);
    EXPECT_NEAR((t[0] + t[1] + sz) / 3.0, p0, 1e-9);
    EXPECT_NEAR((t[1] - t[0]) / (sz - t[0]), b, 1e-12);
    const auto c = lateral_targets(LoadingPath::kConstantPCompression, p0, 0.0, sz);
    EXPECT_EQ(c[0], c[1]);
    EXPECT_NEAR((2.0 * c[0] + sz) / 3.0, p0, 1e-9);
    const auto d = lateral_targets(LoadingPath::kDrainedExtension, p0, 0.0, sz);
    EXPECT_EQ(d[0], p0);
    EXPECT_EQ(d[1], p0);
  }
  for (double h : {0.5, 0.9, 1.0, 1.3})
    EXPECT_NEAR(std::pow(constant_volume_width(2.0, 1.0, h), 2) * h, 4.0, 1e-12);
}

struct PathRun {
  std::map<std::string, std::vector<double>> rows;
  TriaxialSummary summary;
};

PathRun run_path(const Simulation& specimen, LoadingPath path, double b, double max_strain = 0.02,
                 UndrainedLateral lateral = UndrainedLateral::kEqualStrains) {
  Simulation sim = testing::shearing_copy(specimen);
  TriaxialOptions options;
  options.path = path;
  options.b = b;
  options.undrained_lateral = lateral;
  options.max_axial_strain = max_strain;
  options.output_strain_interval = 0.001;
  options.critical_min_strain = 1.0;
  TriaxialTest test(sim, options);
  PathRun run;
  run.summary = test.run(nullptr, [&](const TriaxialProgress&) {
    const std::vector<double> row = test.series_row();
    const auto& names = triaxial_series_names();
    for (std::size_t k = 0; k < names.size(); ++k) run.rows[names[k]].push_back(row[k]);
  });
  return run;
}

// Each path on one dense specimen of 60 clumps at 100 kPa, to 2 % of axial strain.
TEST(LoadingPath, EachPathHoldsWhatItPrescribes) {
  const Simulation specimen = testing::compacted_specimen(60, 0.0, 4);
  const double p0 = 1e5;
  for (const LoadingPath path : {LoadingPath::kUndrainedCompression, LoadingPath::kUndrainedExtension}) {
    const PathRun run = run_path(specimen, path, 0.0);
    const auto& ev = run.rows.at("volumetric_strain");
    const double worst = std::max(std::abs(*std::max_element(ev.begin(), ev.end())),
                                  std::abs(*std::min_element(ev.begin(), ev.end())));
    EXPECT_LT(worst, 1e-12) << loading_path_name(path);  // the volume to rounding
    EXPECT_NEAR(run.rows.at("axial_strain").back(), axial_direction(path) * 0.02, 1e-4);
    // A dense specimen that cannot dilate: the mean effective stress climbs.
    EXPECT_GT(run.rows.at("p").back(), 1.5 * p0) << loading_path_name(path);
    EXPECT_GT(axial_direction(path) * run.rows.at("q").back(), 0.0);
  }
  {
    const PathRun run = run_path(specimen, LoadingPath::kDrainedExtension, 0.0);
    EXPECT_NEAR(run.rows.at("axial_strain").back(), -0.02, 1e-4);
    EXPECT_LT(run.rows.at("q").back(), -0.3 * p0);
    EXPECT_LT(run.summary.peak_eta, -0.5);  // the peak of an extension test is its most negative
    for (const char* wall : {"wall_stress_xx", "wall_stress_yy"})
      EXPECT_NEAR(run.rows.at(wall).back(), p0, 0.03 * p0) << wall;
  }
  for (const double b : {0.0, 0.5}) {
    const LoadingPath path = b == 0.0 ? LoadingPath::kConstantPCompression : LoadingPath::kTrueTriaxial;
    const PathRun run = run_path(specimen, path, b);
    const auto& strain = run.rows.at("axial_strain");
    for (std::size_t k = 0; k < strain.size(); ++k) {
      if (strain[k] < 0.005) continue;  // the servo's first 0.5 %
      EXPECT_NEAR(run.rows.at("p")[k], p0, 0.01 * p0) << loading_path_name(path) << " row " << k;
      const double sx = run.rows.at("wall_stress_xx")[k], sy = run.rows.at("wall_stress_yy")[k],
                   sz = run.rows.at("wall_stress_zz")[k];
      EXPECT_NEAR((sy - sx) / (sz - sx), b, 0.02) << loading_path_name(path) << " row " << k;
    }
    EXPECT_GT(run.rows.at("q").back(), 0.5 * p0);
  }
}

// b = 1 from a specimen that holds no forces yet (restored, as from its file): the first targets
// are the path's start, sigma_x = sigma_y = p0, not sigma_y = sigma_z = 0 (it was refused at
// step 0). At constant p with sigma_y = sigma_z, sigma_x = 3 p0 - 2 sigma_z reaches 0 at
// sigma_z = 1.5 p0 (q/p = 0.75), past which the path is refused by name.
TEST(LoadingPath, TrueTriaxialWithBOneStartsFromTheIsotropicState) {
  const Simulation specimen = testing::compacted_specimen(60, 0.0, 4);
  const PathRun run = run_path(specimen, LoadingPath::kTrueTriaxial, 1.0, 0.004);
  const auto& strain = run.rows.at("axial_strain");
  ASSERT_GE(strain.size(), 4u);
  EXPECT_NEAR(strain.back(), 0.004, 1e-4);
  const double p0 = 1e5;
  // Measured: p within 1.1 % of p0, (sigma_y - sigma_x) / (sigma_z - sigma_x) 0.984-1.004 in
  // the rows past the first, where the servo has followed the first steps.
  for (std::size_t k = 1; k < strain.size(); ++k) {
    EXPECT_NEAR(run.rows.at("p")[k], p0, 0.02 * p0) << "row " << k;
    const double sx = run.rows.at("wall_stress_xx")[k], sy = run.rows.at("wall_stress_yy")[k],
                 sz = run.rows.at("wall_stress_zz")[k];
    EXPECT_NEAR((sy - sx) / (sz - sx), 1.0, 0.03) << "row " << k;
  }
  EXPECT_GT(run.rows.at("q").back(), 0.5 * p0);
}

// A deposit at 90 degrees (bedding normal along y, docs/dem.md) has unequal lateral axes: held at
// constant volume with equal lateral strains, its lateral stresses part; with equal_stresses they
// stay together, as a cell's fluid holds them, and the volume stays constant to rounding.
TEST(LoadingPath, UndrainedEqualStressesHoldsADepositsLateralStressesTogether) {
  RunConfig config = parse_run_config(default_run_config_text());
  config.num_bodies = 150;
  config.preparation.method = PreparationMethod::kDeposition;
  config.preparation.loading_angle_deg = 90.0;
  config.preparation.compaction_friction = 0.15;
  const Simulation specimen = prepare_specimen(config, nullptr);
  auto lateral_parting = [](const PathRun& run) {  // the largest |sigma_x - sigma_y| / p past 0.5 %
    double worst = 0.0;
    for (std::size_t k = 0; k < run.rows.at("axial_strain").size(); ++k)
      if (run.rows.at("axial_strain")[k] > 0.005)
        worst = std::max(worst, std::abs(run.rows.at("wall_stress_xx")[k] -
                                         run.rows.at("wall_stress_yy")[k]) /
                                    run.rows.at("p")[k]);
    return worst;
  };
  const PathRun strains = run_path(specimen, LoadingPath::kUndrainedCompression, 0.0, 0.03);
  const PathRun stresses = run_path(specimen, LoadingPath::kUndrainedCompression, 0.0, 0.03,
                                    UndrainedLateral::kEqualStresses);
  for (const PathRun* run : {&strains, &stresses}) {
    const auto& ev = run->rows.at("volumetric_strain");
    EXPECT_LT(std::max(std::abs(*std::max_element(ev.begin(), ev.end())),
                       std::abs(*std::min_element(ev.begin(), ev.end()))),
              1e-12);
    EXPECT_NEAR(run->rows.at("axial_strain").back(), 0.03, 1e-4);
  }
  // Measured: 0.148 with equal strains, 0.0093 with equal stresses.
  EXPECT_GT(lateral_parting(strains), 0.1) << "equal strains";
  EXPECT_LT(lateral_parting(stresses), 0.02) << "equal stresses";
  // Each wall against the mean lateral stress: 0.026 (the drained servo on this specimen holds
  // its walls within 0.015 of sigma_3; here the two walls of an axis move together, so the
  // contact noise between them stays).
  EXPECT_LT(stresses.summary.worst_lateral_error, 0.04);
}

TEST(LoadingPath, EqualStressesIsReadOnlyByTheUndrainedPaths) {
  TriaxialOptions options;
  options.undrained_lateral = UndrainedLateral::kEqualStresses;
  EXPECT_NE(options.validate().find("read only by the undrained paths"), std::string::npos)
      << options.validate();
  options.path = LoadingPath::kUndrainedExtension;
  EXPECT_EQ(options.validate(), "");
  std::string text = default_run_config_text();
  text.replace(text.find("undrained_lateral = \"equal_strains\""), 35,
               "undrained_lateral = \"equal_pressures\"");
  try {
    parse_run_config(text, "t.toml");
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("t.toml: triaxial.undrained_lateral: unknown"),
              std::string::npos)
        << e.what();
  }
}

// Undrained compression of a very loose specimen (compacted with friction 1): the grains that
// would contract cannot, so the contact network unloads and p falls (static liquefaction).
TEST(LoadingPath, AnUndrainedLooseSpecimenLosesItsMeanStress) {
  const Simulation specimen = testing::compacted_specimen(60, 1.0, 4);
  const PathRun run = run_path(specimen, LoadingPath::kUndrainedCompression, 0.0);
  EXPECT_LT(run.rows.at("p").back(), 0.5e5);
  // With sigma_x = sigma_y held, the same; and the rows where the lateral stress has gone (below
  // 0.01 p0) do not count in the lateral error, which divides by it.
  const PathRun equal = run_path(specimen, LoadingPath::kUndrainedCompression, 0.0, 0.02,
                                 UndrainedLateral::kEqualStresses);
  EXPECT_LT(equal.rows.at("p").back(), 0.5e5);
  // Measured: 0.15 (the rows before p went); 3.0 when the rows after count.
  EXPECT_LT(equal.summary.worst_lateral_error, 0.5);
}

// On a constant-volume path the mean stress takes the volume's place in the critical-state test.
TEST(LoadingPath, UndrainedCriticalStateAsksForAStationaryMeanStress) {
  TriaxialOptions options;
  options.critical_min_strain = 0.2;
  std::vector<double> strain, eta, p_flat, p_rising;
  for (int k = 0; k <= 150; ++k) {
    strain.push_back(0.002 * k);
    eta.push_back(1.2);
    p_flat.push_back(2.0);
    p_rising.push_back(2.0 + 2.0 * strain.back());  // +0.2 of p0 over the window
  }
  EXPECT_TRUE(is_critical_state_at_constant_volume(strain, eta, p_flat, options));
  EXPECT_FALSE(is_critical_state_at_constant_volume(strain, eta, p_rising, options));
  // Liquefied: p / p0 flat at 0.001 is stationary, but no critical state.
  const std::vector<double> p_lost(strain.size(), 0.001);
  EXPECT_FALSE(is_critical_state_at_constant_volume(strain, eta, p_lost, options));
}

// The critical stress ratio in extension is below compression's (issue 18, point 4): dense
// specimens of 100 clumps sheared to |eps_a| = 30 % both ways, M the mean |q/p| over
// |eps_a| >= 20 % (101 rows; a 100-clump q/p scatters by about 0.1 from row to row). One specimen
// is one sample of a chaotic run: specimen 4 gave M_e/M_c = 0.76, and 1.006 once the contact
// normal changed in its last bit (issue 16); specimens 5 and 7 gave 0.77 and 0.91. So the test
// compares the means over three specimens (the 500-clump matrix, docs/reference-matrix.md:
// 0.71-0.95); a Mohr-Coulomb material with the friction angle of M_c would give
// 3/(3 + M_c) = 0.72, a Drucker-Prager one 1.
TEST(LoadingPath, ExtensionIsWeakerThanCompressionAtLargeStrain) {
  double sum_c = 0.0, sum_e = 0.0;
  const std::uint64_t seeds[] = {4, 5, 7};
  for (const std::uint64_t seed : seeds) {
    const Simulation specimen = testing::compacted_specimen(100, 0.0, seed);
    double critical[2] = {0.0, 0.0};
    int k = 0;
    for (const LoadingPath path :
         {LoadingPath::kDrainedCompression, LoadingPath::kDrainedExtension}) {
      const PathRun run = run_path(specimen, path, 0.0, 0.3);
      const auto& strain = run.rows.at("axial_strain");
      double sum = 0.0;
      int rows = 0;
      for (std::size_t r = 0; r < strain.size(); ++r) {
        if (std::abs(strain[r]) < 0.2) continue;
        sum += std::abs(run.rows.at("q")[r] / run.rows.at("p")[r]);
        ++rows;
      }
      ASSERT_GT(rows, 50) << loading_path_name(path);
      critical[k++] = sum / rows;
    }
    std::printf("specimen %llu: M_c %.3f, M_e %.3f, M_e/M_c %.3f\n",
                static_cast<unsigned long long>(seed), critical[0], critical[1],
                critical[1] / critical[0]);
    sum_c += critical[0];
    sum_e += critical[1];
  }
  const double n = static_cast<double>(std::size(seeds));
  const double m_c = sum_c / n, m_e = sum_e / n, ratio = m_e / m_c;
  RecordProperty("M_c", std::to_string(m_c));
  RecordProperty("M_e", std::to_string(m_e));
  RecordProperty("M_e_over_M_c", std::to_string(ratio));
  std::printf("mean of %d: M_c %.3f, M_e %.3f, M_e/M_c %.3f\n", static_cast<int>(n), m_c, m_e,
              ratio);
  EXPECT_GT(m_c, 0.8);  // a frictional granular material, not a stuck or a loose one
  EXPECT_LT(ratio, 0.95);
  EXPECT_GT(ratio, 0.6);
}

// Undrained compression of a medium-dense specimen (100 clumps compacted with friction 0.35,
// e0 = 0.83): p' first falls (contraction held back) to a minimum, the phase transformation, then
// rises as the specimen turns dilative, and q/p approaches the critical stress ratio M_c of the
// same specimen in drained compression (mean q/p over 20-30 %). Measured: p' 28 kPa at 1.9 %,
// 166 kPa at 8 %; q/p over 6-8 % 1.32 against M_c 1.16. Which of these a specimen shows depends
// on how far its e0 lies from the critical void ratio, which scatters from specimen to specimen at
// this size. Undrained to 8 % with the time step at the stability limit, seeds 1-8 of friction
// 0.35 gave: 2 and 4 turn after a minimum, 7 falls only to 0.9 p'0, 6 rises from the start, 1, 3,
// 5 and 8 liquefy or end below p'0; of friction 0.3 (the recipe before that step, seed 4, which
// then fell to 0.77 p'0) only seed 5 falls below 0.9 p'0, and it ends below p'0.
TEST(LoadingPath, UndrainedMediumSpecimenTurnsAfterPhaseTransformationTowardsTheCriticalState) {
  const Simulation specimen = testing::compacted_specimen(100, 0.35, 4);
  const PathRun drained = run_path(specimen, LoadingPath::kDrainedCompression, 0.0, 0.3);
  auto mean_eta = [](const PathRun& run, double from) {
    double sum = 0.0;
    int rows = 0;
    for (std::size_t r = 0; r < run.rows.at("axial_strain").size(); ++r) {
      if (run.rows.at("axial_strain")[r] < from) continue;
      sum += run.rows.at("q")[r] / run.rows.at("p")[r];
      ++rows;
    }
    return rows > 0 ? sum / rows : 0.0;
  };
  const double critical = mean_eta(drained, 0.2);
  const PathRun run = run_path(specimen, LoadingPath::kUndrainedCompression, 0.0, 0.08);
  const std::vector<double>& p = run.rows.at("p");
  const auto lowest = std::min_element(p.begin(), p.end());
  const double transformation_strain = run.rows.at("axial_strain")[static_cast<std::size_t>(lowest - p.begin())];
  const double p0 = p.front(), eta_end = mean_eta(run, 0.06);
  std::printf("p' min %.0f Pa at %.3f, p' end %.0f Pa; q/p over 6-8 %% %.3f, M_c %.3f\n", *lowest,
              transformation_strain, p.back(), eta_end, critical);
  EXPECT_LT(*lowest, 0.9 * p0);            // contractive first
  EXPECT_GT(transformation_strain, 0.005);
  EXPECT_LT(transformation_strain, 0.05);
  EXPECT_GT(p.back(), 2.0 * *lowest);      // dilative after the phase transformation
  EXPECT_GT(p.back(), p0);
  EXPECT_NEAR(eta_end, critical, 0.15 * critical);
}

}  // namespace
}  // namespace dem

