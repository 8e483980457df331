// Fuzz target: the run file's readers (runfile/run_file.h), structure-aware. The bytes choose
// edits of the seed run file (run_file_mutator.h: values, array sizes, shapes and types,
// attributes, groups); the edited copy is then read as every stage reads it: the metadata and
// physics (and the stored config, parsed as --resume parses it), the notes, the summary, every
// series, every snapshot with its consistency check (runfile/src/snapshot_check.h), the
// checkpoint's arrays (dem::read_checkpoint, read-only), the analysis table and the DEM test the
// continuum stages read (runfile::read_dem_test). Each reader either reads or throws a
// std::exception. A snapshot that is accepted is analysed as `sffcal sff` analyses it (its SFF
// input and analysis): what the check lets through, every reader of a snapshot may trust.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <memory>
#include <string>

#include "dem/run_config.h"
#include "dem/run_file_io.h"
#include "fuzz_support.h"
#include "run_file_mutator.h"
#include "runfile/dem_test.h"
#include "runfile/run_file.h"
#include "seed_run.h"
#include "sff/analysis.h"
#include "sff/run_snapshot.h"

namespace {

void read_everything(const std::string& path) {
  using sffcal_fuzz::refused_or_read;
  std::unique_ptr<runfile::RunFile> file;
  refused_or_read("open", [&] {
    file = std::make_unique<runfile::RunFile>(runfile::RunFile::open(path));
  });
  if (!file) return;
  refused_or_read("metadata", [&] {
    const runfile::RunMetadata m = file->metadata();
    refused_or_read("stored config", [&] { dem::parse_run_config(m.config_text, "stored config"); });
  });
  for (const char* note : {"preparation", "specimen", "summary"})
    refused_or_read("note", [&] { file->read_note(note); });
  refused_or_read("summary", [&] {
    if (file->has_summary()) file->read_summary().describe();
  });
  refused_or_read("series", [&] {
    file->series_length();
    for (const std::string& name : file->series_names()) file->series(name);
  });
  refused_or_read("snapshot count", [&] {
    const runfile::RunPhysics physics = file->metadata().physics;
    const int n = file->num_snapshots();
    for (int k = -1; k <= std::min(n, 4); ++k)
      refused_or_read("snapshot", [&] {
        const runfile::Snapshot s = file->read_snapshot(k);
        refused_or_read("SFF analysis", [&] { sff::analyse_snapshot(sff::snapshot_input(s, physics)); });
      });
  });
  refused_or_read("checkpoint", [&] {
    runfile::CheckpointExtras extras;
    if (file->has_checkpoint()) dem::read_checkpoint(*file, &extras);
  });
  refused_or_read("table", [&] {
    if (file->has_table("sff")) file->read_table("sff");
  });
  file.reset();
  refused_or_read("DEM test", [&] { runfile::read_dem_test(path); });
}

}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  setenv("HDF5_USE_FILE_LOCKING", "FALSE", 1);
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const sffcal_fuzz::RunFileMutator mutator(sffcal_fuzz::seed_run_path());
  static const sffcal_fuzz::ScratchFile file("run.h5");
  FuzzedDataProvider bytes(data, size);
  for (const std::string& edit : mutator.write(file.path(), bytes))
    if (sffcal_fuzz::verbose()) std::fprintf(stderr, "edit %s\n", edit.c_str());
  sffcal_fuzz::keep_edited_copy(file.path());
  read_everything(file.path());
  return 0;
}
