// The model strain grid of a DEM test (fit_path.h).
#include "fit_path.h"

#include <algorithm>
#include <cmath>

namespace calibration {
namespace fit_detail {

Grid make_grid(const TestData& t, int max_points, double max_strain_step) {
  Grid g;
  const int n = static_cast<int>(t.axial_strain.size());
  const int wanted = std::max(3, std::min(max_points, n));
  for (int k = 0; k < wanted; ++k) {
    const int row = static_cast<int>(std::lround(static_cast<double>(k) * (n - 1) / (wanted - 1)));
    if (g.rows.empty() || row != g.rows.back()) g.rows.push_back(row);
  }
  std::vector<double> strains = {0.0};
  for (int row : g.rows) strains.push_back(t.axial_strain[row]);
  const double last = t.axial_strain.back();
  for (double s : t.snapshot_axial_strain)
    if (s <= last) strains.push_back(s);
  std::sort(strains.begin(), strains.end());
  std::vector<double> grid;
  for (double s : strains) {
    if (!grid.empty() && !(s - grid.back() > 1e-7)) continue;
    if (!grid.empty() && max_strain_step > 0.0) {
      const double from = grid.back(), gap = s - from;
      const int parts = static_cast<int>(std::ceil(gap / max_strain_step - 1e-9));
      for (int k = 1; k < parts; ++k) grid.push_back(from + gap * k / parts);
    }
    grid.push_back(s);
  }
  auto index_of = [&](double s) {
    const auto it = std::lower_bound(grid.begin(), grid.end(), s - 1e-7);
    return static_cast<int>(it - grid.begin());
  };
  for (int row : g.rows) g.row_at.push_back(std::min(index_of(t.axial_strain[row]),
                                                     static_cast<int>(grid.size()) - 1));
  for (double s : t.snapshot_axial_strain)
    g.snapshot_at.push_back(s <= last + 1e-7 ? std::min(index_of(s), static_cast<int>(grid.size()) - 1)
                                             : -1);
  for (std::size_t k = 1; k < grid.size(); ++k) {
    PathStep step;
    step.control = {Control::kStress, Control::kStress, Control::kStrain,
                    Control::kStrain, Control::kStrain, Control::kStrain};
    step.value = {t.p0, t.p0, grid[k] - grid[k - 1], 0.0, 0.0, 0.0};
    g.steps.push_back(step);
  }
  return g;
}

int count_residuals(const TestData& t, const Grid& g, const ResidualSpec& spec) {
  int n = 0;
  const int rows = static_cast<int>(g.rows.size()) - 1;  // the first row is the initial state
  if (spec.eta) n += rows;
  if (spec.volumetric) n += rows;
  if (spec.fabric)
    for (std::size_t k = 1; k < t.a_c.size(); ++k) n += g.snapshot_at[k] >= 0 ? 1 : 0;
  return n;
}


}  // namespace fit_detail
}  // namespace calibration
