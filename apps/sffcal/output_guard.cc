#include "output_guard.h"

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <stdexcept>
#include <system_error>
#include <utility>

#include "sffcal/unique_name.h"

namespace sffcal {
namespace {

namespace fs = std::filesystem;

// Whether a file can be created in `folder`, found by creating (and removing) one: access(2)
// answers yes to root on any folder, and no permission bit shows a read-only mount, a full quota or
// a file system such as /proc that takes no new files.
bool writable_folder(const fs::path& folder) {
  std::error_code error;
  if (!fs::is_directory(folder, error)) return false;
  const fs::path probe = folder / (".sffcal-write-probe-" + std::to_string(::getpid()));
  const int fd = ::open(probe.c_str(), O_CREAT | O_EXCL | O_WRONLY | O_CLOEXEC, 0600);
  if (fd < 0) return false;
  ::close(fd);
  ::unlink(probe.c_str());
  return true;
}

// The folder a new entry at `path` would be created in ("." for a bare name).
fs::path parent_of(const fs::path& path) {
  const fs::path parent = path.parent_path();
  return parent.empty() ? fs::path(".") : parent;
}

constexpr const char* kReplacing = ".replacing";

}  // namespace

void check_new_output_file(const std::string& path, const std::vector<std::string>& inputs,
                           bool force) {
  std::error_code error;
  for (const std::string& input : inputs) {
    if (!input.empty() && fs::equivalent(path, input, error))
      throw std::runtime_error("output '" + path + "' is also an input of this command ('" +
                               input + "'): choose another output");
  }
  if (fs::exists(path, error)) {
    if (fs::is_directory(path, error))
      throw std::runtime_error("output '" + path + "' is a folder, not a file");
    if (!force)
      throw std::runtime_error("output '" + path +
                               "' exists: pass --force to overwrite it, or choose another output");
    if (::access(path.c_str(), W_OK) != 0)
      throw std::runtime_error("output '" + path + "' exists and is not writable");
    return;
  }
  const fs::path folder = parent_of(path);
  if (!fs::exists(folder, error))
    throw std::runtime_error("the folder of output '" + path + "' ('" + folder.string() +
                             "') does not exist");
  if (!writable_folder(folder))
    throw std::runtime_error("the folder of output '" + path + "' ('" + folder.string() +
                             "') is not a writable folder");
}

void check_new_run_file(const std::string& path, const std::vector<std::string>& inputs,
                        bool force, bool with_series) {
  // The files made beside it (PATH.partial-PID-N, PATH.replacing-PID-N) have names no file holds.
  std::vector<std::string> outputs = {path};
  if (with_series) outputs.push_back(path + ".series.csv");
  for (const std::string& output : outputs) {
    check_new_output_file(output, inputs, force);
    // A run file is made beside its name and renamed over it: only a regular file is ever
    // replaced (--force renamed a new file over /dev/null before).
    std::error_code error;
    if (fs::exists(output, error) && !fs::is_regular_file(output, error))
      throw std::runtime_error("output '" + output +
                               "' is not a regular file (a device, FIFO or socket): it is never "
                               "replaced; choose another output");
  }
}

RunFileTarget::RunFileTarget(std::string path, bool with_series)
    : path_(std::move(path)), with_series_(with_series) {
  std::error_code error;
  replaces_ = fs::exists(path_, error);
}

void RunFileTarget::make(const std::function<void(const std::string&)>& write) const {
  // Claimed only now, when the work begins: a command refused before leaves no name behind.
  const std::string working = replaces_ ? claim_unique_name(path_ + kReplacing) : path_;
  try {
    write(working);
  } catch (const std::exception& e) {
    if (!replaces_) throw;
    std::error_code error;
    // Claimed and no run file made there, or the writer removed what it made (an import).
    if (!fs::exists(working, error) || fs::is_empty(working, error)) {
      fs::remove(working, error);
      throw std::runtime_error(std::string(e.what()) + "\n  (the existing '" + path_ +
                               "' is kept as it was)");
    }
    throw std::runtime_error(std::string(e.what()) + "\n  (the existing '" + path_ +
                             "' is kept as it was; this run's file is '" + working + "')");
  }
  if (!replaces_) return;
  std::vector<std::pair<std::string, std::string>> moves = {{working, path_}};
  if (with_series_) moves.emplace_back(working + ".series.csv", path_ + ".series.csv");
  for (const auto& [from, to] : moves) {
    std::error_code error;
    fs::rename(from, to, error);
    if (error)
      throw std::runtime_error("the new run is complete in '" + from + "' but could not replace '" +
                               to + "': " + error.message());
  }
  std::printf("moved %s over the earlier %s%s\n", working.c_str(), path_.c_str(),
              with_series_ ? " (and its series CSV)" : "");
}

void check_inputs_outside(const std::string& folder, const std::vector<std::string>& inputs) {
  std::error_code error;
  fs::path out = fs::weakly_canonical(folder, error);
  if (error) return;
  if (!out.has_filename()) out = out.parent_path();  // "fe/" ends in an empty component
  for (const std::string& input : inputs) {
    const fs::path in = fs::weakly_canonical(input, error);
    if (error) continue;
    const auto [end, rest] = std::mismatch(out.begin(), out.end(), in.begin(), in.end());
    if (end == out.end())
      throw std::runtime_error("input '" + input + "' lies in the output folder '" + folder +
                               "', whose files this command writes: move it or choose another "
                               "folder");
  }
}

void check_output_folder(const std::string& folder) {
  std::error_code error;
  fs::path existing = folder;
  if (fs::exists(existing, error)) {
    if (!writable_folder(existing))
      throw std::runtime_error("output folder '" + folder + "' is not a writable folder");
    return;
  }
  // It will be created: its nearest existing ancestor must be a writable folder.
  while (!existing.empty() && !fs::exists(existing, error)) existing = existing.parent_path();
  if (existing.empty()) existing = ".";
  if (!writable_folder(existing))
    throw std::runtime_error("output folder '" + folder + "' cannot be created: '" +
                             existing.string() + "' is not a writable folder");
}

}  // namespace sffcal
