// The final window of a test: its output rows within a width of the last axial strain. The DEM's
// critical-state test and the critical q/p of its summary (dem/src/triaxial.cc) and calibration's
// critical states (calibration/src/fit.cc) average over it; the scripts' sffcal.runfile.end_window
// (python/sffcal/runfile.py) is the same rule. Only the widths differ (TriaxialOptions::
// critical_window, FitOptions::critical_window, 5 % in the reports).
#pragma once

#include <cstddef>
#include <vector>

namespace sffcal {

/// The first index k from which every row lies within `width` of `last`: last - strain[k] <=
/// width, scanning back from the end (the axial strain grows along a test, compression positive
/// or |strain|). strain.size() where even the last row is outside.
inline std::size_t final_window_start(const std::vector<double>& strain, double last,
                                      double width) {
  std::size_t start = strain.size();
  while (start > 0 && last - strain[start - 1] <= width) --start;
  return start;
}

/// The same with `last` the series' own last value (0 for an empty series).
inline std::size_t final_window_start(const std::vector<double>& strain, double width) {
  return strain.empty() ? 0 : final_window_start(strain, strain.back(), width);
}

}  // namespace sffcal
