#include "run_file_mutator.h"

#include <hdf5.h>

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <iterator>
#include <sstream>
#include <stdexcept>

#include "fuzz_support.h"
#include "h5.h"  // runfile/src: the run file's own RAII handles and attribute helpers
#include "special_values.h"

namespace sffcal_fuzz {
namespace {

using runfile::h5::check;
using runfile::h5::check_status;
using runfile::h5::Handle;

// No edit makes a dataset larger than this (a grown array, not a memory test).
constexpr std::size_t kMaxDatasetBytes = std::size_t{4} << 20;

std::string parent_of(const std::string& path) {
  const std::size_t slash = path.rfind('/');
  return slash == 0 || slash == std::string::npos ? "/" : path.substr(0, slash);
}

// ---- numbers ----

// Sets the number at `at` (of the native `type`) to a special value: for a record one member, for
// an array one component, as the bytes choose. Returns what was set, e.g. ".position[1] = nan".
std::string patch(unsigned char* at, hid_t type, FuzzedDataProvider& bytes) {
  switch (H5Tget_class(type)) {
    case H5T_COMPOUND: {
      const int members = H5Tget_nmembers(type);
      if (members <= 0) return " (an empty record)";
      const unsigned k = bytes.ConsumeIntegralInRange<unsigned>(0, static_cast<unsigned>(members - 1));
      const Handle member = check(H5Tget_member_type(type, k), "get a member type");
      char* name = H5Tget_member_name(type, k);
      const std::string label = "." + std::string(name ? name : "?");
      H5free_memory(name);
      return label + patch(at + H5Tget_member_offset(type, k), member.get(), bytes);
    }
    case H5T_ARRAY: {
      const Handle base = check(H5Tget_super(type), "get an array's base type");
      const std::size_t base_size = H5Tget_size(base.get());
      const std::size_t count = base_size ? H5Tget_size(type) / base_size : 0;
      if (count == 0) return " (an empty array)";
      const std::size_t k = bytes.ConsumeIntegralInRange<std::size_t>(0, count - 1);
      return "[" + std::to_string(k) + "]" + patch(at + k * base_size, base.get(), bytes);
    }
    case H5T_FLOAT: {
      std::ostringstream said;
      if (H5Tget_size(type) == sizeof(double)) {
        double v;
        std::memcpy(&v, at, sizeof v);
        v = special_real(bytes, v);
        std::memcpy(at, &v, sizeof v);
        said << " = " << v;
      } else if (H5Tget_size(type) == sizeof(float)) {
        float v;
        std::memcpy(&v, at, sizeof v);
        v = static_cast<float>(special_real(bytes, v));
        std::memcpy(at, &v, sizeof v);
        said << " = " << v;
      }
      return said.str();
    }
    case H5T_INTEGER: {
      const std::size_t size = std::min<std::size_t>(H5Tget_size(type), 8);
      const bool is_signed = H5Tget_sign(type) == H5T_SGN_2;
      std::uint64_t raw = 0;
      std::memcpy(&raw, at, size);  // native, little-endian: the low bytes
      if (is_signed && size < 8 && (raw >> (8 * size - 1)) != 0) raw |= ~std::uint64_t{0} << (8 * size);
      const std::int64_t v = special_integer(bytes, static_cast<std::int64_t>(raw));
      std::memcpy(at, &v, size);
      return " = " + std::to_string(v) + " (" + std::to_string(size) + " bytes)";
    }
    default:
      return " (not a number: kept)";
  }
}

// ---- datasets ----

// A dataset's whole content in its native type.
struct Contents {
  Handle file_type, memory_type;
  std::vector<hsize_t> dims;
  std::size_t element_size = 0;
  std::vector<unsigned char> bytes;
  bool extendible = false;  // chunked with an unlimited first dimension (a /series column)

