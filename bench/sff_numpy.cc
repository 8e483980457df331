// The SFF analysis of one snapshot timed in C++ (sff::analyse_snapshot), the reference of the
// Python API's (bench/python/sff_numpy.py writes the contacts as raw records, runs both alternated
// on them and compares). The analysis checks its input as it does for the binding.
//
//   build/bench/sff_numpy CONTACTS.bin BODIES VOLUME SOLID_VOLUME E MU REPEATS   # one time [s] a line
#include <chrono>
#include <cstdio>
#include <exception>
#include <fstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "runfile/records.h"
#include "sff/analysis.h"

int main(int argc, char** argv) {
  if (argc != 8) {
    std::fprintf(stderr, "usage: sff_numpy CONTACTS.bin BODIES VOLUME SOLID_VOLUME E MU REPEATS\n");
    return 2;
  }
  try {
    std::ifstream file(argv[1], std::ios::binary | std::ios::ate);
    if (!file) throw std::runtime_error(std::string("cannot read ") + argv[1]);
    const std::streamsize bytes = file.tellg();
    if (bytes % static_cast<std::streamsize>(sizeof(runfile::ContactRecord)) != 0)
      throw std::runtime_error(std::string(argv[1]) + " is not a whole number of contact records");
    std::vector<runfile::ContactRecord> contacts(static_cast<std::size_t>(bytes) /
                                                 sizeof(runfile::ContactRecord));
    file.seekg(0);
    file.read(reinterpret_cast<char*>(contacts.data()), bytes);
    sff::SnapshotInput in;
    in.contacts = sff::ContactSpan(contacts);
    in.num_bodies = std::stoi(argv[2]);
    in.volume = std::stod(argv[3]);
    in.solid_volume = std::stod(argv[4]);
    in.youngs_modulus = std::stod(argv[5]);
    in.friction = std::stod(argv[6]);
    double eta = 0.0;
    for (int r = 0, repeats = std::stoi(argv[7]); r < repeats; ++r) {
      const auto t0 = std::chrono::steady_clock::now();
      eta = sff::analyse_snapshot(in).eta_sff;
      std::printf("%.6f\n",
                  std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
    }
    std::printf("eta_sff %.17g\n", eta);  // the script compares it with its own
  } catch (const std::exception& e) {
    std::fprintf(stderr, "sff_numpy: %s\n", e.what());
    return 1;
  }
  return 0;
}
