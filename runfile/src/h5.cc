#include "h5.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstddef>
#include <cstring>
#include <stdexcept>

#include "runfile/records.h"

namespace runfile::h5 {

void Handle::reset() {
  if (id_ < 0) return;
  switch (H5Iget_type(id_)) {
    case H5I_FILE: H5Fclose(id_); break;
    case H5I_GROUP: H5Gclose(id_); break;
    case H5I_DATASET: H5Dclose(id_); break;
    case H5I_DATASPACE: H5Sclose(id_); break;
    case H5I_DATATYPE: H5Tclose(id_); break;
    case H5I_ATTR: H5Aclose(id_); break;
    case H5I_GENPROP_LST: H5Pclose(id_); break;
    default: break;
  }
  id_ = -1;
}

Handle check(hid_t id, const std::string& what) {
  if (id < 0) throw std::runtime_error("HDF5: cannot " + what);
  return Handle(id);
}

void check_status(herr_t status, const std::string& what) {
  if (status < 0) throw std::runtime_error("HDF5: cannot " + what);
}

void silence_errors() { H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr); }

bool exists(hid_t location, const std::string& path) {
  // Check each component: H5Lexists fails if an intermediate group is missing.
  std::string partial;
  std::size_t start = 0;
  while (start <= path.size()) {
    const std::size_t slash = path.find('/', start);
    const std::string part = path.substr(start, slash == std::string::npos ? std::string::npos
                                                                            : slash - start);
    if (!part.empty()) {
      partial += (partial.empty() ? "" : "/") + part;
      if (H5Lexists(location, partial.c_str(), H5P_DEFAULT) <= 0) return false;
    }
    if (slash == std::string::npos) break;
    start = slash + 1;
  }
  return true;
}

Handle open_group(hid_t location, const std::string& path) {
  return check(H5Gopen2(location, path.c_str(), H5P_DEFAULT), "open group " + path);
}

Handle create_group(hid_t location, const std::string& path) {
  Handle plist = check(H5Pcreate(H5P_LINK_CREATE), "create a property list");
  H5Pset_create_intermediate_group(plist.get(), 1);
  return check(H5Gcreate2(location, path.c_str(), plist.get(), H5P_DEFAULT, H5P_DEFAULT),
               "create group " + path);
}

Handle create_group(hid_t location, const std::string& path, std::size_t expected_links) {
  Handle links = check(H5Pcreate(H5P_LINK_CREATE), "create a property list");
  H5Pset_create_intermediate_group(links.get(), 1);
  Handle group = check(H5Pcreate(H5P_GROUP_CREATE), "create a property list");
  check_status(H5Pset_local_heap_size_hint(group.get(), 16 * expected_links),
               "size the name heap of " + path);
  return check(H5Gcreate2(location, path.c_str(), links.get(), group.get(), H5P_DEFAULT),
               "create group " + path);
}

Handle create_unlinked_group(hid_t file) {
  return check(H5Gcreate_anon(file, H5P_DEFAULT, H5P_DEFAULT), "create a group");
}

void link(hid_t object, hid_t location, const std::string& path) {
  Handle plist = check(H5Pcreate(H5P_LINK_CREATE), "create a property list");
  H5Pset_create_intermediate_group(plist.get(), 1);
  check_status(H5Olink(object, location, path.c_str(), plist.get(), H5P_DEFAULT), "link " + path);
}

namespace {

void write_scalar_attribute(hid_t object, const std::string& name, hid_t type,
                            const void* value) {
  if (H5Aexists(object, name.c_str()) > 0) H5Adelete(object, name.c_str());
  Handle space = check(H5Screate(H5S_SCALAR), "create a scalar dataspace");
  Handle attr = check(H5Acreate2(object, name.c_str(), type, space.get(), H5P_DEFAULT, H5P_DEFAULT),
                      "create attribute " + name);
  check_status(H5Awrite(attr.get(), type, value), "write attribute " + name);
}

// An attribute read into one value: one of any other size (an edited file's [2, 2]) would be
// read past that value.
Handle open_attribute(hid_t object, const std::string& name) {
  Handle attr = check(H5Aopen(object, name.c_str(), H5P_DEFAULT), "open attribute " + name);
  Handle space = check(H5Aget_space(attr.get()), "get the dataspace of attribute " + name);
  const hssize_t values = H5Sget_simple_extent_npoints(space.get());
  if (values != 1)
    throw std::runtime_error("HDF5: attribute " + name + " holds " + std::to_string(values) +
                             " values where one is expected");
  return attr;
}

}  // namespace

