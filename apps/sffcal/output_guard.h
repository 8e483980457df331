// What a command checks about its outputs before it starts any work (issue 17): an existing file
// is not overwritten unless the user asked (--force), an output is never one of the command's
// inputs, and the folder it goes to exists and is writable; a write that failed is reported.
#pragma once

#include <ostream>
#include <string>
#include <vector>

namespace sffcal {

/// Throws std::runtime_error naming the path: `path` is one of `inputs` (the same file, however
/// spelled), or exists and `force` is false, or its folder is missing or not writable.
void check_new_output_file(const std::string& path, const std::vector<std::string>& inputs,
                           bool force);

/// Throws std::runtime_error naming the path when `folder` exists but is not a writable folder,
/// or does not exist and cannot be created because its nearest existing parent is not writable.
void check_output_folder(const std::string& folder);

/// Flushes `out` and throws std::runtime_error naming `path` if any write to it failed (a full
/// disk, /dev/full).
void check_written(std::ostream& out, const std::string& path);

}  // namespace sffcal