  std::size_t points() const { return element_size ? bytes.size() / element_size : 0; }
  std::size_t row_bytes() const {
    std::size_t n = element_size;
    for (std::size_t k = 1; k < dims.size(); ++k) n *= dims[k];
    return n;
  }
};

Contents read_contents(hid_t file, const std::string& path) {
  const Handle set = check(H5Dopen2(file, path.c_str(), H5P_DEFAULT), "open " + path);
  Contents c;
  c.file_type = check(H5Dget_type(set.get()), "get the type of " + path);
  c.memory_type = check(H5Tget_native_type(c.file_type.get(), H5T_DIR_ASCEND), "native type");
  if (H5Tdetect_class(c.memory_type.get(), H5T_VLEN) > 0 || H5Tis_variable_str(c.memory_type.get()) > 0)
    throw std::runtime_error(path + " holds variable-length data (not edited)");
  const Handle space = check(H5Dget_space(set.get()), "get the dataspace of " + path);
  const int rank = H5Sget_simple_extent_ndims(space.get());
  c.dims.assign(static_cast<std::size_t>(std::max(rank, 0)), 0);
  std::vector<hsize_t> max_dims(c.dims.size(), 0);
  H5Sget_simple_extent_dims(space.get(), c.dims.data(), max_dims.data());
  c.element_size = H5Tget_size(c.memory_type.get());
  const hssize_t points = H5Sget_simple_extent_npoints(space.get());
  c.bytes.resize(static_cast<std::size_t>(std::max<hssize_t>(points, 0)) * c.element_size);
  if (!c.bytes.empty())
    check_status(H5Dread(set.get(), c.memory_type.get(), H5S_ALL, H5S_ALL, H5P_DEFAULT,
                         c.bytes.data()),
                 "read " + path);
  const Handle create = check(H5Dget_create_plist(set.get()), "get the creation properties");
  c.extendible = H5Pget_layout(create.get()) == H5D_CHUNKED && !max_dims.empty() &&
                 max_dims[0] == H5S_UNLIMITED;
  return c;
}

// Replaces the dataset at `path` with one of `file_type` and `dims` written from `data` (in
// `memory_type`); extendible ones stay chunked with an unlimited first dimension. An empty `dims`
// makes a scalar dataset.
void replace_dataset(hid_t file, const std::string& path, hid_t file_type, hid_t memory_type,
                     const std::vector<hsize_t>& dims, const void* data, bool extendible) {
  if (H5Lexists(file, path.c_str(), H5P_DEFAULT) > 0)
    check_status(H5Ldelete(file, path.c_str(), H5P_DEFAULT), "unlink " + path);
  std::vector<hsize_t> max_dims = dims, chunk = dims;
  bool chunked = extendible && !dims.empty();
  for (std::size_t k = 1; k < dims.size(); ++k) chunked = chunked && dims[k] > 0;
  if (chunked) {
    max_dims[0] = H5S_UNLIMITED;
    chunk[0] = 8;
  }
  const Handle space = dims.empty() ? check(H5Screate(H5S_SCALAR), "create a scalar dataspace")
                                    : check(H5Screate_simple(static_cast<int>(dims.size()),
                                                             dims.data(), max_dims.data()),
                                            "create a dataspace");
  const Handle create = check(H5Pcreate(H5P_DATASET_CREATE), "create a property list");
  if (chunked) check_status(H5Pset_chunk(create.get(), static_cast<int>(chunk.size()), chunk.data()), "chunk");
  const Handle set = check(H5Dcreate2(file, path.c_str(), file_type, space.get(), H5P_DEFAULT,
                                      create.get(), H5P_DEFAULT),
                           "create " + path);
  if (H5Sget_simple_extent_npoints(space.get()) > 0)
    check_status(H5Dwrite(set.get(), memory_type, H5S_ALL, H5S_ALL, H5P_DEFAULT, data),
                 "write " + path);
}

// How new rows are filled: zeros, or copies of one existing row.
struct RowFill {
  bool copy = false;
  std::size_t source = 0;
};

// Resizes the first dimension of the dataset at `path` to `rows`.
std::string resize_rows(hid_t file, const std::string& path, std::size_t rows, RowFill fill) {
  Contents c = read_contents(file, path);
  if (c.dims.empty()) return path + ": scalar, not resized";
  const std::size_t row = c.row_bytes(), old_rows = c.dims[0];
  if (row != 0 && rows > kMaxDatasetBytes / row) rows = kMaxDatasetBytes / row;
  std::vector<unsigned char> data(rows * row, 0);
  std::copy_n(c.bytes.begin(), std::min(rows, old_rows) * row, data.begin());
  if (fill.copy && old_rows > 0) {
    const std::size_t source = std::min(fill.source, old_rows - 1);
    for (std::size_t r = old_rows; r < rows; ++r)
      std::copy_n(c.bytes.begin() + static_cast<std::ptrdiff_t>(source * row), row,
                  data.begin() + static_cast<std::ptrdiff_t>(r * row));
  }
  c.dims[0] = rows;
  replace_dataset(file, path, c.file_type.get(), c.memory_type.get(), c.dims, data.data(),
                  c.extendible);
  return path + ": " + std::to_string(old_rows) + " -> " + std::to_string(rows) + " rows" +
         (fill.copy && rows > old_rows ? " (copies of row " + std::to_string(fill.source) + ")" : "");
}

std::size_t new_row_count(FuzzedDataProvider& bytes, std::size_t rows) {
  switch (bytes.ConsumeIntegralInRange(0, 6)) {
    case 0: return 0;
    case 1: return rows > 0 ? rows - 1 : 1;
    case 2: return rows + 1;
    case 3: return rows / 2;
    case 4: return 2 * rows + 1;
    case 5: return 1;
    default: return bytes.ConsumeIntegralInRange<std::size_t>(0, rows + 64);
  }
}

// The datasets directly in `group`.
std::vector<std::string> datasets_in(hid_t file, const std::string& group) {
  std::vector<std::string> names;
  const Handle g = check(H5Gopen2(file, group.c_str(), H5P_DEFAULT), "open " + group);
  H5Literate(
      g.get(), H5_INDEX_NAME, H5_ITER_INC, nullptr,
      [](hid_t location, const char* name, const H5L_info_t*, void* out) -> herr_t {
        H5O_info_t info;
        if (H5Oget_info_by_name2(location, name, &info, H5O_INFO_BASIC, H5P_DEFAULT) >= 0 &&
            info.type == H5O_TYPE_DATASET)
          static_cast<std::vector<std::string>*>(out)->push_back(name);
        return 0;
      },
      &names);
  return names;
}

std::string edit_value(hid_t file, const std::string& path, FuzzedDataProvider& bytes) {
  Contents c = read_contents(file, path);
  if (c.points() == 0) return path + ": empty, no value to set";
  const std::size_t k = bytes.ConsumeIntegralInRange<std::size_t>(0, c.points() - 1);
  const std::string said = patch(c.bytes.data() + k * c.element_size, c.memory_type.get(), bytes);
  const Handle set = check(H5Dopen2(file, path.c_str(), H5P_DEFAULT), "open " + path);
  check_status(H5Dwrite(set.get(), c.memory_type.get(), H5S_ALL, H5S_ALL, H5P_DEFAULT,
                        c.bytes.data()),
               "write " + path);
  return path + "[" + std::to_string(k) + "]" + said;
}

std::string resize_group(hid_t file, const std::string& path, FuzzedDataProvider& bytes) {
  const Contents c = read_contents(file, path);
  if (c.dims.empty()) return path + ": scalar, not resized";
  const std::size_t old_rows = c.dims[0], rows = new_row_count(bytes, old_rows);
  RowFill fill;
  fill.copy = bytes.ConsumeBool();
  fill.source = bytes.ConsumeIntegralInRange<std::size_t>(0, old_rows > 0 ? old_rows - 1 : 0);
  const std::string group = parent_of(path);
  std::string said = "the datasets of " + group + " with " + std::to_string(old_rows) + " rows:";
  for (const std::string& name : datasets_in(file, group)) {
    const std::string member = (group == "/" ? "/" : group + "/") + name;
    const Contents m = read_contents(file, member);
    if (!m.dims.empty() && m.dims[0] == old_rows) said += " " + resize_rows(file, member, rows, fill) + ";";
  }
  return said;
}

// A new rank or number of columns, the elements laid out again row by row (padded with zeros).
std::string reshape(hid_t file, const std::string& path, FuzzedDataProvider& bytes) {
  Contents c = read_contents(file, path);
  std::vector<hsize_t> dims;
  const std::size_t rows = c.dims.empty() ? 1 : c.dims[0];
  const std::size_t columns = c.dims.size() >= 2 ? c.dims[1] : 1;
  switch (bytes.ConsumeIntegralInRange(0, 4)) {
    case 0: dims = {rows, columns > 1 ? columns - 1 : 2}; break;
    case 1: dims = {rows, columns + 1}; break;
    case 2: dims = {c.points()}; break;  // flattened
    case 3: dims = {rows, columns, 1}; break;  // rank 3
    default: break;  // scalar
  }
  std::size_t points = 1;
  for (hsize_t d : dims) points *= d;
  if (points * c.element_size > kMaxDatasetBytes) return path + ": not reshaped (too large)";
  std::vector<unsigned char> data(points * c.element_size, 0);
  const std::size_t new_columns = dims.size() >= 2 ? dims[1] : points;
  if (dims.size() >= 2) {
    for (std::size_t r = 0; r < rows; ++r)
      for (std::size_t k = 0; k < std::min(columns, new_columns); ++k)
        std::copy_n(c.bytes.begin() + static_cast<std::ptrdiff_t>((r * columns + k) * c.element_size),
                    c.element_size,
                    data.begin() + static_cast<std::ptrdiff_t>((r * new_columns + k) * c.element_size));
  } else {
    std::copy_n(c.bytes.begin(), std::min(c.bytes.size(), data.size()), data.begin());
  }
  replace_dataset(file, path, c.file_type.get(), c.memory_type.get(), dims, data.data(),
                  c.extendible && dims.size() >= 1);
  std::string shape;
  for (hsize_t d : dims) shape += (shape.empty() ? "" : " x ") + std::to_string(d);
  return path + ": reshaped to " + (shape.empty() ? "a scalar" : shape);
}

// Another element type: a number type, a record without one member or with one member of another
// type, or fixed-length text.
std::string retype(hid_t file, const std::string& path, FuzzedDataProvider& bytes) {
  const Contents c = read_contents(file, path);
  Handle type;
  std::string said;
  const bool record = H5Tget_class(c.memory_type.get()) == H5T_COMPOUND;
  const int choice = bytes.ConsumeIntegralInRange(0, record ? 7 : 5);
  if (choice < 5) {
    const hid_t numbers[] = {H5T_NATIVE_INT32, H5T_NATIVE_INT64, H5T_NATIVE_FLOAT,
                             H5T_NATIVE_DOUBLE, H5T_NATIVE_UINT8, H5T_STD_I16BE};
    const char* names[] = {"int32", "int64", "float32", "float64", "uint8", "int16 big-endian"};
    const int k = bytes.ConsumeIntegralInRange(0, 5);
    type = check(H5Tcopy(numbers[k]), "copy a type");
    said = names[k];
  } else if (choice == 5) {
    type = check(H5Tcopy(H5T_C_S1), "copy a string type");
    check_status(H5Tset_size(type.get(), 8), "size a string type");
    said = "text of 8 bytes";
  } else {
    // A record with one member left out (choice 6) or of another type (choice 7).
    const int members = H5Tget_nmembers(c.memory_type.get());
    if (members <= 0) return path + ": an empty record, not retyped";
    const int changed = bytes.ConsumeIntegralInRange(0, members - 1);
    std::vector<std::pair<std::string, Handle>> kept;
    std::size_t size = 0;
    for (int m = 0; m < members; ++m) {
      char* name = H5Tget_member_name(c.memory_type.get(), static_cast<unsigned>(m));
      const std::string member_name = name ? name : "?";
      H5free_memory(name);
      Handle member = check(H5Tget_member_type(c.memory_type.get(), static_cast<unsigned>(m)), "member type");
      if (m == changed) {
        said = "record with member '" + member_name + "' " + (choice == 6 ? "left out" : "as int32");
        if (choice == 6) continue;
        member = check(H5Tcopy(H5T_NATIVE_INT32), "copy a type");
      }
      size += H5Tget_size(member.get());
      kept.emplace_back(member_name, std::move(member));
    }
    if (kept.empty()) return path + ": its only member, not left out";
    type = check(H5Tcreate(H5T_COMPOUND, size), "create a record type");
    std::size_t offset = 0;
    for (const auto& [name, member] : kept) {
      check_status(H5Tinsert(type.get(), name.c_str(), offset, member.get()), "insert " + name);
      offset += H5Tget_size(member.get());
    }
  }
  // The values converted by HDF5 where it can (zeros where it cannot: text).
  std::vector<unsigned char> data(c.points() * H5Tget_size(type.get()), 0);
  if (!data.empty() && H5Tget_class(type.get()) != H5T_STRING) {
    const Handle set = check(H5Dopen2(file, path.c_str(), H5P_DEFAULT), "open " + path);
    if (H5Dread(set.get(), type.get(), H5S_ALL, H5S_ALL, H5P_DEFAULT, data.data()) < 0)
      std::fill(data.begin(), data.end(), 0);
  }
  replace_dataset(file, path, type.get(), type.get(), c.dims, data.data(), c.extendible);
  return path + ": retyped to " + said;
}

std::string edit_dataset(hid_t file, const std::string& path, FuzzedDataProvider& bytes) {
  switch (bytes.ConsumeIntegralInRange(0, 7)) {
    case 0:
    case 1:
    case 2: return edit_value(file, path, bytes);
    case 3: {
      const Contents c = read_contents(file, path);
      if (c.dims.empty()) return path + ": scalar, not resized";
      RowFill fill;
      const std::size_t rows = new_row_count(bytes, c.dims[0]);
      fill.copy = bytes.ConsumeBool();
      fill.source = bytes.ConsumeIntegralInRange<std::size_t>(0, c.dims[0] > 0 ? c.dims[0] - 1 : 0);
      return resize_rows(file, path, rows, fill);
    }
    case 4: return resize_group(file, path, bytes);
    case 5: return reshape(file, path, bytes);
    case 6: return retype(file, path, bytes);
    default:
      check_status(H5Ldelete(file, path.c_str(), H5P_DEFAULT), "unlink " + path);
      return path + ": removed";
  }
}

// ---- attributes ----

std::string edited_text(const std::string& text, FuzzedDataProvider& bytes) {
  const std::size_t at = bytes.ConsumeIntegralInRange<std::size_t>(0, text.size());
  switch (bytes.ConsumeIntegralInRange(0, 4)) {
    case 0: return text.substr(0, at);  // cut
    case 1: return text + bytes.ConsumeRandomLengthString(64);
    case 2: return text.substr(0, at) + bytes.ConsumeRandomLengthString(64) + text.substr(at);
    case 3: {  // one line replaced
      const std::size_t begin = text.rfind('\n', at == 0 ? 0 : at - 1);
      const std::size_t first = begin == std::string::npos ? 0 : begin + 1;
      const std::size_t end = text.find('\n', at);
      return text.substr(0, first) + bytes.ConsumeRandomLengthString(64) +
             (end == std::string::npos ? "" : text.substr(end));
    }
    default: return bytes.ConsumeRandomLengthString(256);
  }
}

std::string edit_attribute(hid_t file, const std::string& path, const std::string& name,
                           FuzzedDataProvider& bytes) {
  const Handle object = check(H5Oopen(file, path.c_str(), H5P_DEFAULT), "open " + path);
  const std::string where = path + " attribute '" + name + "'";
  if (H5Aexists(object.get(), name.c_str()) <= 0) return where + ": gone";
  const int op = bytes.ConsumeIntegralInRange(0, 4);
  if (op == 4) {
    check_status(H5Adelete(object.get(), name.c_str()), "delete " + where);
    return where + ": removed";
  }
  H5T_class_t type_class;
  {
    const Handle attribute = check(H5Aopen(object.get(), name.c_str(), H5P_DEFAULT), "open " + where);
    const Handle type = check(H5Aget_type(attribute.get()), "get the type of " + where);
    type_class = H5Tget_class(type.get());
  }
  if (op <= 2 && type_class == H5T_STRING) {
    const std::string text = edited_text(runfile::h5::read_string_attribute(object.get(), name), bytes);
    runfile::h5::write_attribute(object.get(), name, text);
    return where + ": text of " + std::to_string(text.size()) + " bytes";
  }
  if (op <= 2 && (type_class == H5T_INTEGER || type_class == H5T_FLOAT)) {
    const Handle attribute = check(H5Aopen(object.get(), name.c_str(), H5P_DEFAULT), "open " + where);
    const Handle type = check(H5Aget_type(attribute.get()), "get the type of " + where);
    const Handle memory = check(H5Tget_native_type(type.get(), H5T_DIR_ASCEND), "native type");
    const Handle space = check(H5Aget_space(attribute.get()), "get the dataspace of " + where);
    const hssize_t points = H5Sget_simple_extent_npoints(space.get());
    if (points <= 0) return where + ": holds no value";
    std::vector<unsigned char> data(static_cast<std::size_t>(points) * H5Tget_size(memory.get()));
    check_status(H5Aread(attribute.get(), memory.get(), data.data()), "read " + where);
    const std::size_t k = bytes.ConsumeIntegralInRange<std::size_t>(0, static_cast<std::size_t>(points) - 1);
    const std::string said = patch(data.data() + k * H5Tget_size(memory.get()), memory.get(), bytes);
    check_status(H5Awrite(attribute.get(), memory.get(), data.data()), "write " + where);
    return where + said;
  }
  // Another type: text, a double, an integer, no value at all, or two values (read into one, an
  // attribute of two overflowed the stack: runfile/src/h5.cc now checks the size).
  check_status(H5Adelete(object.get(), name.c_str()), "delete " + where);
  switch (bytes.ConsumeIntegralInRange(0, 4)) {
    case 0:
      runfile::h5::write_attribute(object.get(), name, bytes.ConsumeRandomLengthString(64));
      return where + ": now text";
    case 1: {
      const double v = special_real(bytes, 1.0);
      runfile::h5::write_attribute(object.get(), name, v);
      return where + ": now the double " + std::to_string(v);
    }
    case 2: {
      const std::int64_t v = special_integer(bytes, 1);
      runfile::h5::write_attribute(object.get(), name, v);
      return where + ": now the integer " + std::to_string(v);
    }
    default: {
      const bool pair = bytes.ConsumeBool();
      const hsize_t two[1] = {2};
      const Handle space = pair ? check(H5Screate_simple(1, two, nullptr), "create a dataspace")
                                : check(H5Screate(H5S_NULL), "create a null dataspace");
      const Handle attribute = check(H5Acreate2(object.get(), name.c_str(), H5T_NATIVE_DOUBLE,
                                                space.get(), H5P_DEFAULT, H5P_DEFAULT),
                                     "create " + where);
      const double values[2] = {special_real(bytes, 1.0), special_real(bytes, 1.0)};
      if (pair) check_status(H5Awrite(attribute.get(), H5T_NATIVE_DOUBLE, values), "write " + where);
      return where + (pair ? ": now two doubles" : ": now without a value");
    }
  }
}

// ---- groups ----

std::string member_name(FuzzedDataProvider& bytes) {
  static const char* const kNames[] = {"000000", "000001", "000002", "000003", "000099",
                                       "extras", "walls",  "sff",    "series", "checkpoint"};
  if (bytes.ConsumeBool()) return kNames[bytes.ConsumeIntegralInRange<std::size_t>(0, std::size(kNames) - 1)];
  std::string name = bytes.ConsumeRandomLengthString(16);
  name.erase(std::remove_if(name.begin(), name.end(), [](char c) { return c == '/' || c == '\0'; }),
             name.end());
  return name.empty() || name == "." ? "x" : name;
}

std::string edit_group(hid_t file, const std::string& path, const std::vector<std::string>& others,
                       FuzzedDataProvider& bytes) {
  const int op = bytes.ConsumeIntegralInRange(0, 4);
  if (op == 0 && path != "/") {
    check_status(H5Ldelete(file, path.c_str(), H5P_DEFAULT), "unlink " + path);
    return path + ": removed";
  }
  const Handle group = check(H5Gopen2(file, path.c_str(), H5P_DEFAULT), "open " + path);
  const std::string name = member_name(bytes);
  if (H5Lexists(group.get(), name.c_str(), H5P_DEFAULT) > 0) return path + ": has '" + name + "'";
  const std::string where = path + (path == "/" ? "" : "/") + name;
  switch (op) {
    case 1:
      check(H5Gcreate2(group.get(), name.c_str(), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT), "create " + where);
      return where + ": an empty group added";
    case 2: {
      const hsize_t three[1] = {3};
      const double values[3] = {1.0, 2.0, 3.0};
      const Handle space = check(H5Screate_simple(1, three, nullptr), "create a dataspace");
      const Handle set = check(H5Dcreate2(group.get(), name.c_str(), H5T_NATIVE_DOUBLE, space.get(),
                                          H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT),
                               "create " + where);
      check_status(H5Dwrite(set.get(), H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, values),
                   "write " + where);
      return where + ": a dataset added";
    }
    case 3: {
      const std::string target = bytes.ConsumeBool() ? path : "/no/such/object";
      check_status(H5Lcreate_soft(target.c_str(), group.get(), name.c_str(), H5P_DEFAULT, H5P_DEFAULT),
                   "link " + where);
      return where + ": a soft link to " + target;
    }
    default: {
      const std::string& target = others[bytes.ConsumeIntegralInRange<std::size_t>(0, others.size() - 1)];
      check_status(H5Lcreate_hard(file, target.c_str(), group.get(), name.c_str(), H5P_DEFAULT, H5P_DEFAULT),
                   "link " + where);
      return where + ": a second link to " + target;
    }
  }
}

}  // namespace

RunFileMutator::RunFileMutator(const std::string& seed_path) {
  std::ifstream in(seed_path, std::ios::binary);
  seed_.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  if (seed_.empty()) finding("cannot read the seed run file " + seed_path);
  runfile::h5::silence_errors();
  const Handle file = check(H5Fopen(seed_path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), "open the seed");
  H5Ovisit2(
      file.get(), H5_INDEX_NAME, H5_ITER_INC,
      [](hid_t location, const char* name, const H5O_info_t* info, void* out) -> herr_t {
        auto& objects = *static_cast<std::vector<Object>*>(out);
        if (info->type != H5O_TYPE_GROUP && info->type != H5O_TYPE_DATASET) return 0;
        const std::string path = std::string(name) == "." ? "/" : "/" + std::string(name);
        const bool dataset = info->type == H5O_TYPE_DATASET;
        objects.push_back({path, "", dataset});
        struct Owner {
          std::vector<Object>* objects;
          std::string path;
          bool dataset;
        } owner{&objects, path, dataset};
        H5Aiterate_by_name(
            location, name, H5_INDEX_NAME, H5_ITER_INC, nullptr,
            [](hid_t, const char* attribute, const H5A_info_t*, void* data) -> herr_t {
              const auto& o = *static_cast<Owner*>(data);
              o.objects->push_back({o.path, attribute, o.dataset});
              return 0;
            },
            &owner, H5P_DEFAULT);
        return 0;
      },
      &objects_, H5O_INFO_BASIC);
  if (objects_.size() < 2) finding("the seed run file " + seed_path + " holds nothing to edit");
}

std::vector<std::string> RunFileMutator::write(const std::string& path, FuzzedDataProvider& bytes,
                                               const std::string& focus) const {
  {
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    out.write(seed_.data(), static_cast<std::streamsize>(seed_.size()));
    if (!out) finding("cannot write " + path);
  }
  std::vector<std::size_t> focused;
  for (std::size_t k = 0; k < objects_.size(); ++k)
    if (!focus.empty() && objects_[k].path.rfind(focus, 0) == 0) focused.push_back(k);
  std::vector<std::string> paths;
  for (const Object& o : objects_)
    if (o.attribute.empty()) paths.push_back(o.path);

  std::vector<std::string> log;
  const Handle file = check(H5Fopen(path.c_str(), H5F_ACC_RDWR, H5P_DEFAULT), "open " + path);
  const int edits = bytes.ConsumeIntegralInRange(0, kMaxEdits);
  for (int e = 0; e < edits && bytes.remaining_bytes() > 0; ++e) {
    const bool in_focus = !focused.empty() && bytes.ConsumeIntegralInRange(0, 3) != 0;
    const Object& o =
        in_focus ? objects_[focused[bytes.ConsumeIntegralInRange<std::size_t>(0, focused.size() - 1)]]
                 : objects_[bytes.ConsumeIntegralInRange<std::size_t>(0, objects_.size() - 1)];
    try {
      if (!o.attribute.empty()) {
        log.push_back(edit_attribute(file.get(), o.path, o.attribute, bytes));
      } else if (o.dataset) {
        log.push_back(edit_dataset(file.get(), o.path, bytes));
      } else {
        log.push_back(edit_group(file.get(), o.path, paths, bytes));
      }
    } catch (const std::exception& error) {  // an object an earlier edit removed, ...
      log.push_back(o.path + (o.attribute.empty() ? "" : " '" + o.attribute + "'") +
                    ": not edited: " + error.what());
    }
  }
  return log;
}

}  // namespace sffcal_fuzz
