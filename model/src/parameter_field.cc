// The parameter tables' shared row (parameter_field.h).
#include "model/parameter_field.h"

#include <cstdio>
#include <string>

namespace model {

std::string ParameterRange::describe() const {
  auto number = [](double x) {
    char text[32];
    std::snprintf(text, sizeof text, "%g", x);
    return std::string(text);
  };
  if (high == kUnbounded) return (low_closed ? ">= " : "> ") + number(low);
  return std::string("in ") + (low_closed ? "[" : "(") + number(low) + ", " + number(high) +
         (high_closed ? "]" : ")");
}

}  // namespace model
