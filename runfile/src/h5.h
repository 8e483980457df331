// Internal: a thin RAII layer over the HDF5 C API for the run file. Every failure becomes a
// std::runtime_error naming the object; run_file.cc turns those into messages for the caller.
#pragma once

#include <hdf5.h>

#include <cstddef>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

namespace runfile::h5 {

/// Owns one HDF5 identifier and closes it with the matching H5?close.
class Handle {
 public:
  Handle() = default;
  explicit Handle(hid_t id) : id_(id) {}
  Handle(const Handle&) = delete;
  Handle& operator=(const Handle&) = delete;
  Handle(Handle&& other) noexcept : id_(std::exchange(other.id_, -1)) {}
  Handle& operator=(Handle&& other) noexcept {
    if (this != &other) {
      reset();
      id_ = std::exchange(other.id_, -1);
    }
    return *this;
  }
  ~Handle() { reset(); }
  hid_t get() const { return id_; }
  bool valid() const { return id_ >= 0; }
  void reset();

 private:
  hid_t id_ = -1;
};

/// Throws std::runtime_error(what) when id < 0; returns the id wrapped.
Handle check(hid_t id, const std::string& what);
void check_status(herr_t status, const std::string& what);

/// Silences HDF5's own error printing (we report errors ourselves).
void silence_errors();

/// The file-access properties of a file written during a run that may be killed at any moment
/// (docs/run-file.md, "A killed run"): metadata reaches the disk only at H5Fflush, never by an
/// eviction between flushes, so the file on disk stays the one of the last flush until the next.
Handle crash_safe_access_properties();
/// The file-creation properties to go with them: the root group's name heap sized for its links
/// and symbol-table leaves of 128 entries, so that linking a checkpoint, a summary or up to 128
/// snapshots into an existing group changes it in place instead of moving it (a moved heap or a
/// split node written before the superblock was a kill's last open window).
Handle crash_safe_creation_properties();

bool exists(hid_t location, const std::string& path);
Handle open_group(hid_t location, const std::string& path);
Handle create_group(hid_t location, const std::string& path);
/// A group whose name heap has room for `expected_links` links of up to 15 characters.
Handle create_group(hid_t location, const std::string& path, std::size_t expected_links);
/// A group no path leads to yet: written and flushed whole before `link` makes it reachable.
Handle create_unlinked_group(hid_t file);
/// Links `object` at `path` under `location`, creating the missing intermediate groups.
void link(hid_t object, hid_t location, const std::string& path);

void write_attribute(hid_t object, const std::string& name, const std::string& value);
void write_attribute(hid_t object, const std::string& name, double value);
void write_attribute(hid_t object, const std::string& name, std::int64_t value);
std::string read_string_attribute(hid_t object, const std::string& name);
double read_double_attribute(hid_t object, const std::string& name);
std::int64_t read_int_attribute(hid_t object, const std::string& name);

/// A chunked, shuffled and deflated dataset of `rows` x `cols` elements of `type` (cols = 0: a
/// 1-D dataset), written from `data` in row-major order.
void write_dataset(hid_t location, const std::string& name, hid_t type, const void* data,
                   std::size_t rows, std::size_t cols = 0);
/// Reads a whole dataset of `type`; returns the number of rows and sets `cols` (0 for 1-D).
template <typename T>
std::vector<T> read_dataset(hid_t location, const std::string& name, hid_t type,
                            std::size_t* cols = nullptr);

/// Rows of an extendible dataset's chunk: an append that starts a chunk allocates this many.
inline constexpr std::size_t kExtendibleChunkRows = 1024;

/// The file descriptor under a file of HDF5's default (sec2) driver, or -1 under another driver
/// (whose handle is not a descriptor). Looked up once per file: it copies the access properties.
int file_descriptor(hid_t file);

/// Allocates `bytes` of disk from the file's end of allocation (posix_fallocate on its descriptor
/// `fd`; nothing where fd < 0), so that the
/// writes and the flush that follow cannot meet a full disk halfway, which leaves a file HDF5
/// cannot open. Throws std::runtime_error ("no room on the disk ...") where the disk or the
/// quota has not that much. Where the file system has no fallocate, glibc writes a byte per block
/// instead (slower, as sure); a copy-on-write file system (ZFS, btrfs) may still fail a later
/// overwrite; a driver other than HDF5's default is left as it is.
void reserve_space(hid_t file, int fd, std::uint64_t bytes);
/// Gives back what reserve_space allocated beyond the end of allocation (after a flush).
void release_space(hid_t file, int fd);

/// An extendible 1-D dataset of doubles (unlimited length, chunked, not compressed: a compressed
/// chunk moves in the file each time it grows, and a kill between the move and the next flush
/// left it unreadable).
void create_extendible(hid_t location, const std::string& name);
void append(hid_t location, const std::string& name, double value);
std::size_t length(hid_t location, const std::string& name);
/// Shrinks an extendible dataset to `rows` (used when resuming from a checkpoint).
void truncate(hid_t location, const std::string& name, std::size_t rows);

/// HDF5 compound types laid out exactly like the record structs.
Handle particle_record_type();
Handle contact_record_type();
Handle wall_record_type();

}  // namespace runfile::h5
