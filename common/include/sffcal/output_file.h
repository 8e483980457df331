// A text output written whole or not at all, the one way the commands write their text files
// (CSV tables, VTK and ParaView files, parameter JSON, Markdown summaries): the text goes to a
// temporary file of a unique name beside PATH (sffcal/unique_name.h), which takes PATH's place
// (rename) only once every byte has been written. A failed write (a full disk, a file-size
// limit) throws naming PATH and removes the temporary file, so PATH is what it was before, never
// empty or cut short. PATH is then a new regular file: a symbolic link there is replaced, not
// followed, and the old file's permissions are not kept; PATH may not be a device or a FIFO.
#pragma once

#include <sys/stat.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <stdexcept>
#include <string>
#include <utility>

#include "sffcal/unique_name.h"

namespace sffcal {

class OutputFile {
 public:
  /// Opens the temporary file beside `path`. Throws std::runtime_error where `path` exists and
  /// is not a regular file (a device or a FIFO is never replaced) or the folder is not writable.
  explicit OutputFile(std::string path) : path_(std::move(path)) {
    struct stat status {};
    if (::stat(path_.c_str(), &status) == 0 && !S_ISREG(status.st_mode))
      throw std::runtime_error("cannot write " + path_ + ": it exists and is not a regular file");
    temporary_ = claim_unique_name(path_ + ".partial");
    out_.open(temporary_, std::ios::binary | std::ios::trunc);
    if (!out_) {
      std::remove(temporary_.c_str());
      throw std::runtime_error("cannot write " + path_);
    }
  }
  OutputFile(const OutputFile&) = delete;
  OutputFile& operator=(const OutputFile&) = delete;
  ~OutputFile() {
    if (temporary_.empty()) return;
    out_.close();
    std::remove(temporary_.c_str());
  }

  std::ostream& stream() { return out_; }

  /// Writes out what is buffered and puts the file in PATH's place; throws std::runtime_error
  /// naming PATH (left as it was) where any write failed.
  void commit() {
    out_.close();
    if (out_.fail()) {
      std::remove(temporary_.c_str());
      temporary_.clear();
      throw std::runtime_error("writing " + path_ +
                               " failed (disk full or write error); it was left as it was");
    }
    if (std::rename(temporary_.c_str(), path_.c_str()) != 0) {
      const std::string why = std::strerror(errno);
      std::remove(temporary_.c_str());
      temporary_.clear();
      throw std::runtime_error("cannot put " + path_ + " in place: " + why);
    }
    temporary_.clear();
  }

 private:
  std::string path_, temporary_;
  std::ofstream out_;
};

/// Writes `text` to `path` through an OutputFile.
inline void write_text_file(const std::string& path, const std::string& text) {
  OutputFile file(path);
  file.stream() << text;
  file.commit();
}

}  // namespace sffcal
