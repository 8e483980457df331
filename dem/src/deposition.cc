#include "deposition.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <random>
#include <sstream>
#include <stdexcept>
#include <utility>
#include <vector>

#include "dem/packing.h"
#include "dem/rigid_body.h"
#include "sffcal/constants.h"

namespace dem {
namespace {

using sffcal::kPi;

// Sizing of the bed. The cube keeps only the bodies wholly inside it, which leaves about half a
// mean body length empty along each face: a cube of N bodies at the bed's solid fraction (about
// 0.55, measured) needs one mean body length more on its side. The bed holds 20 % more bodies
// than that, for the rough free surface.
constexpr double kBedSolidFraction = 0.55;
constexpr double kOverfill = 1.2;
// Bodies nearer than this many body lengths (about two mean diameters each) to a wall or to the
// free surface are left out: walls order the first layers of grains.
constexpr double kMarginLengths = 1.0;
// Room between the bodies stacked in a column, as a fraction of the largest diameter.
constexpr double kStackGap = 0.05;

double mean_body_volume(const GrainSpec& g) {
  // A clump's volume scales with d^3; E[d^3] for d uniform in [a, b].
  const double a = g.min_diameter, b = g.max_diameter;
  const double mean_cube = b > a ? (std::pow(b, 4) - std::pow(a, 4)) / (4.0 * (b - a)) : a * a * a;
  return two_sphere_union_properties(0.5, g.centre_distance_ratio, 1.0).volume * mean_cube;
}

// Random insertion for the bed: columns on a square grid of `site` wide cells, each body drawn
// with a random diameter and orientation, shifted at random within its cell and stacked on the
// one below it with a small gap (its vertical extent is |e_z| s + d). Columns are disjoint, so no
// body overlaps another; stacking by extent rather than a cubic lattice makes the bed start about
// twice as dense, which halves the height the top bodies fall. Bottom at z = 0.
Particles stacked_columns(int num_bodies, const GrainSpec& grains, std::uint64_t seed, double site,
                          int sites_x, int sites_y) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::normal_distribution<double> gauss(0.0, 1.0);
  const double gap = kStackGap * grains.max_diameter;
  std::vector<double> column_top(static_cast<std::size_t>(sites_x * sites_y), 0.0);
  Particles particles;
  for (int n = 0; n < num_bodies; ++n) {
    const int column = n % (sites_x * sites_y), ix = column % sites_x, iy = column / sites_x;
    const double d = grains.min_diameter + (grains.max_diameter - grains.min_diameter) * unit(rng);
    Eigen::Quaterniond q(gauss(rng), gauss(rng), gauss(rng), gauss(rng));  // uniform rotation
    q.normalize();
    const double s = grains.centre_distance_ratio * d;
    const Eigen::Vector3d half_extent = 0.5 * (s * body_axis(q).cwiseAbs().array() + d);
    Eigen::Vector3d centre;
    for (int k = 0; k < 2; ++k) {
      const double play = 0.5 * site - half_extent[k];  // >= 0: the site holds the longest body
      centre[k] = site * ((k == 0 ? ix : iy) + 0.5) + play * (2.0 * unit(rng) - 1.0);
    }
    double& top = column_top[static_cast<std::size_t>(column)];
    centre.z() = top + gap + half_extent.z();
    top = centre.z() + half_extent.z();
    particles.add_body({0.5 * d, s}, grains.density, centre, q);
  }
  return particles;
}

// Lets the bodies fall and settle until the unbalanced-force ratio stays below 1e-3.
std::int64_t settle(Simulation& sim, std::int64_t max_steps, const ProgressLog& log) {
  const std::int64_t start = sim.step_count();
  int quiet = 0;
  std::int64_t next_report = 50000;
  while (sim.step_count() - start < max_steps) {
    sim.run(2000);
    const double ratio = sim.unbalanced_force_ratio();
    quiet = (sim.num_touching_pairs() > 0 && ratio < 1e-3) ? quiet + 1 : 0;
    if (quiet >= 3) return sim.step_count() - start;
    if (log && sim.step_count() - start >= next_report) {
      std::ostringstream msg;
      msg << "  deposition: " << sim.step_count() - start << " steps, unbalanced-force ratio " << ratio;
      log(msg.str());
      next_report += 50000;
    }
  }
  if (log) log("deposition: bodies still moving after preparation.max_steps; compacting anyway");
  return sim.step_count() - start;
}

// Height of the lowest point of the free surface: the lowest of the highest sphere tops over
// columns about two body lengths wide.
double free_surface_low_point(const Particles& p, double column_width) {
  std::map<std::pair<long, long>, double> top;
  for (int s = 0; s < p.num_spheres(); ++s) {
    const Eigen::Vector3d& x = p.sphere_position[s];
    const std::pair<long, long> cell(std::lround(std::floor(x.x() / column_width)),
                                     std::lround(std::floor(x.y() / column_width)));
    auto [it, inserted] = top.emplace(cell, x.z() + p.sphere_radius[s]);
    if (!inserted) it->second = std::max(it->second, x.z() + p.sphere_radius[s]);
  }
  double lowest = HUGE_VAL;
  for (const auto& cell : top) lowest = std::min(lowest, cell.second);
  return lowest;
}

// For each body of `bed`, the half side of the smallest cube [-h, h]^3 that holds it wholly after
// the map x -> tilt (x - centre): the body is inside a cube of half side h iff its reach <= h.
std::vector<double> cube_reach(const Particles& bed, const Eigen::Vector3d& centre,
                               const Eigen::Quaterniond& tilt) {
  std::vector<double> reach(static_cast<std::size_t>(bed.num_bodies()), 0.0);
  for (int b = 0; b < bed.num_bodies(); ++b) {
    const int s0 = bed.first_sphere[b];
    for (int k = s0; k < s0 + bed.num_body_spheres[b]; ++k)
      reach[b] = std::max(reach[b], (tilt * (bed.sphere_position[k] - centre)).cwiseAbs().maxCoeff() +
                                        bed.sphere_radius[k]);
  }
  return reach;
}

}  // namespace

