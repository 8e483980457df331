// What every fuzz target shares (fuzz/README.md): the one oracle of a reader (it reads, or it
// throws a std::exception with a message; a crash, a sanitizer report, a hang or an exception of
// another kind is a finding) and the scratch file a reader that takes a path is given.
#pragma once

#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <fstream>
#include <string>
#include <system_error>

namespace sffcal_fuzz {

/// SFFCAL_FUZZ_VERBOSE set (and not "0"): the targets print what each reader said, and the
/// structure-aware ones each edit, for replaying a reproducer by hand.
inline bool verbose() {
  static const bool on = [] {
    const char* v = std::getenv("SFFCAL_FUZZ_VERBOSE");
    return v && *v && std::string(v) != "0";
  }();
  return on;
}

/// Runs one reader: success and a std::exception are both fine (the message is printed when
/// verbose). Any other exception escapes, reaches std::terminate and is reported as a crash.
template <typename Reader>
void refused_or_read(const char* what, Reader&& reader) {
  try {
    reader();
    if (verbose()) std::fprintf(stderr, "  %s: read\n", what);
  } catch (const std::exception& e) {
    if (verbose()) std::fprintf(stderr, "  %s: refused: %s\n", what, e.what());
  }
}

/// A finding that is neither a crash nor a sanitizer report (e.g. a reader accepted what the
/// code after it cannot use): printed, then abort(), which libFuzzer reports as a crash and keeps
/// the input.
[[noreturn]] inline void finding(const std::string& what) {
  std::fprintf(stderr, "sffcal fuzz finding: %s\n", what.c_str());
  std::abort();
}

/// SFFCAL_FUZZ_EDITED=PATH: the structure-aware targets copy the file they edited there before
/// reading it (then `sffcal info PATH`, `sffcal triaxial --resume -o PATH`, ... reproduce a
/// finding with the command line).
inline void keep_edited_copy(const std::string& path) {
  const char* copy = std::getenv("SFFCAL_FUZZ_EDITED");
  if (!copy || !*copy) return;
  std::error_code error;
  std::filesystem::copy_file(path, copy, std::filesystem::copy_options::overwrite_existing, error);
  if (error) std::fprintf(stderr, "cannot copy %s to %s: %s\n", path.c_str(), copy, error.message().c_str());
}

/// A scratch file of this process for the readers that take a path: in /dev/shm where there is
/// one (no disk writes at every input), removed at exit.
class ScratchFile {
 public:
  explicit ScratchFile(const std::string& name) {
    std::error_code error;
    const std::filesystem::path dir =
        std::filesystem::is_directory("/dev/shm", error) && access("/dev/shm", W_OK) == 0
            ? std::filesystem::path("/dev/shm")
            : std::filesystem::temp_directory_path();
    path_ = (dir / ("sffcal_fuzz_" + std::to_string(getpid()) + "_" + name)).string();
  }
  ScratchFile(const ScratchFile&) = delete;
  ScratchFile& operator=(const ScratchFile&) = delete;
  ~ScratchFile() { std::remove(path_.c_str()); }
  const std::string& path() const { return path_; }
  /// Replaces the file's content with `size` bytes at `data`.
  void write(const void* data, std::size_t size) const {
    std::ofstream out(path_, std::ios::binary | std::ios::trunc);
    out.write(static_cast<const char*>(data), static_cast<std::streamsize>(size));
    if (!out) finding("cannot write the scratch file " + path_);
  }

 private:
  std::string path_;
};

}  // namespace sffcal_fuzz