void write_attribute(hid_t object, const std::string& name, const std::string& value) {
  // Variable-length UTF-8, so h5py returns str rather than bytes.
  Handle type = check(H5Tcopy(H5T_C_S1), "copy a string type");
  H5Tset_size(type.get(), H5T_VARIABLE);
  H5Tset_cset(type.get(), H5T_CSET_UTF8);
  const char* text = value.c_str();
  write_scalar_attribute(object, name, type.get(), &text);
}

void write_attribute(hid_t object, const std::string& name, double value) {
  write_scalar_attribute(object, name, H5T_NATIVE_DOUBLE, &value);
}

void write_attribute(hid_t object, const std::string& name, std::int64_t value) {
  write_scalar_attribute(object, name, H5T_NATIVE_INT64, &value);
}

std::string read_string_attribute(hid_t object, const std::string& name) {
  Handle attr = open_attribute(object, name);
  Handle type = check(H5Aget_type(attr.get()), "get the type of attribute " + name);
  if (H5Tget_class(type.get()) != H5T_STRING)
    throw std::runtime_error("HDF5: attribute " + name + " is not a string");
  Handle memtype = check(H5Tcopy(H5T_C_S1), "copy a string type");
  H5Tset_size(memtype.get(), H5T_VARIABLE);
  H5Tset_cset(memtype.get(), H5T_CSET_UTF8);
  char* text = nullptr;
  check_status(H5Aread(attr.get(), memtype.get(), &text), "read attribute " + name);
  std::string value = text ? text : "";
  Handle space = check(H5Aget_space(attr.get()), "get a dataspace");
  H5Dvlen_reclaim(memtype.get(), space.get(), H5P_DEFAULT, &text);
  return value;
}

double read_double_attribute(hid_t object, const std::string& name) {
  double value = 0.0;
  Handle attr = open_attribute(object, name);
  check_status(H5Aread(attr.get(), H5T_NATIVE_DOUBLE, &value), "read attribute " + name);
  return value;
}

std::int64_t read_int_attribute(hid_t object, const std::string& name) {
  std::int64_t value = 0;
  Handle attr = open_attribute(object, name);
  check_status(H5Aread(attr.get(), H5T_NATIVE_INT64, &value), "read attribute " + name);
  return value;
}

Handle crash_safe_creation_properties() {
  Handle plist = check(H5Pcreate(H5P_FILE_CREATE), "create a property list");
  check_status(H5Pset_sym_k(plist.get(), 16, 64), "set the symbol-table node sizes");
  check_status(H5Pset_local_heap_size_hint(plist.get(), 1024), "size the root group's name heap");
  return plist;
}

Handle crash_safe_access_properties() {
  Handle plist = check(H5Pcreate(H5P_FILE_ACCESS), "create a property list");
  // No metadata evictions between flushes (the cache holds what one row, snapshot or checkpoint
  // changes): a half-updated object never reaches the disk ahead of the flush.
  H5AC_cache_config_t cache;
  cache.version = H5AC__CURR_CACHE_CONFIG_VERSION;
  check_status(H5Pget_mdc_config(plist.get(), &cache), "read the metadata cache settings");
  cache.evictions_enabled = false;
  cache.incr_mode = H5C_incr__off;
  cache.flash_incr_mode = H5C_flash_incr__off;
  cache.decr_mode = H5C_decr__off;
  check_status(H5Pset_mdc_config(plist.get(), &cache), "set the metadata cache");
  return plist;
}

void write_dataset(hid_t location, const std::string& name, hid_t type, const void* data,
                   std::size_t rows, std::size_t cols) {
  const int rank = cols == 0 ? 1 : 2;
  const hsize_t dims[2] = {rows, cols};
  Handle space = check(H5Screate_simple(rank, dims, nullptr), "create dataspace for " + name);
  Handle plist = check(H5Pcreate(H5P_DATASET_CREATE), "create a property list");
  if (rows > 0) {
    const hsize_t chunk[2] = {std::min<hsize_t>(rows, 4096), cols};
    H5Pset_chunk(plist.get(), rank, chunk);
    H5Pset_shuffle(plist.get());
    H5Pset_deflate(plist.get(), 4);
  }
  Handle set = check(H5Dcreate2(location, name.c_str(), type, space.get(), H5P_DEFAULT,
                                plist.get(), H5P_DEFAULT),
                     "create dataset " + name);
  if (rows > 0)
    check_status(H5Dwrite(set.get(), type, H5S_ALL, H5S_ALL, H5P_DEFAULT, data),
                 "write dataset " + name);
}

