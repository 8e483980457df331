#include "dem/loading_path.h"

#include <cmath>
#include <sstream>
#include <stdexcept>

namespace dem {
namespace {

// The enum value whose config spelling is `name`; throws naming `what` and the accepted spellings.
template <typename Enum>
Enum parse_spelling(const std::vector<std::string>& names, const std::string& name,
                    const char* what) {
  for (std::size_t k = 0; k < names.size(); ++k)
    if (names[k] == name) return static_cast<Enum>(k);
  std::string accepted;
  for (const std::string& n : names) accepted += (accepted.empty() ? "\"" : ", \"") + n + "\"";
  throw std::invalid_argument("unknown " + std::string(what) + " \"" + name + "\" (one of " +
                              accepted + ")");
}

}  // namespace

const std::vector<std::string>& loading_path_names() {
  static const std::vector<std::string> names = {
      "drained_compression",   "drained_extension",   "constant_p_compression",
      "undrained_compression", "undrained_extension", "true_triaxial"};
  return names;
}

const std::vector<std::string>& undrained_lateral_names() {
  static const std::vector<std::string> names = {"equal_strains", "equal_stresses"};
  return names;
}

const std::string& undrained_lateral_name(UndrainedLateral lateral) {
  return undrained_lateral_names()[static_cast<std::size_t>(lateral)];
}

UndrainedLateral parse_undrained_lateral(const std::string& name) {
  return parse_spelling<UndrainedLateral>(undrained_lateral_names(), name,
                                          "undrained lateral control");
}

const std::string& loading_path_name(LoadingPath path) {
  return loading_path_names()[static_cast<std::size_t>(path)];
}

LoadingPath parse_loading_path(const std::string& name) {
  return parse_spelling<LoadingPath>(loading_path_names(), name, "loading path");
}

int axial_direction(LoadingPath path) {
  return path == LoadingPath::kDrainedExtension || path == LoadingPath::kUndrainedExtension ? -1
                                                                                            : 1;
}

bool holds_volume(LoadingPath path) {
  return path == LoadingPath::kUndrainedCompression || path == LoadingPath::kUndrainedExtension;
}

bool lateral_targets_follow_axial_stress(LoadingPath path) {
  return path == LoadingPath::kConstantPCompression || path == LoadingPath::kTrueTriaxial;
}

bool uses_b(LoadingPath path) { return path == LoadingPath::kTrueTriaxial; }

std::array<double, 2> lateral_targets(LoadingPath path, double p0, double b, double sigma_z) {
  if (!lateral_targets_follow_axial_stress(path)) return {p0, p0};
  const double bb = path == LoadingPath::kTrueTriaxial ? b : 0.0;
  const double sigma_x = (3.0 * p0 - (1.0 + bb) * sigma_z) / (2.0 - bb);
  return {sigma_x, sigma_x + bb * (sigma_z - sigma_x)};
}

double constant_volume_width(double w0, double h0, double h) { return w0 * std::sqrt(h0 / h); }

std::array<double, 2> widths_of_area(double area, double ratio) {
  const double wx = std::sqrt(area * ratio);
  return {wx, area / wx};
}

std::array<std::string, 3> axis_controls(LoadingPath path, double p0, double b, double strain_rate,
                                         UndrainedLateral lateral) {
  std::ostringstream z;
  z << "strain-controlled, platens " << (axial_direction(path) > 0 ? "closing" : "parting")
    << " at " << strain_rate << " /s";
  if (holds_volume(path)) {
    const std::string held =
        lateral == UndrainedLateral::kEqualStrains
            ? "kinematic: width w0 sqrt(h0 / h), constant volume"
            : "kinematic: sigma_x = sigma_y at constant volume (W_x W_y = V0 / h, W_x / W_y "
              "servo-held)";
    return {held, held, z.str()};
  }
  std::ostringstream x, y;
  if (path == LoadingPath::kTrueTriaxial) {
    x << "stress-controlled: sigma_3 = (3 p0 - (1 + b) sigma_z) / (2 - b), p0 " << p0 << " Pa";
    y << "stress-controlled: sigma_2 = sigma_3 + b (sigma_z - sigma_3), b " << b;
  } else if (path == LoadingPath::kConstantPCompression) {
    x << "stress-controlled: (3 p0 - sigma_z) / 2, p0 " << p0 << " Pa";
    y << x.str();
  } else {
    x << "stress-controlled: sigma_3 " << p0 << " Pa";
    y << x.str();
  }
  return {x.str(), y.str(), z.str()};
}

}  // namespace dem
