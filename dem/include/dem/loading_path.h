// The loading paths of a triaxial-cell test (issue 18): what drives each axis of the box.
// z is always the driven axis: its platens close (compression) or part (extension) at the strain
// rate. The lateral walls x and y are servo-held at stresses that follow the path, or, on the
// undrained paths, moved with the platens so that the volume stays constant (the dry-DEM
// equivalent of an undrained test: the effective stress path is what is recorded).
#pragma once

#include <array>
#include <string>
#include <vector>

namespace dem {

enum class LoadingPath {
  kDrainedCompression,    ///< sigma_x = sigma_y = sigma_3, platens close
  kDrainedExtension,      ///< sigma_x = sigma_y = sigma_3, platens part (axial stress falls)
  kConstantPCompression,  ///< sigma_x = sigma_y = (3 p0 - sigma_z) / 2, platens close
  kUndrainedCompression,  ///< constant volume, platens close
  kUndrainedExtension,    ///< constant volume, platens part
  kTrueTriaxial,          ///< constant p0 and b = (sigma_y - sigma_x) / (sigma_z - sigma_x)
};

/// How the undrained paths share the volume between the two lateral axes.
enum class UndrainedLateral {
  kEqualStrains,   ///< both widths scaled alike, W = w0 sqrt(h0 / h) (the lateral stresses free)
  kEqualStresses,  ///< sigma_x = sigma_y, as a cell's fluid holds them: the widths' product is
                   ///< V0 / h, their ratio servo-held (a deposit's two lateral axes differ)
};

/// The config spellings ("equal_strains", "equal_stresses"), in the order of the enum.
const std::vector<std::string>& undrained_lateral_names();
const std::string& undrained_lateral_name(UndrainedLateral lateral);
/// Throws std::invalid_argument naming the accepted spellings.
UndrainedLateral parse_undrained_lateral(const std::string& name);

/// The config spellings ("drained_compression", ...), in the order of the enum.
const std::vector<std::string>& loading_path_names();
const std::string& loading_path_name(LoadingPath path);
/// Throws std::invalid_argument naming the accepted spellings.
LoadingPath parse_loading_path(const std::string& name);

/// +1 where the platens close (compression), -1 where they part (extension).
int axial_direction(LoadingPath path);
/// The undrained paths: the lateral walls follow the volume, not a stress.
bool holds_volume(LoadingPath path);
/// Constant p and true triaxial: the lateral targets follow the axial stress, step by step.
bool lateral_targets_follow_axial_stress(LoadingPath path);
/// Whether the path reads the intermediate principal stress ratio b.
bool uses_b(LoadingPath path);

/// The lateral stresses to hold [Pa] (compression positive) when the axial stress is sigma_z:
/// sigma_3 on the drained paths; on constant p and true triaxial the pair that keeps
/// p = (sigma_x + sigma_y + sigma_z) / 3 = p0 with sigma_y - sigma_x = b (sigma_z - sigma_x):
/// sigma_x = (3 p0 - (1 + b) sigma_z) / (2 - b), sigma_y = sigma_x + b (sigma_z - sigma_x)
/// (b = 0 gives constant p compression). `p0` is the confining stress the test starts from.
std::array<double, 2> lateral_targets(LoadingPath path, double p0, double b, double sigma_z);

/// The lateral width that keeps the volume of a box of initial width w0 and height h0 at height
/// h, with both lateral widths scaled alike: W = w0 sqrt(h0 / h).
double constant_volume_width(double w0, double h0, double h);

/// The lateral widths of area (product) `area` whose ratio W_x / W_y is `ratio`.
std::array<double, 2> widths_of_area(double area, double ratio);

/// How each axis (x, y, z) is held, in words, for the run file and `sffcal info`.
std::array<std::string, 3> axis_controls(LoadingPath path, double p0, double b, double strain_rate,
                                         UndrainedLateral lateral = UndrainedLateral::kEqualStrains);

}  // namespace dem
