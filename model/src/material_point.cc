#include "model/material_point.h"

#include <sstream>
#include <stdexcept>
#include <string>

namespace model::acst {

std::vector<PathStep> parse_path_table(const std::string& text) {
  std::vector<PathStep> steps;
  std::istringstream lines(text);
  std::string line;
  for (int number = 1; std::getline(lines, line); ++number) {
    const std::size_t hash = line.find('#');
    if (hash != std::string::npos) line.erase(hash);
    std::istringstream fields(line);
    std::string field;
    PathStep step;
    int count = 0;
    while (fields >> field) {
      if (count == 6) throw std::runtime_error("path table line " + std::to_string(number) +
                                               ": more than 6 fields");
      const bool strain = field.rfind("e:", 0) == 0, stress = field.rfind("s:", 0) == 0;
      if (!strain && !stress)
        throw std::runtime_error("path table line " + std::to_string(number) + ": field '" +
                                 field + "' must be e:<strain increment> or s:<stress in Pa>");
      std::size_t used = 0;
      double v = 0.0;
      try {
        v = std::stod(field.substr(2), &used);
      } catch (const std::exception&) {
        used = 0;
      }
      if (used == 0 || used != field.size() - 2)
        throw std::runtime_error("path table line " + std::to_string(number) + ": '" + field +
                                 "' has no valid number");
      step.control[static_cast<std::size_t>(count)] = strain ? Control::kStrain : Control::kStress;
      step.value[static_cast<std::size_t>(count)] = v;
      ++count;
    }
    if (count == 0) continue;
    if (count != 6)
      throw std::runtime_error("path table line " + std::to_string(number) + ": " +
                               std::to_string(count) + " fields, 6 needed (xx yy zz xy yz xz)");
    steps.push_back(step);
  }
  return steps;
}

}  // namespace model::acst
