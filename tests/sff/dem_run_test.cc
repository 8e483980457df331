// The SFF analysis of a whole (small) dense DEM triaxial test, read back from its run file:
// walls and particle-form stress agree (T3), the SFF equation follows eta over the whole test
// (T11), and the normal-force anisotropy and the mobilisation peak with the stress ratio.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>

#include "../dem/specimen_fixture.h"
#include "dem/triaxial.h"
#include "sff/analysis.h"
#include "sff/run_snapshot.h"

namespace sff {
namespace {

TEST(DemRun, SffFollowsADenseTestAndForceAnisotropyPeaksWithTheStress) {
  dem::Simulation sim = dem::testing::shearing_copy(dem::testing::compacted_specimen(150, 0.0, 21));
  dem::TriaxialOptions options;
  options.strain_rate = 100.0;
  options.max_axial_strain = 0.15;
  options.output_strain_interval = 0.005;
  options.snapshot_strain_interval = 0.01;
  options.checkpoint_strain_interval = 1.0;
  const std::string path =
      (std::filesystem::temp_directory_path() / "sffcal_dem_run_test.h5").string();
  runfile::RunMetadata meta{"triaxial", "", 21, "test"};
  meta.physics.youngs_modulus = sim.contact_parameters().youngs_modulus;
  meta.physics.friction = sim.contact_parameters().friction;
  {
    runfile::RunFile file = runfile::RunFile::create(path, meta, dem::triaxial_series_names());
    dem::TriaxialTest(sim, options).run(&file, nullptr);
  }
  const runfile::RunFile file = runfile::RunFile::open(path);
  const runfile::RunPhysics physics = file.metadata().physics;
  ASSERT_GE(file.num_snapshots(), 15);

  std::vector<SnapshotAnalysis> all;
  std::vector<double> strain;
  for (int k = 0; k < file.num_snapshots(); ++k) {
    const runfile::Snapshot s = file.read_snapshot(k);
    const SnapshotInput in = snapshot_input(s, physics);
    all.push_back(analyse_snapshot(in));
    strain.push_back(s.axial_strain);
    const SnapshotAnalysis& a = all.back();
    std::printf("eps %.3f eta %.3f walls %.3f (|particle - walls| %.4f p, wall layer %.3f) "
                "eta_sff %.3f (stress error %.3f) a_c %.3f a_n %.3f m %.3f\n",
                s.axial_strain, a.eta, a.wall_eta, a.wall_stress_error, a.wall_layer_ratio,
                a.eta_sff, a.sff_error, a.a_c, a.a_n, a.m);
  }
  std::filesystem::remove(path);

  auto argmax = [&](auto value) {
    std::size_t best = 0;
    for (std::size_t k = 0; k < all.size(); ++k)
      if (value(all[k]) > value(all[best])) best = k;
    return best;
  };
  const std::size_t peak = argmax([](const SnapshotAnalysis& a) { return a.eta; });
  double decoupled_ratio_sum = 0.0;
  int sheared = 0;
  for (std::size_t k = 0; k < all.size(); ++k) {
    const SnapshotAnalysis& a = all[k];
    // T3: with the wall contacts' terms, the average stress is the wall stress; only inertia
    // separates them (I < 2e-3 here): within 2 % of p.
    EXPECT_LT(a.wall_stress_error, 0.02) << "snapshot " << k;
    // The SFF equation over the whole test (150 clumps; measured below 5 %).
    EXPECT_LT(a.sff_error, 0.10) << "snapshot " << k;
    if (a.eta > 0.3) {
      EXPECT_NEAR(a.eta_sff, a.eta, 0.12 * a.eta) << "snapshot " << k;
      // T11: the clump branch remainder is small; the anisotropies carrying the shear are
      // positive; the decoupled form (2/5)(a_c + a_n) + (3/5) mu m, which assumes the
      // mobilisation independent of the normal force, understates eta: within 15 % on average
      // over the test and 20 % at each snapshot. Measured on six specimens of this recipe
      // (seeds 21-26), the lowest ratio over a test was 0.864-0.934 with the step of earlier
      // versions and 0.835-0.928 with the step at 0.7 of the stability limit (seed 21: 0.826-0.864
      // at 0.37-1.0 of it, so its specimen and not the step), the mean 0.88 here.
      EXPECT_LT(a.branch_ratio, 0.1) << "snapshot " << k;
      EXPECT_GT(a.a_c, 0.0) << "snapshot " << k;
      EXPECT_GT(a.a_n, 0.0) << "snapshot " << k;
      EXPECT_GT(a.m, 0.0) << "snapshot " << k;
      EXPECT_GT(a.sliding_fraction, 0.0) << "snapshot " << k;
      EXPECT_NEAR(a.eta_decoupled, a.eta, 0.20 * a.eta) << "snapshot " << k;
      decoupled_ratio_sum += a.eta_decoupled / a.eta;
      ++sheared;
    }
    EXPECT_GE(a.mechanical_coordination, a.coordination);  // removing rattlers raises Z
  }
  ASSERT_GT(sheared, 0);
  EXPECT_NEAR(decoupled_ratio_sum / sheared, 1.0, 0.15);
  // The analysis of the stored records equals the engine's own Love-Weber stress.
  EXPECT_LT((all.back().stress - sim.contact_stress(false)).norm(), 1e-9 * all.back().stress.norm());
  // A dense specimen: a stress peak well above the final ratio; the normal-force anisotropy and
  // the mobilisation reach their maxima near it, while the fabric keeps growing after it.
  EXPECT_GT(all[peak].eta, 1.15 * all.back().eta);
  const std::size_t peak_an = argmax([](const SnapshotAnalysis& a) { return a.a_n; });
  const std::size_t peak_m = argmax([](const SnapshotAnalysis& a) { return a.m; });
  std::printf("peak eta at %.3f, a_n at %.3f, m at %.3f\n", strain[peak], strain[peak_an], strain[peak_m]);
  EXPECT_NEAR(strain[peak_an], strain[peak], 0.03);
  EXPECT_NEAR(strain[peak_m], strain[peak], 0.03);
}

}  // namespace
}  // namespace sff
