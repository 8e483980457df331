// The equal-area direction cells of the general §6 checks (sff-theory.md §6.2; issue 18): equal
// solid angles, exact cell moments, and a partition that a sign change of a frame axis maps onto
// itself.
#include "sff/direction_cells.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <random>

#include "sff/statistics.h"
#include "sffcal/constants.h"
#include "synthetic_contacts.h"

namespace sff {
namespace {

using testing::random_unit;

TEST(DirectionCells, HaveEqualSolidAnglesAndExactMoments) {
  const Eigen::Matrix3d frame =
      Eigen::AngleAxisd(0.7, Eigen::Vector3d(1.0, 2.0, 3.0).normalized()).toRotationMatrix();
  for (const int size : {3, 41, 201}) {
    const DirectionCells cells(size, frame);
    // Uniform directions fill equal-area cells equally (binomial scatter).
    std::mt19937_64 rng(31);
    const int samples = 400'000;
    std::vector<int> counts(static_cast<std::size_t>(size), 0);
    std::vector<Eigen::Matrix3d> dyads(static_cast<std::size_t>(size), Eigen::Matrix3d::Zero());
    for (int k = 0; k < samples; ++k) {
      const Eigen::Vector3d n = random_unit(rng);
      const int cell = cells.cell_of(n);
      ASSERT_GE(cell, 0);
      ASSERT_LT(cell, size);
      EXPECT_EQ(cells.cell_of(-n), cell);  // n and -n are one direction
      ++counts[static_cast<std::size_t>(cell)];
      double sign = 1.0;
      const Eigen::Vector3d local = cells.to_frame(n, sign);
      dyads[static_cast<std::size_t>(cell)] += local * local.transpose();
    }
    const double expected = static_cast<double>(samples) / size;
    const double p = 1.0 / size;
    for (int k = 0; k < size; ++k) {
      const auto kk = static_cast<std::size_t>(k);
      EXPECT_NEAR(counts[kk], expected, 5.0 * std::sqrt(samples * p * (1.0 - p))) << size << " " << k;
      // The closed-form cell average of n n against the sampled one: within a cell of angular size
      // sqrt(solid angle) the entries of n n vary by about that much.
      EXPECT_LT((cells.mean_dyad(k) - dyads[kk] / counts[kk]).norm(),
                5.0 * std::sqrt(cells.solid_angle() / counts[kk]))
          << size << " " << k;
      EXPECT_NEAR(cells.mean_dyad(k).trace(), 1.0, 1e-12);
    }
    Eigen::Matrix3d sum = Eigen::Matrix3d::Zero();
    for (int k = 0; k < size; ++k) sum += cells.mean_dyad(k);
    EXPECT_LT((sum / size - Eigen::Matrix3d::Identity() / 3.0).norm(), 1e-12) << size;
    EXPECT_NEAR(cells.solid_angle() * size, 4.0 * sffcal::kPi, 1e-12);
  }
}

// Flipping the sign of any frame axis (as an eigen-solver may) only renumbers the cells: the
// multiset of cell counts of any set of directions is unchanged.
TEST(DirectionCells, AFlippedFrameAxisGivesTheSamePartition) {
  std::mt19937_64 rng(32);
  std::vector<Eigen::Vector3d> normals;
  for (int k = 0; k < 20'000; ++k) normals.push_back(random_unit(rng));
  const Eigen::Matrix3d frame =
      Eigen::AngleAxisd(0.4, Eigen::Vector3d(0.2, -1.0, 0.5).normalized()).toRotationMatrix();
  auto sorted_counts = [&](const DirectionCells& cells) {
    std::vector<int> counts(static_cast<std::size_t>(cells.size()), 0);
    for (const Eigen::Vector3d& n : normals) ++counts[static_cast<std::size_t>(cells.cell_of(n))];
    std::sort(counts.begin(), counts.end());
    return counts;
  };
  const std::vector<int> reference = sorted_counts(DirectionCells(41, frame));
  for (int axis = 0; axis < 3; ++axis) {
    Eigen::Matrix3d flipped = frame;
    flipped.col(axis) *= -1.0;
    EXPECT_EQ(sorted_counts(DirectionCells(41, flipped)), reference) << "axis " << axis;
  }
}

TEST(DirectionCells, RefuseAnEvenCountAndABadFrame) {
  EXPECT_THROW(DirectionCells(40), StatisticsError);
  EXPECT_THROW(DirectionCells(1), StatisticsError);
  EXPECT_THROW(DirectionCells(41, 2.0 * Eigen::Matrix3d::Identity()), StatisticsError);
  // The cap of cells about a tensor's principal axes is about its major axis.
  const DirectionCells cells = DirectionCells::principal(41, Eigen::Vector3d(1.0, 5.0, 2.0).asDiagonal());
  EXPECT_NEAR(std::abs(cells.frame().col(2).y()), 1.0, 1e-12);
  EXPECT_EQ(cells.cell_of(Eigen::Vector3d::UnitY()), 0);
}

}  // namespace
}  // namespace sff
