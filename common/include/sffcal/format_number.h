// A number as the messages write it: %g, so that 1e-08 is not to_string's 0.000000.
#pragma once

#include <cstdio>
#include <string>

namespace sffcal {

inline std::string format_number(double x) {
  char text[32];
  std::snprintf(text, sizeof text, "%g", x);
  return text;
}

}  // namespace sffcal
