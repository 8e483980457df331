// The seed run file of the structure-aware targets (fuzz/corpus/tiny_run.h5, made by
// fuzz/make_seed_run.sh), or the one SFFCAL_FUZZ_SEED_RUN names.
#pragma once

#include <cstdlib>
#include <string>

namespace sffcal_fuzz {

inline std::string seed_run_path() {
  const char* path = std::getenv("SFFCAL_FUZZ_SEED_RUN");
  return path && *path ? path : SFFCAL_FUZZ_DIR "/corpus/tiny_run.h5";
}

}  // namespace sffcal_fuzz
