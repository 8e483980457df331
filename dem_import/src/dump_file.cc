#include "dem_import/dump_file.h"

#include <algorithm>
#include <charconv>
#include <stdexcept>
#include <string_view>
#include <utility>

#include "text_fields.h"

namespace dem_import {

std::size_t DumpFrame::find(const std::string& name) const {
  const auto it = std::find(columns.begin(), columns.end(), name);
  return it == columns.end() ? npos : static_cast<std::size_t>(it - columns.begin());
}

DumpReader::DumpReader(std::string path, std::string what)
    : path_(std::move(path)), what_(std::move(what)), in_(path_) {
  if (!in_) throw std::runtime_error("cannot read the " + name() + ": no such file or not readable");
}

std::string DumpReader::name() const { return what_ + " " + path_; }

void DumpReader::fail(const std::string& what) const {
  throw std::runtime_error(name() + ", line " + std::to_string(line_number_) + ": " + what);
}

bool DumpReader::read_line() {
  if (!std::getline(in_, line_)) return false;
  ++line_number_;
  if (!line_.empty() && line_.back() == '\r') line_.pop_back();
  return true;
}

bool DumpReader::next(DumpFrame& frame) {
  // Blank lines between frames are allowed; the end of the file here ends the dump.
  do {
    if (!read_line()) return false;
  } while (internal::fields(line_).empty());
  const auto expect_item = [&](std::string_view item) {
    if (line_.rfind("ITEM: " + std::string(item), 0) != 0)
      fail("expected 'ITEM: " + std::string(item) + "', found '" + line_.substr(0, 60) + "'");
  };
  const auto next_line = [&](const std::string& what) {
    if (!read_line()) fail("the file ends inside a frame, before " + what + " (truncated?)");
  };
  // LAMMPS may write the units and the time before the timestep (dump_modify units/time yes).
  while (line_.rfind("ITEM: UNITS", 0) == 0 || line_.rfind("ITEM: TIME", 0) == 0) {
    if (line_.rfind("ITEM: TIMESTEP", 0) == 0) break;
    next_line("the value of " + line_);
    next_line("ITEM: TIMESTEP");
  }
  expect_item("TIMESTEP");
  frame.first_line = line_number_;
  next_line("the timestep");
  frame.timestep = internal::parse_integer(line_, "the timestep", [&](const std::string& w) { fail(w); });
  next_line("ITEM: NUMBER OF ...");
  if (line_ != "ITEM: NUMBER OF ATOMS" && line_ != "ITEM: NUMBER OF ENTRIES")
    fail("expected 'ITEM: NUMBER OF ATOMS' or 'ITEM: NUMBER OF ENTRIES', found '" +
         line_.substr(0, 60) + "'");
  next_line("the number of rows");
  const std::int64_t rows =
      internal::parse_integer(line_, "the number of rows", [&](const std::string& w) { fail(w); });
  if (rows < 0) fail("a negative number of rows");
  next_line("ITEM: BOX BOUNDS");
  expect_item("BOX BOUNDS");
  std::vector<std::string_view> flags = internal::fields(line_);
  flags.erase(flags.begin(), flags.begin() + 3);  // ITEM: BOX BOUNDS
  frame.triclinic = flags.size() == 6 && flags[0] == "xy";
  if (frame.triclinic) flags.erase(flags.begin(), flags.begin() + 3);
  if (flags.size() != 3) fail("'ITEM: BOX BOUNDS' needs three boundary flags (e.g. pp pp pp)");
  for (int a = 0; a < 3; ++a) frame.boundary[a] = std::string(flags[a]);
  for (int a = 0; a < 3; ++a) {
    next_line("the box bounds");
    const std::vector<std::string_view> bounds = internal::fields(line_);
    if (bounds.size() != (frame.triclinic ? 3u : 2u)) fail("a box-bounds line needs its bounds");
    const auto bad = [&](const std::string& w) { fail("a box bound: " + w); };
    frame.lower[a] = internal::parse_real(bounds[0], bad);
    frame.upper[a] = internal::parse_real(bounds[1], bad);
  }
  next_line("ITEM: ATOMS or ITEM: ENTRIES");
  if (line_.rfind("ITEM: ATOMS", 0) != 0 && line_.rfind("ITEM: ENTRIES", 0) != 0)
    fail("expected 'ITEM: ATOMS ...' or 'ITEM: ENTRIES ...', found '" + line_.substr(0, 60) + "'");
  frame.columns.clear();
  for (std::string_view c : internal::fields(line_)) frame.columns.emplace_back(c);
  frame.columns.erase(frame.columns.begin(), frame.columns.begin() + 2);  // ITEM: ATOMS
  if (frame.columns.empty()) fail("the frame names no columns");
  const std::size_t width = frame.columns.size();
  frame.values.clear();
  frame.values.reserve(static_cast<std::size_t>(rows) * width);
  for (std::int64_t r = 0; r < rows; ++r) {
    if (!read_line())
      fail("the frame at timestep " + std::to_string(frame.timestep) + " announces " +
           std::to_string(rows) + " rows but the file ends after " + std::to_string(r) +
           " (truncated?)");
    const std::vector<std::string_view> values = internal::fields(line_);
    if (values.size() != width)
      fail(std::to_string(values.size()) + " values for " + std::to_string(width) + " columns");
    for (std::size_t k = 0; k < width; ++k)
      frame.values.push_back(internal::parse_real(values[k], [&](const std::string& w) {
        fail("column '" + frame.columns[k] + "': " + w);
      }));
  }
  return true;
}

}  // namespace dem_import
