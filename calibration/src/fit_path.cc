// The model strain grid of a DEM test (fit_path.h).
#include "fit_path.h"

#include <algorithm>
#include <cmath>

namespace calibration {
namespace fit_detail {

Lateral lateral_of(TestPath path) {
  if (is_undrained(path)) return Lateral::kVolume;
  return path == TestPath::kConstantPCompression ? Lateral::kMeanStress : Lateral::kStress;
}

Grid make_grid(const TestData& t, int max_points, double max_strain_step) {
  Grid g;
  // The grid counts |eps_a| (the strain along the path's direction); the steps carry the sign.
  const double direction = axial_direction(t.path);
  auto along = [&](double axial) { return direction * axial; };
  const int n = static_cast<int>(t.axial_strain.size());
  const int wanted = std::max(3, std::min(max_points, n));
  for (int k = 0; k < wanted; ++k) {
    const int row = static_cast<int>(std::lround(static_cast<double>(k) * (n - 1) / (wanted - 1)));
    if (g.rows.empty() || row != g.rows.back()) g.rows.push_back(row);
  }
  std::vector<double> strains = {0.0};
  for (int row : g.rows) strains.push_back(along(t.axial_strain[row]));
  const double last = along(t.axial_strain.back());
  for (double s : t.snapshot_axial_strain)
    if (along(s) <= last) strains.push_back(along(s));
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
  const int end = static_cast<int>(grid.size()) - 1;
  auto liquefied = [&](int row) {
    return static_cast<char>(liquefied_at_row(t, static_cast<std::size_t>(row)) ? 1 : 0);
  };
  for (int row : g.rows) {
    g.row_at.push_back(std::min(index_of(along(t.axial_strain[row])), end));
    g.row_liquefied.push_back(liquefied(row));
  }
  for (double s : t.snapshot_axial_strain) {
    g.snapshot_at.push_back(along(s) <= last + 1e-7 ? std::min(index_of(along(s)), end) : -1);
    // The series row nearest in strain.
    int nearest = 0;
    for (int row = 1; row < n; ++row)
      if (std::abs(t.axial_strain[row] - s) < std::abs(t.axial_strain[nearest] - s)) nearest = row;
    g.snapshot_liquefied.push_back(liquefied(nearest));
  }
  for (std::size_t k = 1; k < grid.size(); ++k) {
    PathStep step;
    if (is_undrained(t.path)) {
      const double d = direction * (grid[k] - grid[k - 1]);
      step.control = {Control::kStrain, Control::kStrain, Control::kStrain,
                      Control::kStrain, Control::kStrain, Control::kStrain};
      step.value = {-0.5 * d, -0.5 * d, d, 0.0, 0.0, 0.0};
    } else {
      // The lateral stress sigma_3 = p0 (for constant p the driver holds the mean stress, which
      // the general driver's per-component controls cannot say: axisymmetric_path reads value[0]).
      step.control = {Control::kStress, Control::kStress, Control::kStrain,
                      Control::kStrain, Control::kStrain, Control::kStrain};
      step.value = {t.p0, t.p0, direction * (grid[k] - grid[k - 1]), 0.0, 0.0, 0.0};
    }
    g.steps.push_back(step);
  }
  return g;
}

std::vector<int> residual_series(const TestData& t, const Grid& g, const ResidualSpec& spec) {
  std::vector<int> lengths;
  const int rows = static_cast<int>(g.rows.size()) - 1;  // the first row is the initial state
  if (spec.eta) {
    int n = 0;
    for (int i = 1; i <= rows; ++i) n += g.row_liquefied[i] ? 0 : 1;
    lengths.push_back(n);
  }
  if (spec.volumetric) lengths.push_back(rows);
  if (spec.fabric) {
    int n = 0;
    for (std::size_t k = 1; k < t.a_c.size(); ++k)
      n += g.snapshot_at[k] >= 0 && !g.snapshot_liquefied[k] ? 1 : 0;
    lengths.push_back(n);
  }
  return lengths;
}

int count_residuals(const TestData& t, const Grid& g, const ResidualSpec& spec) {
  int n = 0;
  for (int length : residual_series(t, g, spec)) n += length;
  return n;
}

}  // namespace fit_detail
}  // namespace calibration
