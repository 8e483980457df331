// Command-line helper shared by the benchmark executables.
#pragma once

#include <cstdlib>
#include <sstream>
#include <string>
#include <vector>

namespace bench {

/// "1,2,4" -> {1, 2, 4}.
inline std::vector<int> parse_int_list(const std::string& text) {
  std::vector<int> values;
  std::stringstream in(text);
  std::string item;
  while (std::getline(in, item, ',')) values.push_back(std::atoi(item.c_str()));
  return values;
}

}  // namespace bench