template <typename T>
std::vector<T> read_dataset(hid_t location, const std::string& name, hid_t type,
                            std::size_t* cols) {
  Handle set = check(H5Dopen2(location, name.c_str(), H5P_DEFAULT), "open dataset " + name);
  Handle space = check(H5Dget_space(set.get()), "get the dataspace of " + name);
  hsize_t dims[2] = {0, 0};
  const int rank = H5Sget_simple_extent_ndims(space.get());
  if (rank < 1 || rank > 2) throw std::runtime_error("HDF5: dataset " + name + " has rank " + std::to_string(rank));
  H5Sget_simple_extent_dims(space.get(), dims, nullptr);
  if (cols) *cols = rank == 2 ? dims[1] : 0;
  std::vector<T> values(dims[0] * (rank == 2 ? dims[1] : 1));
  if (!values.empty())
    check_status(H5Dread(set.get(), type, H5S_ALL, H5S_ALL, H5P_DEFAULT, values.data()),
                 "read dataset " + name);
  return values;
}

template std::vector<double> read_dataset(hid_t, const std::string&, hid_t, std::size_t*);
template std::vector<std::int64_t> read_dataset(hid_t, const std::string&, hid_t, std::size_t*);
template std::vector<std::int32_t> read_dataset(hid_t, const std::string&, hid_t, std::size_t*);
template std::vector<std::uint8_t> read_dataset(hid_t, const std::string&, hid_t, std::size_t*);
template std::vector<ParticleRecord> read_dataset(hid_t, const std::string&, hid_t, std::size_t*);
template std::vector<ContactRecord> read_dataset(hid_t, const std::string&, hid_t, std::size_t*);
template std::vector<WallRecord> read_dataset(hid_t, const std::string&, hid_t, std::size_t*);

int file_descriptor(hid_t file) {
  const Handle access(H5Fget_access_plist(file));
  if (!access.valid() || H5Pget_driver(access.get()) != H5FD_SEC2) return -1;
  void* handle = nullptr;
  if (H5Fget_vfd_handle(file, H5P_DEFAULT, &handle) < 0 || handle == nullptr) return -1;
  return *static_cast<int*>(handle);
}

void reserve_space(hid_t file, int fd, std::uint64_t bytes) {
  haddr_t end = 0;
  if (fd < 0 || H5Fget_eoa(file, &end) < 0) return;
  const int error = posix_fallocate(fd, static_cast<off_t>(end), static_cast<off_t>(bytes));
  if (error == ENOSPC || error == EDQUOT || error == EFBIG)
    throw std::runtime_error("no room on the disk for the next " + std::to_string(bytes) +
                             " bytes (" + std::strerror(error) + ")");
}

void release_space(hid_t file, int fd) {
  haddr_t end = 0;
  struct stat status {};
  if (fd < 0 || H5Fget_eoa(file, &end) < 0 || fstat(fd, &status) != 0) return;
  if (static_cast<haddr_t>(status.st_size) > end)
    (void)!ftruncate(fd, static_cast<off_t>(end));
}

void create_extendible(hid_t location, const std::string& name) {
  const hsize_t dims[1] = {0}, max_dims[1] = {H5S_UNLIMITED}, chunk[1] = {kExtendibleChunkRows};
  Handle space = check(H5Screate_simple(1, dims, max_dims), "create dataspace for " + name);
  Handle plist = check(H5Pcreate(H5P_DATASET_CREATE), "create a property list");
  H5Pset_chunk(plist.get(), 1, chunk);
  check(H5Dcreate2(location, name.c_str(), H5T_NATIVE_DOUBLE, space.get(), H5P_DEFAULT,
                   plist.get(), H5P_DEFAULT),
        "create dataset " + name);
}

std::size_t length(hid_t location, const std::string& name) {
  Handle set = check(H5Dopen2(location, name.c_str(), H5P_DEFAULT), "open dataset " + name);
  Handle space = check(H5Dget_space(set.get()), "get the dataspace of " + name);
  hsize_t dims[1] = {0};
  H5Sget_simple_extent_dims(space.get(), dims, nullptr);
  return dims[0];
}

void append(hid_t location, const std::string& name, double value) {
  Handle set = check(H5Dopen2(location, name.c_str(), H5P_DEFAULT), "open dataset " + name);
  Handle space = check(H5Dget_space(set.get()), "get the dataspace of " + name);
  hsize_t dims[1] = {0};
  H5Sget_simple_extent_dims(space.get(), dims, nullptr);
  const hsize_t new_dims[1] = {dims[0] + 1}, start[1] = {dims[0]}, count[1] = {1};
  check_status(H5Dset_extent(set.get(), new_dims), "extend dataset " + name);
  Handle file_space = check(H5Dget_space(set.get()), "get the dataspace of " + name);
  H5Sselect_hyperslab(file_space.get(), H5S_SELECT_SET, start, nullptr, count, nullptr);
  Handle mem_space = check(H5Screate_simple(1, count, nullptr), "create a dataspace");
  check_status(H5Dwrite(set.get(), H5T_NATIVE_DOUBLE, mem_space.get(), file_space.get(),
                        H5P_DEFAULT, &value),
               "append to dataset " + name);
}

