// Fuzz target: the checkpoint of a run file (dem::read_checkpoint, which validates it),
// structure-aware. The bytes choose edits of the seed run file, three in four under /checkpoint
// (run_file_mutator.h); the edited copy is read as `sffcal triaxial` reads a specimen (read-only)
// and as `sffcal triaxial --resume` reads a killed run: open for writing, the stored config
// parsed, the checkpoint read (which drops the series rows and snapshots written after it), and
// the engine started from it for a few steps. What read_checkpoint accepts the engine must be able
// to run: a crash or a sanitizer report in those steps is a hole in its checks. Every reader either
// reads or throws a std::exception.
#include <omp.h>

#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string>

#include "dem/run_config.h"
#include "dem/run_file_io.h"
#include "dem/simulation.h"
#include "fuzz_support.h"
#include "run_file_mutator.h"
#include "runfile/run_file.h"
#include "seed_run.h"

namespace {

constexpr int kSteps = 5;

void resume(const std::string& path) {
  using sffcal_fuzz::refused_or_read;
  refused_or_read("checkpoint (read-only)", [&] {
    runfile::RunFile file = runfile::RunFile::open(path);
    runfile::CheckpointExtras extras;
    if (file.has_checkpoint()) dem::read_checkpoint(file, &extras);
  });
  refused_or_read("resume", [&] {
    runfile::RunFile file = runfile::RunFile::open(path, true);
    const dem::RunConfig config =
        dem::parse_run_config(file.metadata().config_text, path + " (stored config)");
    if (!file.has_checkpoint()) return;
    runfile::CheckpointExtras extras;
    dem::SimulationState state = dem::read_checkpoint(file, &extras);
    refused_or_read("after the rewind", [&] {
      file.series_length();
      for (const std::string& name : file.series_names()) file.series(name);
      if (file.num_snapshots() > 0) file.read_snapshot(file.num_snapshots() - 1);
    });
    dem::Simulation simulation(std::move(state), config.contact, config.engine);
    simulation.run(kSteps);
  });
}

}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  setenv("HDF5_USE_FILE_LOCKING", "FALSE", 1);
  omp_set_num_threads(1);  // the engine's steps: a fuzzer runs one input at a time per process
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const sffcal_fuzz::RunFileMutator mutator(sffcal_fuzz::seed_run_path());
  static const sffcal_fuzz::ScratchFile file("checkpoint.h5");
  FuzzedDataProvider bytes(data, size);
  for (const std::string& edit : mutator.write(file.path(), bytes, "/checkpoint"))
    if (sffcal_fuzz::verbose()) std::fprintf(stderr, "edit %s\n", edit.c_str());
  sffcal_fuzz::keep_edited_copy(file.path());
  resume(file.path());
  return 0;
}
