// Small specimens shared by the triaxial and run-file tests.
#pragma once

#include "dem/compaction.h"
#include "dem/packing.h"
#include "dem/simulation.h"

namespace dem::testing {

/// Loose, randomly inserted bodies in a box, damped for preparation.
inline Simulation loose_specimen(int bodies, double friction, std::uint64_t seed,
                                 double centre_distance_ratio = 0.5) {
  GrainSpec grains;
  grains.centre_distance_ratio = centre_distance_ratio;
  Particles p = random_lattice_packing(bodies, grains, seed);
  Eigen::Vector3d lo, hi;
  bounding_box(p, lo, hi);
  ContactParameters law;
  law.friction = friction;
  SimulationOptions options;
  options.local_damping = 0.7;
  return Simulation(std::move(p), box_walls(lo, hi), law, options);
}

/// A compacted specimen of `bodies` clumps at 100 kPa; the compaction friction sets its density.
inline Simulation compacted_specimen(int bodies, double compaction_friction, std::uint64_t seed) {
  Simulation sim = loose_specimen(bodies, compaction_friction, seed);
  const CompactionResult result = compact_isotropically(sim, CompactionOptions{});
  if (!result.converged) throw std::runtime_error("test specimen: " + result.summary());
  return sim;
}

/// The same specimen ready for shearing: friction tan 30, no damping.
inline Simulation shearing_copy(const Simulation& specimen) {
  ContactParameters law = specimen.contact_parameters();
  law.friction = 0.5773502691896257;
  SimulationOptions options = specimen.options();
  options.local_damping = 0.0;
  return Simulation(specimen.state(), law, options);
}

}  // namespace dem::testing
