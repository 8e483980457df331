// Fuzz target: the TOML configuration of a DEM run. The bytes are a config file's text, given to
// dem::parse_run_config as a user's config (unknown keys refused) and as a config stored in a run
// file (unknown keys ignored), and to runfile::physics_from_config_text (a schema-1 run file's
// physics). A config that is accepted must give the run metadata the CLI writes next.
#include <cstddef>
#include <cstdint>
#include <string>

#include "dem/run_config.h"
#include "fuzz_support.h"
#include "runfile/stored_physics.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  sffcal_fuzz::refused_or_read("user config", [&] {
    const dem::RunConfig config = dem::parse_run_config(text, "fuzz.toml");
    dem::run_metadata("triaxial", config, "fuzz");
  });
  sffcal_fuzz::refused_or_read("stored config", [&] {
    const dem::RunConfig config =
        dem::parse_run_config(text, "stored config", dem::UnknownKeys::kIgnore);
    dem::run_metadata("specimen", config, "fuzz");
  });
  sffcal_fuzz::refused_or_read("schema-1 physics",
                               [&] { runfile::physics_from_config_text(text, "stored config"); });
  return 0;
}
