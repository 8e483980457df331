// Fuzz target: a packing read from CSV (preparation method "csv", docs/config.md). The bytes are
// the file's text, given to dem::parse_csv_packing with the default grains and overlap limit. A
// packing that is accepted must be one the engine can take: its box finite with hi > lo, and
// its bodies passing the engine's own check (Particles::check).
#include <cstddef>
#include <cstdint>
#include <string>

#include "dem/specimen.h"
#include "fuzz_support.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  sffcal_fuzz::refused_or_read("packing", [&] {
    Eigen::Vector3d lo, hi;
    const dem::Particles particles =
        dem::parse_csv_packing(text, "fuzz.csv", dem::GrainSpec{}, &lo, &hi);
    if (!lo.allFinite() || !hi.allFinite() || !(hi - lo).allFinite() ||
        !((hi - lo).minCoeff() > 0.0))
      sffcal_fuzz::finding("an accepted packing has a box that is not finite with hi > lo");
    const std::string error = particles.check();
    if (!error.empty())
      sffcal_fuzz::finding("an accepted packing fails the engine's check: " + error);
  });
  return 0;
}
