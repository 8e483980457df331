// A typed parameter set and the vector of its values in the order of its table (a kParameterFields
// of model/parameter_field.h rows): what the model interface and the parameter file exchange.
#pragma once

#include <cstddef>
#include <vector>

namespace model {

template <typename Table, typename Set>
std::vector<double> values_in_table_order(const Table& table, const Set& set) {
  std::vector<double> values;
  for (const auto& field : table) values.push_back(set.*field.member);
  return values;
}

template <typename Set, typename Table>
Set set_from_table_order(const Table& table, const std::vector<double>& values) {
  Set set;
  for (std::size_t k = 0; k < table.size(); ++k) set.*table[k].member = values[k];
  return set;
}

}  // namespace model
