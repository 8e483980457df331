// What a command checks about its outputs before it starts any work (issue 17): an existing file
// is not overwritten unless the user asked (--force), an output is never one of the command's
// inputs, and the folder it goes to exists and is writable; a write that failed is reported.
#pragma once

#include <functional>
#include <ostream>
#include <string>
#include <vector>

namespace sffcal {

/// Throws std::runtime_error naming the path: `path` is one of `inputs` (the same file, however
/// spelled), or exists and `force` is false, or its folder is missing or not writable.
void check_new_output_file(const std::string& path, const std::vector<std::string>& inputs,
                           bool force);

/// The same for a run file and, for a test (`with_series`), its series CSV; and neither may be
/// anything but a regular file, even with `force` (a rename would replace a device or FIFO). The
/// files made beside them (PATH.partial-PID-N, where a run file is made before it is renamed to
/// PATH; PATH.replacing-PID-N, where a run that replaces one is made) take names no file holds.
void check_new_run_file(const std::string& path, const std::vector<std::string>& inputs,
                        bool force, bool with_series);

/// Where a run file that may replace an existing one is made: at its path when none is there,
/// else at PATH.replacing-PID-N (with its series CSV beside it), moved over PATH by make() once
/// the run is complete, so that --force never destroys a good run before the new one is whole.
/// A run that fails leaves PATH as it was and names its own file.
class RunFileTarget {
 public:
  /// `path` must have passed check_new_run_file (with the same `with_series`).
  RunFileTarget(std::string path, bool with_series);
  const std::string& path() const { return path_; }
  /// Calls write(the path to make the run at) and then moves the finished run (and its series
  /// CSV) over the old one. A failure is rethrown as std::runtime_error saying that PATH is kept
  /// and where the failed run is.
  void make(const std::function<void(const std::string&)>& write) const;

 private:
  std::string path_;
  bool replaces_;  ///< PATH existed when the target was made
  bool with_series_;
};

/// Throws std::runtime_error naming the input that lies in `folder`, whose files a command writes
/// (fe-check's summary.csv given as its parameter file was overwritten before).
void check_inputs_outside(const std::string& folder, const std::vector<std::string>& inputs);

/// Throws std::runtime_error naming the path when `folder` exists but is not a writable folder,
/// or does not exist and cannot be created because its nearest existing parent is not writable.
void check_output_folder(const std::string& folder);

}  // namespace sffcal
