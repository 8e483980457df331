// Times the SFF analysis of one snapshot: the statistics and SFF predictions, the checks of the
// assumptions, and the 200-resample bootstrap, at 1 thread and at all threads. Prints a table.
//
//   sff_analysis RUN.h5 [SNAPSHOT] [REPEATS]   (SNAPSHOT: index, default the last)
#include <omp.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <string>

#include "runfile/run_file.h"
#include "sff/analysis.h"
#include "sff/run_snapshot.h"

namespace {

// Best of `repeats` wall-clock times [s]: the least disturbed by other load.
double best_time(int repeats, const std::function<void()>& work) {
  double best = 1e300;
  for (int r = 0; r < repeats; ++r) {
    const auto start = std::chrono::steady_clock::now();
    work();
    best = std::min(best, std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
  }
  return best;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: %s RUN.h5 [SNAPSHOT] [REPEATS]\n", argv[0]);
    return 2;
  }
  try {
    const runfile::RunFile file = runfile::RunFile::open(argv[1]);
    if (file.num_snapshots() == 0) throw std::runtime_error(std::string(argv[1]) + " has no snapshot");
    const int index = argc > 2 ? std::atoi(argv[2]) : file.num_snapshots() - 1;
    const int repeats = argc > 3 ? std::atoi(argv[3]) : 5;
    const runfile::Snapshot snapshot = file.read_snapshot(index);
    const sff::SnapshotInput input = sff::snapshot_input(snapshot, file.metadata().physics);
    std::printf("%s snapshot %d: %zu bodies, %zu contacts (%zu body-body), axial strain %.3f\n",
                argv[1], index, snapshot.particles.size(), snapshot.contacts.size(),
                sff::count_body_contacts(input.contacts), snapshot.axial_strain);

    const sff::SnapshotAnalysis analysis = sff::analyse_snapshot(input);
    sff::CheckOptions no_bootstrap;
    no_bootstrap.resamples = 0;
    const int threads = omp_get_max_threads();
    std::printf("\n| stage | threads | seconds (best of %d) |\n|---|---|---|\n", repeats);
    for (int t : {1, threads}) {
      omp_set_num_threads(t);
      const double stats = best_time(repeats, [&] { sff::analyse_snapshot(input); });
      const double checks = best_time(repeats, [&] { sff::check_snapshot(input, analysis, no_bootstrap); });
      const double total = best_time(repeats, [&] { sff::check_snapshot(input, sff::analyse_snapshot(input)); });
      std::printf("| statistics + SFF predictions | %d | %.4f |\n", t, stats);
      std::printf("| checks without bootstrap | %d | %.4f |\n", t, checks);
      std::printf("| bootstrap (200 resamples) | %d | %.4f |\n", t, total - stats - checks);
      std::printf("| whole snapshot | %d | %.4f |\n", t, total);
      if (threads == 1) break;
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "sff_analysis: error: %s\n", e.what());
    return 1;
  }
  return 0;
}
