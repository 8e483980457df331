// The parameter tables' shared row (parameter_field.h).
#include "model/parameter_field.h"

#include <cstdio>
#include <string>

namespace model {

std::string format_number(double x) {
  char text[32];
  std::snprintf(text, sizeof text, "%g", x);
  return text;
}

std::string ParameterRange::describe() const {
  if (high == kUnbounded) return (low_closed ? ">= " : "> ") + format_number(low);
  return std::string("in ") + (low_closed ? "[" : "(") + format_number(low) + ", " +
         format_number(high) +
         (high_closed ? "]" : ")");
}

}  // namespace model
