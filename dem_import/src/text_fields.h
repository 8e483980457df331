// Internal: the fields of one line of a dump or a series table, and their numbers, parsed without
// the locale (std::from_chars). A failure calls fail(message), which throws naming file and line.
#pragma once

#include <charconv>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace dem_import::internal {

/// The fields of `line`, separated by spaces, tabs or commas.
inline std::vector<std::string_view> fields(std::string_view line) {
  std::vector<std::string_view> out;
  std::size_t k = 0;
  const auto separator = [](char c) { return c == ' ' || c == '\t' || c == ','; };
  while (k < line.size()) {
    while (k < line.size() && separator(line[k])) ++k;
    const std::size_t start = k;
    while (k < line.size() && !separator(line[k])) ++k;
    if (k > start) out.push_back(line.substr(start, k - start));
  }
  return out;
}

/// The number in `text`; otherwise fail("'<text>' is not a number"), to which the caller adds what
/// the value is (only then: a dump has millions of values).
template <class Fail>
double parse_real(std::string_view text, Fail&& fail) {
  std::string_view t = text;
  if (!t.empty() && t.front() == '+') t.remove_prefix(1);
  double value = 0.0;
  const auto [end, error] = std::from_chars(t.data(), t.data() + t.size(), value);
  if (error != std::errc() || end != t.data() + t.size())
    fail("'" + std::string(text.substr(0, 40)) + "' is not a number");
  return value;
}

template <class Fail>
std::int64_t parse_integer(std::string_view line, const std::string& what, Fail&& fail) {
  const std::vector<std::string_view> f = fields(line);
  std::int64_t value = 0;
  if (f.size() != 1)
    fail(what + ": expected one integer, found '" + std::string(line.substr(0, 40)) + "'");
  const auto [end, error] = std::from_chars(f[0].data(), f[0].data() + f[0].size(), value);
  if (error != std::errc() || end != f[0].data() + f[0].size())
    fail(what + ": '" + std::string(f[0].substr(0, 40)) + "' is not an integer");
  return value;
}

}  // namespace dem_import::internal
