#include "dem_import/import_run.h"

#include <cmath>
#include <cstdint>
#include <map>
#include <sstream>
#include <stdexcept>

#include "dem_import/dump_file.h"
#include "dem_import/series_table.h"
#include "frame_snapshot.h"
#include "runfile/run_file.h"
#include "runfile/snapshot_geometry.h"

namespace dem_import {
namespace {

// The source's roles in the series table (docs/import.md): all of a periodic cell's; a box
// between walls adds the lower walls' positions, and its shear stresses may be absent (frictionless
// walls give only the normal ones: then 0).
const std::vector<std::string> kSeriesRoles = {"step", "time", "sxx", "syy", "szz", "lx", "ly", "lz"};
const std::vector<std::string> kShearRoles = {"syz", "sxz", "sxy"};
const std::vector<std::string> kWallRoles = {"xlo", "ylo", "zlo"};

}  // namespace

const std::vector<std::string>& imported_series_names() {
  static const std::vector<std::string> names = {
      "step", "time", "axial_strain", "lateral_strain_x", "lateral_strain_y", "volumetric_strain",
      "void_ratio", "sigma_1", "sigma_3", "p", "q", "eta", "stress_xx", "stress_yy", "stress_zz",
      "stress_yz", "stress_xz", "stress_xy"};
  return names;
}

ImportReport import_run(const ImportDescription& d, const std::string& output,
                        const std::string& program_version,
                        const std::function<void(const std::string&)>& progress) {
  ImportReport report;
  // The dumps' first frame first: a box of the wrong kind is named before the series' columns.
  DumpReader atoms(d.atoms_path, "atoms dump"), contacts(d.contacts_path, "contacts dump");
  DumpFrame atoms_frame, contacts_frame;
  if (!atoms.next(atoms_frame)) throw std::runtime_error(atoms.name() + " holds no frame");
  internal::check_box_kind(atoms_frame, d,
                           atoms.name() + " at timestep " + std::to_string(atoms_frame.timestep));
  const SeriesTable table = read_series_table(d.series_path);
  const std::string table_name = "the series table " + d.series_path;
  std::map<std::string, const std::vector<double>*> role;
  const auto take = [&](const std::string& r) {
    role[r] = &table.column(ImportDescription::column(d.series_columns, r), table_name);
  };
  for (const std::string& r : kSeriesRoles) take(r);
  const std::vector<double> zeros(table.rows(), 0.0);
  bool shear_given = true;
  for (const std::string& r : kShearRoles)
    if (!d.walls || table.has(ImportDescription::column(d.series_columns, r))) take(r);
    else role[r] = &zeros, shear_given = false;
  if (d.walls)
    for (const std::string& r : kWallRoles) take(r);
  std::vector<std::string> extra;                   // the source's other columns, kept
  std::vector<const std::vector<double>*> extra_values;
  for (std::size_t k = 0; k < table.columns.size(); ++k) {
    bool used = false;
    for (const auto& [r, values] : role) used |= values == &table.values[k];
    if (!used) extra.push_back(table.columns[k]), extra_values.push_back(&table.values[k]);
  }
  // The roles' values: finite, and the steps whole and increasing (the strains are taken against
  // the first row). The source's other columns are kept as they are (YADE's fabric is NaN
  // where a cell has no contact).
  const std::size_t rows = table.rows();
  for (const auto& [r, values] : role)
    for (std::size_t k = 0; k < rows; ++k)
      if (!std::isfinite((*values)[k]))
        throw std::runtime_error(table_name + ": row " + std::to_string(k + 1) + ", column '" +
                                 ImportDescription::column(d.series_columns, r) +
                                 "': a value that is not finite");
  std::map<std::int64_t, std::size_t> row_of_step;
  for (std::size_t k = 0; k < rows; ++k) {
    const double step = (*role["step"])[k];
    if (step != std::floor(step) || !(std::abs(step) < 9e15))
      throw std::runtime_error(table_name + ": row " + std::to_string(k + 1) +
                               " has a step that is not an integer");
    if (k > 0 && !(step > (*role["step"])[k - 1]))
      throw std::runtime_error(table_name + ": row " + std::to_string(k + 1) + " has step " +
                               std::to_string(static_cast<std::int64_t>(step)) +
                               ", not after the row before it; steps must increase");
    row_of_step.emplace(static_cast<std::int64_t>(step), k);
  }

  runfile::RunMetadata meta;
  meta.kind = d.kind;
  meta.config_text = d.text;
  meta.program_version = program_version;
  meta.physics = d.physics;
  meta.loading = d.loading;
  std::vector<std::string> names = imported_series_names();
  for (const std::string& c : extra) names.push_back("source_" + c);
  runfile::RunFile file = runfile::RunFile::create(output, meta, names);
  std::ostringstream note;
  note << d.program << " " << d.version << ", imported from " << d.atoms_path << ", "
       << d.contacts_path << " and " << d.series_path << " (described by " << d.path
       << "). Bodies are numbered in the order of their source ids; the source's velocities are "
          "not imported (zero in the snapshots); the sliding flag is |f_t| >= mu f_n with the "
          "stated friction. Stress: " << d.stress_definition << ".";
  if (d.walls)
    note << " A box between six walls: their positions from the series, their contacts from the "
            "walls' forces on the spheres in the atoms dump; the walls' velocities and control are "
            "not imported (axis_control says how they moved)."
         << (shear_given ? "" : " The series has no shear stresses: stress_yz, stress_xz and "
                                "stress_xy are 0.");
  file.write_note("import", note.str());

  double solid = 0.0;
  std::size_t bodies = 0;
  std::int64_t last_step = 0;
  const double height0 = (*role["lz"])[0];
  for (bool more = true; more; more = atoms.next(atoms_frame)) {
    const std::string at = " (timestep " + std::to_string(atoms_frame.timestep) + ")";
    if (!contacts.next(contacts_frame))
      throw std::runtime_error(contacts.name() + " ends after " + std::to_string(report.snapshots) +
                               " frames, but the " + atoms.name() + " has more" + at);
    if (contacts_frame.timestep != atoms_frame.timestep)
      throw std::runtime_error("frame " + std::to_string(report.snapshots + 1) + " of the " +
                               atoms.name() + " is at timestep " +
                               std::to_string(atoms_frame.timestep) + ", of the " + contacts.name() +
                               " at " + std::to_string(contacts_frame.timestep) +
                               "; the two dumps must be written at the same timesteps");
    if (report.snapshots > 0 && atoms_frame.timestep <= last_step)
      throw std::runtime_error(atoms.name() + at + ": the frames' timesteps must increase (the "
                               "one before is at " + std::to_string(last_step) + ")");
    last_step = atoms_frame.timestep;
    const auto row = row_of_step.find(atoms_frame.timestep);
    if (row == row_of_step.end())
      throw std::runtime_error(table_name + " has no row at step " +
                               std::to_string(atoms_frame.timestep) + ", where the dumps have a frame");
    internal::FrameBox box;
    for (int a = 0; a < 3; ++a) {
      box.length[a] = (*role[std::string("l") + "xyz"[a]])[row->second];
      if (d.walls) box.lower[a] = (*role[kWallRoles[a]])[row->second];
    }
    runfile::Snapshot s = internal::snapshot_from_frames(atoms_frame, contacts_frame, box, d,
                                                         atoms.name(), contacts.name());
    if (report.snapshots == 0) {
      solid = runfile::solid_volume(s);
      bodies = s.particles.size();
    } else if (s.particles.size() != bodies) {
      throw std::runtime_error(atoms.name() + at + " holds " + std::to_string(s.particles.size()) +
                               " bodies, its first frame " + std::to_string(bodies));
    }
    s.step = atoms_frame.timestep;
    s.time = (*role["time"])[row->second];
    s.axial_strain = (height0 - (*role["lz"])[row->second]) / height0;
    file.write_snapshot(s);
    ++report.snapshots;
    report.contacts = s.contacts.size();
    report.spheres = s.spheres.size();
    progress("snapshot " + std::to_string(report.snapshots) + " at step " +
             std::to_string(s.step) + ": " + std::to_string(s.particles.size()) + " bodies, " +
             std::to_string(s.contacts.size()) + " contacts");
  }
  if (contacts.next(contacts_frame))
    throw std::runtime_error(contacts.name() + " has more frames than the " + atoms.name() + " (" +
                             std::to_string(report.snapshots) + ")");

  // The series: strains against the first row, the stress compression positive.
  const double sign = d.stress_tension_positive ? -1.0 : 1.0;
  const auto& lx = *role["lx"];
  const auto& ly = *role["ly"];
  const auto& lz = *role["lz"];
  const double volume0 = lx[0] * ly[0] * lz[0];
  for (std::size_t k = 0; k < rows; ++k) {
    const auto value = [&](const char* r) { return (*role[r])[k]; };
    const double volume = lx[k] * ly[k] * lz[k];
    if (!(volume > 0.0))
      throw std::runtime_error(table_name + ": row " + std::to_string(k + 1) +
                               " has a cell length that is not positive");
    const double sxx = sign * value("sxx"), syy = sign * value("syy"), szz = sign * value("szz");
    const double sigma_3 = 0.5 * (sxx + syy), p = (sxx + syy + szz) / 3.0, q = szz - sigma_3;
    std::vector<double> out = {value("step"), value("time"), (lz[0] - lz[k]) / lz[0],
                               (lx[0] - lx[k]) / lx[0], (ly[0] - ly[k]) / ly[0],
                               (volume0 - volume) / volume0, volume / solid - 1.0, szz, sigma_3, p,
                               q, p != 0.0 ? q / p : 0.0, sxx, syy, szz, sign * value("syz"),
                               sign * value("sxz"), sign * value("sxy")};
    for (const std::vector<double>* values : extra_values) out.push_back((*values)[k]);
    file.append_series(out);
  }
  file.flush();
  report.series_rows = rows;
  report.bodies = bodies;
  report.solid_volume = solid;
  report.initial_void_ratio = volume0 / solid - 1.0;
  return report;
}

}  // namespace dem_import
