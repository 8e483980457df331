// One row of a model's parameter table: the single list that its parameter file, its UMAT PROPS,
// its validation, a fit's bounds and tables and its docs page follow
// (model::acst::kParameterFields, model::network::kParameterFields). Standard library only.
#pragma once

#include <limits>
#include <string>

namespace model {

/// ParameterField::value_if_absent of a parameter every parameter file must give.
inline constexpr double kRequired = std::numeric_limits<double>::quiet_NaN();
inline constexpr double kUnbounded = std::numeric_limits<double>::infinity();

/// A number as the parameter messages write it (%g: 1e-08, not to_string's 0.000000;
/// sffcal/format_number.h, for the installed interface).
std::string format_number(double x);

/// Where a parameter is physical: low < x < high, with <= at a closed end.
struct ParameterRange {
  double low, high;
  bool low_closed, high_closed;
  constexpr bool contains(double x) const {
    return (low_closed ? x >= low : x > low) && (high_closed ? x <= high : x < high);
  }
  /// As the docs write it: "> 0", ">= 0", "in (-1, 0.5)", "in (0, 1]".
  std::string describe() const;
};

/// One parameter of the model whose parameter set is the struct `Set` of scalars T: its name (the
/// key of the parameter file and of the fits' tables), its member, its unit, the range validation
/// accepts, the fits' default search range, and the value a parameter file or UMAT PROPS without
/// it stands for (kRequired: none; a parameter added after a model's first version takes the value
/// that gives the model without it).
template <typename Set, typename T>
struct ParameterField {
  const char* name;
  T Set::*member;
  const char* unit;
  ParameterRange physical;
  double fit_low, fit_high;
  double value_if_absent = kRequired;
  constexpr bool required() const { return value_if_absent != value_if_absent; }  // NaN: none
};

}  // namespace model
