// Fuzz target: the parameter file of every registered model (model/parameter_file.h; strict
// JSON: unknown or repeated keys and trailing content refused). The bytes are the file, written to
// a scratch file and read as the CLI, the FE side and the UMAT read it: for any model, for each
// fitted model by name, and through the two fitted models' typed readers. A file that is accepted
// must give its model's behaviour.
#include <cstddef>
#include <cstdint>
#include <string>

#include "fuzz_support.h"
#include "model/acst_model.h"
#include "model/descriptor.h"
#include "model/network_model.h"
#include "model/parameter_file.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const sffcal_fuzz::ScratchFile file("parameters.json");
  file.write(data, size);
  const std::string& path = file.path();
  sffcal_fuzz::refused_or_read("model name", [&] { model::parameter_file_model(path); });
  sffcal_fuzz::refused_or_read("any model", [&] {
    const model::ParameterValues values = model::read_parameter_file(path);
    try {
      model::find_model(values.model).make(values.constants, values.parameters);
    } catch (const std::exception& e) {
      sffcal_fuzz::finding("an accepted parameter file of model '" + values.model +
                           "' gives no behaviour: " + e.what());
    }
  });
  for (const char* name : {"acst", "contact_network", "linear_elastic"})
    sffcal_fuzz::refused_or_read(name, [&] { model::read_parameter_file(path, name); });
  sffcal_fuzz::refused_or_read("ACST typed", [&] { model::acst::read_parameters_json(path); });
  sffcal_fuzz::refused_or_read("network typed", [&] {
    double youngs_modulus = 0.0;
    model::network::read_parameters_json(path, &youngs_modulus);
  });
  return 0;
}
