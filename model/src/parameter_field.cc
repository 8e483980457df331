// The parameter tables' shared row (parameter_field.h).
#include "model/parameter_field.h"

#include <string>

#include "sffcal/format_number.h"

namespace model {

std::string format_number(double x) { return sffcal::format_number(x); }

std::string ParameterRange::describe() const {
  if (high == kUnbounded) return (low_closed ? ">= " : "> ") + format_number(low);
  return std::string("in ") + (low_closed ? "[" : "(") + format_number(low) + ", " +
         format_number(high) +
         (high_closed ? "]" : ")");
}

}  // namespace model
