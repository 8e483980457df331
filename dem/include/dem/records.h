// The records the engine produces: the grain-scale ones are the run file's (runfile/records.h,
// where the sign convention is stated); the scalar history of one output step is the engine's own.
#pragma once

#include <array>
#include <cstdint>

#include "runfile/records.h"

namespace dem {

using runfile::ContactRecord;
using runfile::ParticleRecord;
using runfile::Vec3Record;
using runfile::WallRecord;

/// Scalar history of one output step.
struct MacroRecord {
  std::int64_t step = 0;
  double time = 0.0;                       ///< [s]
  std::array<double, 6> wall_position{};   ///< -x, +x, -y, +y, -z, +z [m]
  std::array<double, 6> wall_force{};      ///< normal force the bodies exert on each wall [N]
  std::array<double, 6> contact_stress{};  ///< Love–Weber, xx yy zz yz xz xy [Pa], compression +
  double volume = 0.0;                     ///< box volume [m^3]
  double coordination_number = 0.0;       ///< 2 N_c / N_p over body–body contacts
  double kinetic_energy = 0.0;             ///< translational + rotational [J]
  double unbalanced_force_ratio = 0.0;     ///< mean |net force| / mean |contact force|
  std::int64_t num_contacts = 0;           ///< body–body sphere contacts
};

}  // namespace dem