void truncate(hid_t location, const std::string& name, std::size_t rows) {
  Handle set = check(H5Dopen2(location, name.c_str(), H5P_DEFAULT), "open dataset " + name);
  const hsize_t dims[1] = {rows};
  check_status(H5Dset_extent(set.get(), dims), "truncate dataset " + name);
}

namespace {

Handle array_type(hid_t base, hsize_t n) {
  const hsize_t dims[1] = {n};
  return check(H5Tarray_create2(base, 1, dims), "create an array type");
}

}  // namespace

Handle particle_record_type() {
  Handle t = check(H5Tcreate(H5T_COMPOUND, sizeof(ParticleRecord)), "create a compound type");
  Handle v3 = array_type(H5T_NATIVE_DOUBLE, 3), v4 = array_type(H5T_NATIVE_DOUBLE, 4);
  H5Tinsert(t.get(), "id", offsetof(ParticleRecord, id), H5T_NATIVE_INT64);
  H5Tinsert(t.get(), "num_spheres", offsetof(ParticleRecord, num_spheres), H5T_NATIVE_INT32);
  H5Tinsert(t.get(), "sphere_diameter", offsetof(ParticleRecord, sphere_diameter), H5T_NATIVE_DOUBLE);
  H5Tinsert(t.get(), "position", offsetof(ParticleRecord, position), v3.get());
  H5Tinsert(t.get(), "orientation", offsetof(ParticleRecord, orientation), v4.get());
  H5Tinsert(t.get(), "velocity", offsetof(ParticleRecord, velocity), v3.get());
  H5Tinsert(t.get(), "angular_velocity", offsetof(ParticleRecord, angular_velocity), v3.get());
  return t;
}

Handle contact_record_type() {
  Handle t = check(H5Tcreate(H5T_COMPOUND, sizeof(ContactRecord)), "create a compound type");
  Handle v3 = array_type(H5T_NATIVE_DOUBLE, 3);
  H5Tinsert(t.get(), "body_a", offsetof(ContactRecord, body_a), H5T_NATIVE_INT64);
  H5Tinsert(t.get(), "body_b", offsetof(ContactRecord, body_b), H5T_NATIVE_INT64);
  H5Tinsert(t.get(), "wall", offsetof(ContactRecord, wall), H5T_NATIVE_INT32);
  H5Tinsert(t.get(), "sliding", offsetof(ContactRecord, sliding), H5T_NATIVE_INT32);
  H5Tinsert(t.get(), "point", offsetof(ContactRecord, point), v3.get());
  H5Tinsert(t.get(), "normal", offsetof(ContactRecord, normal), v3.get());
  H5Tinsert(t.get(), "branch", offsetof(ContactRecord, branch), v3.get());
  H5Tinsert(t.get(), "overlap", offsetof(ContactRecord, overlap), H5T_NATIVE_DOUBLE);
  H5Tinsert(t.get(), "normal_force", offsetof(ContactRecord, normal_force), H5T_NATIVE_DOUBLE);
  H5Tinsert(t.get(), "tangential_force", offsetof(ContactRecord, tangential_force), v3.get());
  return t;
}

Handle wall_record_type() {
  Handle t = check(H5Tcreate(H5T_COMPOUND, sizeof(WallRecord)), "create a compound type");
  H5Tinsert(t.get(), "axis", offsetof(WallRecord, axis), H5T_NATIVE_INT32);
  H5Tinsert(t.get(), "upper", offsetof(WallRecord, upper), H5T_NATIVE_INT32);
  H5Tinsert(t.get(), "stress_controlled", offsetof(WallRecord, stress_controlled), H5T_NATIVE_INT32);
  H5Tinsert(t.get(), "padding", offsetof(WallRecord, padding), H5T_NATIVE_INT32);
  H5Tinsert(t.get(), "position", offsetof(WallRecord, position), H5T_NATIVE_DOUBLE);
  H5Tinsert(t.get(), "velocity", offsetof(WallRecord, velocity), H5T_NATIVE_DOUBLE);
  H5Tinsert(t.get(), "normal_force", offsetof(WallRecord, normal_force), H5T_NATIVE_DOUBLE);
  H5Tinsert(t.get(), "target_stress", offsetof(WallRecord, target_stress), H5T_NATIVE_DOUBLE);
  return t;
}

}  // namespace runfile::h5
