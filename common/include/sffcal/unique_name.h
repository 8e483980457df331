// A file name beside an output that no file holds, claimed by creating it empty with O_EXCL, so
// that two writers (two runs, or a run and a user's own file) never share it. The one way the
// commands name their temporary files (sffcal/output_file.h, the run file's PATH.partial-PID-N,
// the replacing run's PATH.replacing-PID-N).
#pragma once

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <stdexcept>
#include <string>

namespace sffcal {

/// STEM-PID-0, STEM-PID-1, ...: the first that no file holds, created empty (mode 0666 less the
/// umask). Throws std::runtime_error naming STEM where none can be created.
inline std::string claim_unique_name(const std::string& stem) {
  const std::string base = stem + "-" + std::to_string(::getpid()) + "-";
  for (int k = 0; k < 1000; ++k) {
    const std::string name = base + std::to_string(k);
    const int fd = ::open(name.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
    if (fd >= 0) {
      ::close(fd);
      return name;
    }
    if (errno != EEXIST)
      throw std::runtime_error("cannot create " + name + ": " + std::strerror(errno));
  }
  throw std::runtime_error("cannot create a file " + base + "N: the first 1000 names are taken");
}

}  // namespace sffcal
