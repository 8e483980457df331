// A text input read whole, from a regular file of bounded size: a device (/dev/zero, a FIFO) or a
// file larger than the reader expects is refused by name instead of filling the memory.
#pragma once

#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>

namespace sffcal {

/// The text of `path`; throws std::invalid_argument naming `what` and the path where it is not a
/// regular file, is larger than max_bytes, or cannot be read.
inline std::string read_text_file(const std::string& path, std::uintmax_t max_bytes,
                                  const std::string& what) {
  std::error_code error;
  const std::filesystem::file_status status = std::filesystem::status(path, error);
  if (error || !std::filesystem::exists(status))
    throw std::invalid_argument("cannot read the " + what + " " + path + ": no such file");
  if (!std::filesystem::is_regular_file(status))
    throw std::invalid_argument("the " + what + " " + path +
                                " is not a regular file (a device, FIFO or folder)");
  const std::uintmax_t size = std::filesystem::file_size(path, error);
  if (error) throw std::invalid_argument("cannot read the " + what + " " + path);
  if (size > max_bytes)
    throw std::invalid_argument("the " + what + " " + path + " has " + std::to_string(size) +
                                " bytes, more than the " + std::to_string(max_bytes) +
                                " such a file can hold");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::invalid_argument("cannot read the " + what + " " + path);
  std::ostringstream buffer;
  buffer << in.rdbuf();
  if (in.bad()) throw std::invalid_argument("cannot read the " + what + " " + path);
  return buffer.str();
}

}  // namespace sffcal
