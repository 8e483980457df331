// Fuzz target: `sffcal import` (dem_import, docs/import.md). The first byte chooses a small run,
// a periodic one of YADE (corpus/import_seed, written by examples/yade/triaxial.py) or one between
// walls of LAMMPS (corpus/import_walls_seed, examples/lammps/walls/run.sh), and which of its four
// files the rest of the bytes replace: import.toml, the atoms dump, the contacts dump or the
// series table (byte % 4; (byte / 4) % 2 the run).
// The run is then imported into a scratch run file. What the importer accepts, every reader after
// it must take: each snapshot read back with the run file's own check, its SFF input built.
#include <array>
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

const char* const kSeeds[] = {"import_seed", "import_walls_seed"};

std::string seed_text(const char* seed, const char* name) {
  const std::string path = std::string(SFFCAL_FUZZ_DIR) + "/corpus/" + seed + "/" + name;
  std::ifstream in(path);
  if (!in) sffcal_fuzz::finding("cannot read the seed file " + path);
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
  static const auto seeds = [] {
    std::array<std::array<std::string, 4>, 2> text;
    for (std::size_t run = 0; run < 2; ++run)
      for (std::size_t k = 0; k < 4; ++k) text[run][k] = seed_text(kSeeds[run], kFiles[k]);
    return text;
  }();
  const std::size_t replaced = data[0] % 4, run = (data[0] / 4) % 2;
  for (std::size_t k = 0; k < 4; ++k) {
    std::ofstream out(folder + "/" + kFiles[k], std::ios::binary | std::ios::trunc);
    if (k == replaced) out.write(reinterpret_cast<const char*>(data + 1), static_cast<std::streamsize>(size - 1));
    else out << seeds[run][k];
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
