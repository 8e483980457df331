// The text dumps of LAMMPS (`dump custom`, `dump local`; LIGGGHTS writes the same), which the
// project's YADE exporter also writes: frames of named columns, read one frame at a time so that a
// large run never sits in memory whole (docs/import.md). Every error names the file and the line.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <fstream>
#include <string>
#include <vector>

namespace dem_import {

/// One frame: its timestep, box and rows of numbers under named columns.
struct DumpFrame {
  static constexpr std::size_t npos = static_cast<std::size_t>(-1);

  std::int64_t timestep = 0;
  std::array<std::string, 3> boundary;      ///< LAMMPS's flags per axis, e.g. "pp" (periodic)
  std::array<double, 3> lower{}, upper{};   ///< the box's bounds [m]
  bool triclinic = false;                   ///< a tilted box (xy xz yz given)
  std::vector<std::string> columns;
  std::vector<double> values;               ///< rows() x columns.size(), row by row
  std::size_t first_line = 0;               ///< the line of its TIMESTEP item (from 1)

  std::size_t rows() const { return columns.empty() ? 0 : values.size() / columns.size(); }
  /// The column's index, or npos.
  std::size_t find(const std::string& name) const;
  double at(std::size_t row, std::size_t column) const { return values[row * columns.size() + column]; }
};

class DumpReader {
 public:
  /// `what` names the file in messages (e.g. "atoms dump"). Throws std::runtime_error where the
  /// file cannot be opened.
  DumpReader(std::string path, std::string what);
  /// Reads the next frame into `frame`; false at the end of the file. Throws std::runtime_error
  /// naming the file and line where a frame is truncated, an item is not the one expected, a row
  /// has too few or too many values or a value is not a number.
  bool next(DumpFrame& frame);
  /// "<what> <path>", for messages.
  std::string name() const;

 private:
  bool read_line();
  [[noreturn]] void fail(const std::string& what) const;

  std::string path_, what_;
  std::ifstream in_;
  std::string line_;
  std::size_t line_number_ = 0;
};

}  // namespace dem_import
