// The input-deck cards of a model's UMAT (umat_cards.h).
#include "fe_model/umat_cards.h"

#include <cstdio>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "fe_model/model_start.h"
#include "model/descriptor.h"
#include "model/parameter_file.h"

namespace fe_model {
namespace {

// %.17g: PROPS read back bit for bit.
std::string exact(double x) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.17g", x);
  return buffer;
}

}  // namespace

std::string umat_cards(const UmatCardOptions& options) {
  if (options.client != "calculix" && options.client != "abaqus")
    throw std::invalid_argument("--client " + options.client + ": calculix or abaqus");
  if (options.integration_points < 1)
    throw std::invalid_argument("--points must be >= 1 (integration points per element)");
  for (int e : options.elements)
    if (e < 1) throw std::invalid_argument("--elements: element numbers start at 1");
  const model::ParameterValues values = model::read_parameter_file(options.parameters_path);
  const model::ModelDescription& d = model::find_model(values.model);
  const ModelStart start = specimen_start(values, options.parameters_path, options.start);
  const std::vector<double> props =
      model::umat_props(d, start.inputs, values.constants, values.parameters);
  const std::vector<std::string> names = model::umat_props_names(d);
  const std::string material = (options.client == "calculix" ? "ABAQUS" : "") + d.umat_name();

  std::ostringstream out;
  out << "** sffcal umat-cards: the " << d.name() << " model, parameters "
      << options.parameters_path << "\n** start: "
      << (options.start.dem_run.empty() ? "a plain specimen" : options.start.dem_run)
      << ", sigma_3 = " << exact(start.confining_pressure) << " Pa, inputs " << start.source
      << "\n** PROPS (compression positive, SI):";
  for (std::size_t i = 0; i < names.size(); ++i)
    out << (i % 4 == 0 ? "\n**  " : "  ") << i + 1 << " " << names[i];
  if (options.client == "calculix")
    out << "\n** CalculiX reads a temperature after the last constant (on a line of its own where "
           "the\n** constants fill their last line): 0 here, unused by the UMAT";
  out << "\n*MATERIAL, NAME=" << material << "\n*USER MATERIAL, CONSTANTS=" << props.size();
  for (std::size_t i = 0; i < props.size(); ++i)
    out << (i % 8 == 0 ? "\n" : ", ") << exact(props[i]);
  if (options.client == "calculix") out << (props.size() % 8 == 0 ? "\n" : ", ") << "0";
  // STATEV(1): the UMAT's flag, then the model's state.
  out << "\n*DEPVAR\n" << 1 + model::slot_components(d.state()) << "\n";
  if (!options.elements.empty()) {
    const std::string s = exact(-start.confining_pressure);
    out << "** the specimen's initial stress, tension positive (the UMAT starts its state from it)\n"
        << "*INITIAL CONDITIONS, TYPE=STRESS\n";
    // CalculiX reads element, integration point, six components; Abaqus element, six components.
    for (int e : options.elements) {
      if (options.client == "abaqus") {
        out << e << ", " << s << ", " << s << ", " << s << ", 0, 0, 0\n";
        continue;
      }
      for (int k = 1; k <= options.integration_points; ++k)
        out << e << ", " << k << ", " << s << ", " << s << ", " << s << ", 0, 0, 0\n";
    }
  }
  return out.str();
}

}  // namespace fe_model
