// The registered constitutive models: the one place a model is added (descriptor.h).
#include <stdexcept>
#include <string>
#include <vector>

#include "model/descriptor.h"

namespace model {

// Each defined in its model's own description file.
const ModelDescription& acst_description();             // acst_description.cc
const ModelDescription& network_description();          // network_description.cc
const ModelDescription& linear_elastic_description();   // linear_elastic.cc

const std::vector<const ModelDescription*>& registered_models() {
  static const std::vector<const ModelDescription*> models = {
      &acst_description(), &network_description(), &linear_elastic_description()};
  return models;
}

const ModelDescription& find_model(const std::string& name) {
  std::string known;
  for (const ModelDescription* m : registered_models()) {
    if (m->name() == name) return *m;
    known += (known.empty() ? "" : ", ") + m->name();
  }
  throw std::invalid_argument("unknown model '" + name + "' (registered: " + known + ")");
}

}  // namespace model
