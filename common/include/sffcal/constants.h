// Mathematical constants of the whole project, defined once (C++17 has no std::numbers).
#pragma once

namespace sffcal {

inline constexpr double kPi = 3.14159265358979323846;
inline constexpr double kDegreesPerRadian = 180.0 / kPi;

}  // namespace sffcal