Deposit deposit_at_loading_angle(const RunConfig& config, const SimulationOptions& options,
                                 const ContactParameters& law, const ProgressLog& log) {
  const PreparationConfig& prep = config.preparation;
  const GrainSpec& grains = config.grains;
  const double alpha = prep.loading_angle_deg * kPi / 180.0;
  // A cube of side L tilted about X spans L (|cos a| + |sin a|) along Y and Z.
  const double spread = std::abs(std::cos(alpha)) + std::abs(std::sin(alpha));
  const double margin = kMarginLengths * grains.max_diameter * (1.0 + grains.centre_distance_ratio);
  const double body_volume = mean_body_volume(grains);
  const double mean_length = 0.5 * (grains.min_diameter + grains.max_diameter) * (1.0 + grains.centre_distance_ratio);
  const double side = std::cbrt(config.num_bodies * body_volume / kBedSolidFraction) + mean_length;

  // The bed: L + 2 margins wide along X, L spread + 2 margins along Y, deep enough for the tilted
  // cube plus a margin at the bottom and two under the rough free surface.
  const double spacing = (1.0 + kStackGap) * grains.max_diameter * (1.0 + grains.centre_distance_ratio);
  const int sites_x = static_cast<int>(std::ceil((side + 2.0 * margin) / spacing));
  const int sites_y = static_cast<int>(std::ceil((side * spread + 2.0 * margin) / spacing));
  const double depth = side * spread + 3.0 * margin;
  const int bed_bodies = static_cast<int>(std::ceil(
      kOverfill * kBedSolidFraction * sites_x * sites_y * spacing * spacing * depth / body_volume));

  Deposit d;
  d.deposited = bed_bodies;
  Particles columns = stacked_columns(bed_bodies, grains, config.seed, spacing, sites_x, sites_y);
  Eigen::Vector3d lo, hi;
  bounding_box(columns, lo, hi);
  lo.head<2>().setZero();  // the columns' sides: no body sticks out of them
  hi.head<2>() = Eigen::Vector2d(sites_x * spacing, sites_y * spacing);
  SimulationOptions falling = options;
  falling.gravity = {0.0, 0.0, -prep.deposition_gravity};
  falling.local_damping = prep.deposition_damping;
  Simulation sim(std::move(columns), box_walls(lo, hi), law, falling);
  if (log) {
    std::ostringstream msg;
    msg << "depositing " << bed_bodies << " bodies (" << sites_x << " x " << sites_y
        << " columns) under " << prep.deposition_gravity << " m/s^2";
    log(msg.str());
  }
  d.steps = settle(sim, prep.compaction.max_steps, log);

  // The interior: a margin from every wall and from the lowest point of the free surface.
  const Particles& bed = sim.particles();
  Eigen::Vector3d in_lo = lo.array() + margin, in_hi = hi.array() - margin;
  in_hi.z() = std::min(in_hi.z(), free_surface_low_point(bed, 2.0 * margin) - margin);
  const Eigen::Vector3d centre = 0.5 * (in_lo + in_hi), half = 0.5 * (in_hi - in_lo);
  const double h_max = std::min(half.x(), std::min(half.y(), half.z()) / spread);
  if (!(h_max > 0.0))
    throw std::runtime_error("deposition: the settled bed is too shallow for the cut (raise bodies)");
  const Eigen::Quaterniond tilt(Eigen::AngleAxisd(alpha, Eigen::Vector3d::UnitX()));

  // The smallest cube holding the bodies asked for: bisection on its half side.
  const std::vector<double> reach = cube_reach(bed, centre, tilt);
  auto bodies_within = [&](double h) {
    return static_cast<int>(std::count_if(reach.begin(), reach.end(), [h](double r) { return r <= h; }));
  };
  double h = h_max;
  if (const int count = bodies_within(h_max); count < config.num_bodies) {
    if (log) {
      std::ostringstream msg;
      msg << "deposition: only " << count << " of " << config.num_bodies
          << " bodies fit in the interior of the bed (" << 2.0 * half.transpose() * 1e3
          << " mm; cube side " << 2.0 * h_max * 1e3 << " mm); keeping them";
      log(msg.str());
    }
  } else {
    double h_lo = 0.0;
    for (int i = 0; i < 40; ++i) {
      const double mid = 0.5 * (h_lo + h);
      (bodies_within(mid) >= config.num_bodies ? h : h_lo) = mid;
    }
  }
  for (int b = 0; b < bed.num_bodies(); ++b) {
    if (reach[b] > h) continue;
    const int s0 = bed.first_sphere[b];
    d.bodies.add_body({bed.sphere_radius[s0], 2.0 * std::abs(bed.sphere_offset[s0])},
                      bed.mass[b] / bed.volume[b], tilt * (bed.position[b] - centre),
                      tilt * bed.orientation[b]);
  }
  d.lo = Eigen::Vector3d::Constant(-h);
  d.hi = Eigen::Vector3d::Constant(h);
  return d;
}

}  // namespace dem
