// Command-line helpers shared by the benchmark executables.
#pragma once

#include <cstdio>
#include <cstdlib>
#include <functional>
#include <sstream>
#include <string>
#include <vector>

namespace bench {

/// "a,b,c" -> {convert("a"), convert("b"), convert("c")}.
template <typename T, typename Convert>
std::vector<T> parse_list(const std::string& text, Convert convert) {
  std::vector<T> values;
  std::stringstream in(text);
  std::string item;
  while (std::getline(in, item, ',')) values.push_back(convert(item));
  return values;
}

/// "1,2,4" -> {1, 2, 4}.
inline std::vector<int> parse_int_list(const std::string& text) {
  return parse_list<int>(text, [](const std::string& item) { return std::atoi(item.c_str()); });
}

/// "0.5,0.7" -> {0.5, 0.7}.
inline std::vector<double> parse_double_list(const std::string& text) {
  return parse_list<double>(text, [](const std::string& item) { return std::atof(item.c_str()); });
}

/// Positional arguments into `positional`, and each "--name value" to set(name, value), which
/// returns false for a name it does not know. False, with a message on stderr, for an option
/// without a value or with an unknown name.
inline bool parse_arguments(int argc, char** argv, std::vector<std::string>& positional,
                            const std::function<bool(const std::string&, const std::string&)>& set) {
  for (int k = 1; k < argc; ++k) {
    const std::string arg = argv[k];
    if (arg.rfind("--", 0) != 0) {
      positional.push_back(arg);
      continue;
    }
    if (k + 1 >= argc) {
      std::fprintf(stderr, "%s needs a value\n", arg.c_str());
      return false;
    }
    if (!set(arg, argv[++k])) {
      std::fprintf(stderr, "unknown option %s\n", arg.c_str());
      return false;
    }
  }
  return true;
}

}  // namespace bench
