// The ParaView collection (.pvd) of a series of VTK files: one writer for the DEM snapshots
// (dem/vtk_writer) and the FE runs (fe_model/triaxial).
#pragma once

#include <iomanip>
#include <stdexcept>
#include <string>
#include <vector>

#include "sffcal/output_file.h"

namespace sffcal {

/// Writes `path` (through an OutputFile) listing `files` (names relative to the .pvd's folder) at
/// `times`; the comment `time_meaning` says what the timestep values are. Throws
/// std::runtime_error naming the path when it cannot be written, std::invalid_argument for
/// unequal lists.
inline void write_pvd(const std::string& path, const std::vector<std::string>& files,
                      const std::vector<double>& times, const std::string& time_meaning) {
  if (files.size() != times.size())
    throw std::invalid_argument("write_pvd: as many times as files are needed");
  OutputFile file(path);
  std::ostream& out = file.stream();
  out << "<?xml version=\"1.0\"?>\n<!-- timestep = " << time_meaning << " -->\n"
      << "<VTKFile type=\"Collection\" version=\"0.1\">\n<Collection>\n"
      << std::setprecision(10);
  for (std::size_t i = 0; i < files.size(); ++i)
    out << "  <DataSet timestep=\"" << times[i] << "\" file=\"" << files[i] << "\"/>\n";
  out << "</Collection>\n</VTKFile>\n";
  file.commit();
}

}  // namespace sffcal
