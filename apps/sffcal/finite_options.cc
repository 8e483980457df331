// Non-finite numeric options refused by name (finite_options.h).
#include "finite_options.h"

#include <CLI/CLI.hpp>

#include <cmath>
#include <cstdlib>
#include <sstream>
#include <stdexcept>
#include <string>

namespace sffcal {
namespace {

// Whether the whole text reads as a number that is not finite (a file called "nan.h5" does not).
bool non_finite_number(const std::string& text) {
  if (text.empty()) return false;
  char* end = nullptr;
  const double x = std::strtod(text.c_str(), &end);
  return end == text.c_str() + text.size() && !std::isfinite(x);
}

}  // namespace

void refuse_non_finite_options(const CLI::App& app) {
  for (const CLI::Option* option : app.get_options()) {
    // Numbers only: a file or folder may be called "inf" (CLI11 names a double's type FLOAT).
    if (option->get_type_name().find("FLOAT") == std::string::npos) continue;
    for (const std::string& result : option->results()) {
      std::istringstream parts(result);
      std::string part;
      while (std::getline(parts, part, ','))
        if (non_finite_number(part))
          throw std::invalid_argument(option->get_name() + " " + result +
                                      ": not a finite number");
    }
  }
  for (const CLI::App* sub : app.get_subcommands()) refuse_non_finite_options(*sub);
}

}  // namespace sffcal
