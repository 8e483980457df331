#include "dem/specimen.h"

#include <Eigen/Eigenvalues>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "deposition.h"
#include "dem/packing.h"
#include "dem/rigid_body.h"
#include "sffcal/constants.h"
#include "sffcal/read_text_file.h"

namespace dem {
namespace {

using sffcal::kPi;

double void_ratio(const Simulation& sim) {
  double solid = 0.0;
  for (double v : sim.particles().volume) solid += v;
  return sim.box_volume() / solid - 1.0;
}

Eigen::Vector3d major_direction(const Eigen::Matrix3d& tensor, bool largest) {
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver(tensor);  // ascending eigenvalues
  const Eigen::Vector3d v = solver.eigenvectors().col(largest ? 2 : 0);
  Eigen::Index k = 0;
  v.cwiseAbs().maxCoeff(&k);
  return v[k] < 0.0 ? (-v).eval() : v;  // a sign convention: the largest component positive
}

// A cell as the error message shows it: quoted, control characters and bytes beyond ASCII as \xNN
// (a raw carriage return would overwrite the message on the terminal).
std::string quoted_cell(const std::string& cell) {
  std::string out = "'";
  for (const unsigned char c : cell) {
    if (c >= 0x20 && c < 0x7f) {
      out += static_cast<char>(c);
    } else {
      char hex[8];
      std::snprintf(hex, sizeof(hex), "\\x%02x", c);
      out += hex;
    }
  }
  return out + "'";
}

}  // namespace

std::string PreparationReport::describe() const {
  std::ostringstream s;
  s << method << ": compaction friction " << compaction_friction;
  if (friction_trials > 0) s << " (found in " << friction_trials << " trials)";
  s << ", void ratio " << void_ratio << ", coordination number " << coordination_number << "; "
    << compaction.summary();
  if (deposition_steps > 0) {
    s << "; deposited in " << deposition_steps << " steps, bedding normal (" << bedding_normal.transpose()
      << "), contact-fabric major direction (" << fabric_major.transpose()
      << "), particle-axis minor direction (" << axis_minor.transpose() << ")";
  }
  return s.str();
}

Eigen::Vector3d bedding_normal(double loading_angle_deg) {
  const double a = loading_angle_deg * kPi / 180.0;
  return {0.0, -std::sin(a), std::cos(a)};
}

Eigen::Matrix3d contact_normal_fabric(const Simulation& sim) {
  Eigen::Matrix3d phi = Eigen::Matrix3d::Zero();
  int n = 0;
  for (const ContactRecord& c : sim.contact_records(false)) {
    const Eigen::Vector3d normal(c.normal[0], c.normal[1], c.normal[2]);
    phi += normal * normal.transpose();
    ++n;
  }
  return n > 0 ? (phi / n).eval() : phi;
}

Eigen::Matrix3d particle_axis_fabric(const Particles& particles) {
  Eigen::Matrix3d phi = Eigen::Matrix3d::Zero();
  for (const auto& q : particles.orientation) {
    const Eigen::Vector3d e = body_axis(q);
    phi += e * e.transpose();
  }
  return phi / particles.num_bodies();
}

Particles load_csv_packing(const std::string& path, const GrainSpec& grains, Eigen::Vector3d* lo,
                           Eigen::Vector3d* hi, double max_overlap_ratio) {
  // A packing row is under 100 bytes: 1 GB holds ten million bodies, and refuses a device.
  return parse_csv_packing(sffcal::read_text_file(path, std::uintmax_t{1} << 30, "packing file"),
                           path, grains, lo, hi, max_overlap_ratio);
}

Particles parse_csv_packing(const std::string& text, const std::string& path,
                            const GrainSpec& grains, Eigen::Vector3d* lo, Eigen::Vector3d* hi,
                            double max_overlap_ratio) {
  std::istringstream in(text);
  Particles particles;
  bool have_box = false, have_header = false;
  std::string line;
  int line_number = 0;
  auto fail = [&](const std::string& what) {
    throw std::invalid_argument(path + ":" + std::to_string(line_number) + ": " + what);
  };
  while (std::getline(in, line)) {
    ++line_number;
    if (line.find_first_not_of(" \t\r") == std::string::npos) continue;
    if (line[0] == '#') {
      const std::size_t at = line.find("box:");
      if (at != std::string::npos) {
        std::istringstream box(line.substr(at + 4));
        double v[6];
        for (double& x : v)
          if (!(box >> x)) fail("the box line needs six numbers: xlo ylo zlo xhi yhi zhi [m]");
        *lo = {v[0], v[1], v[2]};
        *hi = {v[3], v[4], v[5]};
        if (!((*hi - *lo).minCoeff() > 0.0)) fail("the box must have hi > lo on every axis");
        if (!(*hi - *lo).allFinite()) fail("the box must have a finite size (hi - lo)");
        have_box = true;
      }
      continue;
    }
    if (!have_header) {
      if (line.rfind("x,y,z,axis_x,axis_y,axis_z,diameter", 0) != 0)
        fail("expected the header x,y,z,axis_x,axis_y,axis_z,diameter[,vx,vy,vz]");
      have_header = true;
      continue;
    }
    const std::size_t end = line.find_last_not_of(" \t\r");
    if (line[end] == ',') fail("the row ends with an empty cell");
    std::vector<double> v;
    std::stringstream row(line);
    std::string cell;
    while (std::getline(row, cell, ',')) {
      // The whole cell must be one finite number ("5e-05abc" and "6e-05 7e-05" are not).
      const std::size_t first = cell.find_first_not_of(" \t\r");
      const std::size_t last = cell.find_last_not_of(" \t\r");
      const std::string value = first == std::string::npos ? "" : cell.substr(first, last - first + 1);
      std::size_t used = 0;
      double x = 0.0;
      try {
        x = std::stod(value, &used);
      } catch (const std::exception&) {
        used = 0;
      }
      if (value.empty() || used != value.size()) fail(quoted_cell(cell) + " is not a number");
      if (!std::isfinite(x)) fail(quoted_cell(cell) + " is not finite");
      v.push_back(x);
    }
    if (v.size() != 7 && v.size() != 10) fail("a row needs 7 or 10 values, found " + std::to_string(v.size()));
    const Eigen::Vector3d centre(v[0], v[1], v[2]), axis(v[3], v[4], v[5]);
    if (!(v[6] > 0.0)) fail("the diameter must be positive [m]");
    if (!(std::abs(axis.norm() - 1.0) < 1e-3)) fail("the axis must be a unit vector");
    const Eigen::Quaterniond q = Eigen::Quaterniond::FromTwoVectors(Eigen::Vector3d::UnitX(), axis);
    const int b = particles.add_body({0.5 * v[6], grains.centre_distance_ratio * v[6]},
                                     grains.density, centre, q);
    if (v.size() == 10) particles.velocity[b] = {v[7], v[8], v[9]};
    // A diameter far from any grain's (1e150 m, 1e-300 m) overflows or underflows the mass.
    auto positive = [](double x) { return std::isfinite(x) && x > 0.0; };
    if (!positive(particles.mass[b]) || !positive(particles.volume[b]) ||
        !positive(particles.inertia_axial[b]) || !positive(particles.inertia_transverse[b])) {
      std::ostringstream msg;
      msg << "a body of diameter " << v[6] << " m has a mass or inertia that is not a positive "
          << "finite number";
      fail(msg.str());
    }
  }
  if (!have_box) throw std::invalid_argument(path + ": no '# box: xlo ylo zlo xhi yhi zhi' line");
  if (particles.num_bodies() == 0) throw std::invalid_argument(path + ": no bodies");
  // A packing compacted by another code presses into its walls as wall contacts under load do;
  // compaction restores the balance. Deeper than the engine's overlap limit is an error.
  static const char* kWallName[3][2] = {{"x lower", "x upper"}, {"y lower", "y upper"},
                                         {"z lower", "z upper"}};
  for (int s = 0; s < particles.num_spheres(); ++s) {
    const Eigen::Vector3d& x = particles.sphere_position[s];
    const double r = particles.sphere_radius[s];
    for (int axis = 0; axis < 3; ++axis)
      for (int upper = 0; upper < 2; ++upper) {
        // The ratio as Simulation measures it, so the two checks agree at the limit.
        const double ratio = 1.0 - (upper ? (*hi)[axis] - x[axis] : x[axis] - (*lo)[axis]) / r;
        if (ratio > max_overlap_ratio) {
          std::ostringstream msg;
          msg << path << ": body " << particles.sphere_body[s] << " (data row "
              << particles.sphere_body[s] + 1 << ") overlaps the " << kWallName[axis][upper]
              << " wall of the box by " << ratio << " of its sphere radius (limit "
              << "max_overlap_ratio " << max_overlap_ratio << ")";
          throw std::invalid_argument(msg.str());
        }
      }
  }
  return particles;
}

SimulationOptions preparation_engine(const RunConfig& config) {
  SimulationOptions options = config.engine;
  options.local_damping = config.preparation.local_damping;
  options.servo.max_speed = config.preparation.servo_max_speed;
  return options;
}

SimulationState reconsolidate(SimulationState specimen, const RunConfig& config, double pressure) {
  Simulation sim(std::move(specimen), config.contact, preparation_engine(config));
  CompactionOptions compaction = config.preparation.compaction;
  compaction.target_stress = pressure;
  const CompactionResult result = compact_isotropically(sim, compaction);
  if (!result.converged) throw std::runtime_error("re-consolidation: " + result.summary());
  return sim.state();
}

Simulation prepare_specimen(const RunConfig& config, PreparationReport* report,
                            const ProgressLog& log, const CompactionProgress& compaction_progress) {
  const PreparationConfig& prep = config.preparation;
  PreparationReport local;
  PreparationReport& r = report ? *report : local;

  Eigen::Vector3d lo, hi;
  Particles loose;
  const SimulationOptions options = preparation_engine(config);
  ContactParameters law = config.contact;
  law.friction = prep.compaction_friction;

  if (prep.method == PreparationMethod::kCsv) {
    loose = load_csv_packing(prep.csv_path, config.grains, &lo, &hi, options.max_overlap_ratio);
    r.method = "csv packing " + prep.csv_path;
  } else if (prep.method == PreparationMethod::kCompaction) {
    loose = random_lattice_packing(config.num_bodies, config.grains, config.seed);
    bounding_box(loose, lo, hi);
    r.method = "compaction";
  } else {
    Deposit bed = deposit_at_loading_angle(config, options, law, log);
    r.deposition_steps = bed.steps;
    r.bedding_normal = bedding_normal(prep.loading_angle_deg);
    loose = std::move(bed.bodies);
    lo = bed.lo;
    hi = bed.hi;
    r.method = "deposition at " + std::to_string(prep.loading_angle_deg) + " deg (" +
               std::to_string(loose.num_bodies()) + " bodies cut from a bed of " +
               std::to_string(bed.deposited) + ") + compaction";
    if (loose.num_bodies() < 2) throw std::runtime_error("deposition: too few bodies left after the cut");
  }

  // The state compaction starts from, at rest.
  const SimulationState start = Simulation(std::move(loose), box_walls(lo, hi), law, options).state();

  auto compact = [&](double friction) {
    ContactParameters trial_law = law;
    trial_law.friction = friction;
    Simulation sim(start, trial_law, options);
    CompactionResult result = compact_isotropically(sim, prep.compaction, compaction_progress);
    if (!result.converged)
      throw std::runtime_error("preparation: compaction to " + std::to_string(prep.pressure) +
                               " Pa did not settle (" + result.summary() +
                               "); raise preparation.max_steps or loosen stress_tolerance / "
                               "max_unbalanced_force");
    r.compaction = result;
    if (log) {
      std::ostringstream msg;
      msg << "compaction with friction " << friction << ": void ratio " << void_ratio(sim) << ", "
          << result.summary();
      log(msg.str());
    }
    return sim;
  };

  // The void ratio grows with the compaction friction: bracket [0, 1], then regula falsi
  // (Illinois variant) until it is within tolerance of the target.
  auto search = [&](double* friction) {
    const double target = prep.target_void_ratio, tol = prep.void_ratio_tolerance;
    double f_lo = 0.0, f_hi = 1.0;
    Simulation best = compact(f_lo);
    double e_lo = void_ratio(best) - target;
    *friction = f_lo;
    r.friction_trials = 1;
    if (e_lo > tol)
      throw std::runtime_error("preparation: target_void_ratio " + std::to_string(target) +
                               " is below the densest this packing reaches (" +
                               std::to_string(e_lo + target) + " with frictionless compaction)");
    if (std::abs(e_lo) <= tol) return best;
    best = compact(f_hi);
    double e_hi = void_ratio(best) - target;
    *friction = f_hi;
    r.friction_trials = 2;
    if (e_hi < -tol)
      throw std::runtime_error("preparation: target_void_ratio " + std::to_string(target) +
                               " is above the loosest this packing reaches (" +
                               std::to_string(e_hi + target) + " at compaction friction 1)");
    int side = 0;
    while (std::abs(void_ratio(best) - target) > tol && r.friction_trials < 12) {
      const double f = (f_lo * e_hi - f_hi * e_lo) / (e_hi - e_lo);
      best = compact(f);
      *friction = f;
      ++r.friction_trials;
      const double e = void_ratio(best) - target;
      if (e > 0.0) {
        f_hi = f, e_hi = e;
        if (side == 1) e_lo *= 0.5;
        side = 1;
      } else {
        f_lo = f, e_lo = e;
        if (side == -1) e_hi *= 0.5;
        side = -1;
      }
    }
    if (std::abs(void_ratio(best) - target) > tol)
      throw std::runtime_error("preparation: no compaction friction in [0, 1] gave void ratio " +
                               std::to_string(target) + " within " + std::to_string(tol) +
                               " after 12 compactions (last " + std::to_string(void_ratio(best)) +
                               "); loosen void_ratio_tolerance");
    return best;
  };

  double friction = prep.compaction_friction;
  Simulation result = prep.target_void_ratio > 0.0 ? search(&friction) : compact(friction);
  r.compaction_friction = friction;
  if (log && friction > config.contact.friction)
    log("warning: the compaction friction " + std::to_string(friction) +
        " exceeds the shearing friction " + std::to_string(config.contact.friction) +
        ": contacts beyond the lower Coulomb limit slip when shearing starts, and a loose "
        "specimen partly collapses");
  r.void_ratio = void_ratio(result);
  r.coordination_number = result.macro_record().coordination_number;
  r.fabric_major = major_direction(contact_normal_fabric(result), true);
  r.axis_minor = major_direction(particle_axis_fabric(result.particles()), false);
  return result;
}

}  // namespace dem
