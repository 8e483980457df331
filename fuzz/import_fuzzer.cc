// Fuzz target: `sffcal import` (dem_import, docs/import.md). The first byte chooses which of the
// four files of a small YADE run (corpus/import_seed, written by examples/yade/triaxial.py) the
// rest of the bytes replace: import.toml, the atoms dump, the contacts dump or the series table.
// The run is then imported into a scratch run file. What the importer accepts, every reader after
// it must take: each snapshot read back with the run file's own check, its SFF input built.
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "dem_import/description.h"
#include "dem_import/import_run.h"
#include "fuzz_support.h"
#include "runfile/run_file.h"
#include "sff/run_snapshot.h"

namespace {

const char* const kFiles[] = {"import.toml", "atoms.dump", "contacts.dump", "series.txt"};

std::string seed_text(const char* name) {
  std::ifstream in(std::string(SFFCAL_FUZZ_DIR) + "/corpus/import_seed/" + name);
  if (!in) sffcal_fuzz::finding(std::string("cannot read the seed file ") + name);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

// A scratch folder of this process (where the other targets keep their scratch files), removed
// at exit.
struct ScratchFolder {
  sffcal_fuzz::ScratchFile name{"import"};
  ScratchFolder() { std::filesystem::create_directories(name.path()); }
  ~ScratchFolder() {
    std::error_code error;
    std::filesystem::remove_all(name.path(), error);
  }
};

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  static const ScratchFolder scratch;
  const std::string& folder = scratch.name.path();
  static const std::string seeds[4] = {seed_text(kFiles[0]), seed_text(kFiles[1]),
                                       seed_text(kFiles[2]), seed_text(kFiles[3])};
  const std::size_t replaced = data[0] % 4;
  for (std::size_t k = 0; k < 4; ++k) {
    std::ofstream out(folder + "/" + kFiles[k], std::ios::binary | std::ios::trunc);
    if (k == replaced) out.write(reinterpret_cast<const char*>(data + 1), static_cast<std::streamsize>(size - 1));
    else out << seeds[k];
  }
  const std::string output = folder + "/run.h5";
  std::filesystem::remove(output);
  bool imported = false;
  sffcal_fuzz::refused_or_read("import", [&] {
    const dem_import::ImportDescription d = dem_import::read_description(folder + "/import.toml");
    dem_import::import_run(d, output, "fuzz", [](const std::string&) {});
    imported = true;
  });
  if (!imported) return 0;
  try {
    const runfile::RunFile file = runfile::RunFile::open(output);
    for (const std::string& name : file.series_names()) file.series(name);
    for (int k = 0; k < file.num_snapshots(); ++k)
      sff::snapshot_input(file.read_snapshot(k), file.metadata().physics);
  } catch (const std::exception& e) {
    sffcal_fuzz::finding(std::string("an accepted import does not read back: ") + e.what());
  }
  return 0;
}
