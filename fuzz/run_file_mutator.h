// Structure-aware edits of a run file, for the fuzz targets of its readers (fuzz/README.md).
// Raw bytes given to HDF5 would mostly fuzz libhdf5, which is not this project's code; instead the
// bytes choose edits of a valid seed run file through the HDF5 API, so that the file stays
// well-formed HDF5 while its content becomes damaged or hostile:
//   a value of a dataset (an element, a member of a record, a component) or of a numeric
//   attribute set to NaN, an infinity, a huge, negative or zero number, or off by one;
//   a dataset shrunk, grown (rows repeated or zero), reshaped, retyped (another number type, a
//   record without one of its members, text) or removed; all the datasets of its group with its
//   row count resized together (the arrays of one checkpoint or snapshot stay consistent with
//   each other and wrong as a whole);
//   a text attribute cut, extended or replaced, any attribute retyped or removed;
//   a group removed, or given an extra member (a group, a dataset, a link back to itself).
#pragma once

#include <fuzzer/FuzzedDataProvider.h>

#include <string>
#include <vector>

namespace sffcal_fuzz {

class RunFileMutator {
 public:
  /// Reads the seed file and lists its groups, datasets and attributes.
  explicit RunFileMutator(const std::string& seed_path);

  /// Writes the seed to `path` with up to kMaxEdits edits chosen by `bytes` (none where they are
  /// used up). Where `focus` is not empty, objects whose path begins with it are chosen three
  /// times in four. Returns one line per edit (verbose output, reproducing a finding).
  std::vector<std::string> write(const std::string& path, FuzzedDataProvider& bytes,
                                 const std::string& focus = "") const;

  static constexpr int kMaxEdits = 6;

 private:
  struct Object {
    std::string path;       ///< of the group or dataset
    std::string attribute;  ///< empty: the object itself
    bool dataset = false;
  };
  std::string seed_;
  std::vector<Object> objects_;
};

}  // namespace sffcal_fuzz
