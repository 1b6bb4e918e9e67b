#include "h5_file.hpp"

#include <fcntl.h>
#include <hdf5_hl.h>
#include <unistd.h>

#include "output_target.hpp"
#include "vibrissa/core/limits.hpp"

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <stdexcept>

namespace vibrissa::io::h5 {

Handle& Handle::operator=(Handle&& o) noexcept {
  if (this != &o) {
    reset();
    id_ = o.id_;
    close_ = o.close_;
    o.id_ = H5I_INVALID_HID;
  }
  return *this;
}

hid_t Handle::release() {
  const hid_t id = id_;
  id_ = H5I_INVALID_HID;
  return id;
}

void Handle::reset() {
  if (id_ >= 0 && close_) close_(id_);
  id_ = H5I_INVALID_HID;
}

QuietErrors::QuietErrors() {
  H5Eget_auto2(H5E_DEFAULT, &func_, &data_);
  H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
}
QuietErrors::~QuietErrors() {
  // An error left on this thread's stack makes thread-safe libhdf5 1.10 loop at exit ("HDF5: infinite loop
  // closing library") when the error happened on a thread other than the main one.
  H5Eclear2(H5E_DEFAULT);
  H5Eset_auto2(H5E_DEFAULT, func_, data_);
}

Handle create_file(const std::string& path) {
  // In memory (the core driver without a backing store): libhdf5 never writes to the disk, so a full disk
  // or a file size limit is met by close_file's own write, not inside libhdf5, whose clean-up after a failed
  // write crashes at exit (1.10.8: SIGSEGV in H5F__close_cb).
  Handle fapl(H5Pcreate(H5P_FILE_ACCESS), H5Pclose);
  if (!fapl.valid() || H5Pset_fapl_core(fapl.get(), 4u << 20, false) < 0)
    throw std::runtime_error(path + ": cannot create the HDF5 file");
  Handle f(H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, fapl.get()), H5Fclose);
  if (!f.valid()) throw std::runtime_error(path + ": cannot create the HDF5 file");
  return f;
}

Handle open_file_read(const std::string& path) {
  if (H5Fis_hdf5(path.c_str()) <= 0) throw std::invalid_argument(path + ": cannot open as an HDF5 file");
  Handle f(H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), H5Fclose);
  if (!f.valid()) throw std::invalid_argument(path + ": cannot open as an HDF5 file");
  return f;
}

void close_file(Handle& file, const std::string& path) {
  const ssize_t name_size = H5Fget_name(file.get(), nullptr, 0);
  std::string name(name_size > 0 ? static_cast<std::size_t>(name_size) : 0, '\0');
  const bool flushed = H5Fflush(file.get(), H5F_SCOPE_GLOBAL) >= 0;  // the metadata cache into the image
  const ssize_t size = flushed ? H5Fget_file_image(file.get(), nullptr, 0) : -1;
  std::vector<char> image(size > 0 ? static_cast<std::size_t>(size) : 0);
  if (name_size <= 0 || H5Fget_name(file.get(), name.data(), name.size() + 1) < 0 || size <= 0 ||
      H5Fget_file_image(file.get(), image.data(), image.size()) != size)
    throw std::runtime_error(path + ": cannot finish the HDF5 file");
  file.reset();
  const int fd = ::open(name.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_NOFOLLOW | O_CLOEXEC, 0666);
  if (fd < 0) throw std::runtime_error("cannot write " + quoted_path(path) + ": " + std::strerror(errno));
  try {
    write_all(fd, image.data(), image.size(), path);
  } catch (...) {
    ::close(fd);
    throw;
  }
  if (::close(fd) != 0 && errno != EINTR)
    throw std::runtime_error("cannot write " + quoted_path(path) + ": " + std::strerror(errno));
}

Handle create_group(hid_t parent, const std::string& name) {
  Handle g(H5Gcreate2(parent, name.c_str(), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT), H5Gclose);
  if (!g.valid()) throw std::runtime_error("cannot create HDF5 group '" + name + "'");
  return g;
}

bool has_dataset(hid_t loc, const std::string& name) {
  return H5Lexists(loc, name.c_str(), H5P_DEFAULT) > 0;
}

std::optional<std::vector<hsize_t>> dataset_dims(hid_t loc, const std::string& name) {
  if (!has_dataset(loc, name)) return std::nullopt;
  Handle d(H5Dopen2(loc, name.c_str(), H5P_DEFAULT), H5Dclose);
  if (!d.valid()) return std::nullopt;
  Handle space(H5Dget_space(d.get()), H5Sclose);
  const int rank = H5Sget_simple_extent_ndims(space.get());
  if (rank < 0) return std::nullopt;
  std::vector<hsize_t> dims(static_cast<std::size_t>(rank));
  H5Sget_simple_extent_dims(space.get(), dims.data(), nullptr);
  return dims;
}

std::vector<double> read_doubles(hid_t loc, const std::string& name, std::vector<hsize_t>& dims,
                                 const std::string& source) {
  Handle d(H5Dopen2(loc, name.c_str(), H5P_DEFAULT), H5Dclose);
  if (!d.valid()) throw std::invalid_argument(source + ": column '" + name + "': dataset is missing");
  Handle space(H5Dget_space(d.get()), H5Sclose);
  const int rank = H5Sget_simple_extent_ndims(space.get());
  if (rank < 0) throw std::invalid_argument(source + ": column '" + name + "': unreadable dataspace");
  dims.assign(static_cast<std::size_t>(rank), 0);
  H5Sget_simple_extent_dims(space.get(), dims.data(), nullptr);
  std::size_t count = 1;
  for (hsize_t x : dims) {  // bounded before any allocation (and before the product could overflow)
    if (x > limits::max_array_elements || count * static_cast<std::size_t>(x) > limits::max_array_elements)
      throw std::invalid_argument(source + ": column '" + name + "': more than " +
                                  std::to_string(limits::max_array_elements) + " values (docs/formats.md, \"Limits\")");
    count *= static_cast<std::size_t>(x);
  }
  Handle type(H5Dget_type(d.get()), H5Tclose);
  const H5T_class_t cls = H5Tget_class(type.get());
  if (cls != H5T_FLOAT && cls != H5T_INTEGER)
    throw std::invalid_argument(source + ": column '" + name + "': dataset is not numeric");
  std::vector<double> data(count);
  if (count > 0 && H5Dread(d.get(), H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, data.data()) < 0)
    throw std::invalid_argument(source + ": column '" + name + "': cannot read the dataset");
  return data;
}

namespace {

// One dataset of `file_type` from `data` in `memory_type`, optionally chunked + deflated.
void write_raw(hid_t loc, const std::string& name, hid_t file_type, hid_t memory_type, const void* data,
               const std::vector<hsize_t>& dims, const DatasetOptions& options) {
  if (options.units.empty()) throw std::logic_error("HDF5 dataset '" + name + "' written without units");
  Handle space(H5Screate_simple(static_cast<int>(dims.size()), dims.data(), nullptr), H5Sclose);
  Handle plist(H5Pcreate(H5P_DATASET_CREATE), H5Pclose);
  if (!space.valid() || !plist.valid()) throw std::runtime_error("cannot create HDF5 dataset '" + name + "'");
  hsize_t total = 1;
  for (hsize_t d : dims) total *= d;
  if (options.compress && total > 4096 && !dims.empty()) {
    // Chunks of at most ~64k values along the trailing dimensions.
    std::vector<hsize_t> chunk(dims);
    for (std::size_t i = 0; i + 1 < chunk.size() && total > 65536; ++i) {
      total /= chunk[i];
      chunk[i] = 1;
    }
    H5Pset_chunk(plist.get(), static_cast<int>(chunk.size()), chunk.data());
    H5Pset_deflate(plist.get(), 4);
  }
  Handle d(H5Dcreate2(loc, name.c_str(), file_type, space.get(), H5P_DEFAULT, plist.get(), H5P_DEFAULT), H5Dclose);
  if (!d.valid() || H5Dwrite(d.get(), memory_type, H5S_ALL, H5S_ALL, H5P_DEFAULT, data) < 0)
    throw std::runtime_error("cannot write HDF5 dataset '" + name + "'");
  write_string_attribute(d.get(), "units", options.units);
  if (!options.codes.empty()) write_string_attribute(d.get(), "codes", options.codes);
  if (!options.long_name.empty()) write_string_attribute(d.get(), "long_name", options.long_name);
}

// Variable-length UTF-8 strings (netCDF-4's NC_STRING).
Handle utf8_string_type() {
  Handle type(H5Tcopy(H5T_C_S1), H5Tclose);
  if (!type.valid() || H5Tset_size(type.get(), H5T_VARIABLE) < 0 || H5Tset_cset(type.get(), H5T_CSET_UTF8) < 0)
    throw std::runtime_error("cannot create the HDF5 string type");
  return type;
}

}  // namespace

void write_dataset(hid_t loc, const std::string& name, std::span<const double> data,
                   const std::vector<hsize_t>& dims, const DatasetOptions& options) {
  write_raw(loc, name, H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, data.data(), dims, options);
}
void write_dataset(hid_t loc, const std::string& name, std::span<const float> data,
                   const std::vector<hsize_t>& dims, const DatasetOptions& options) {
  write_raw(loc, name, H5T_IEEE_F32LE, H5T_NATIVE_FLOAT, data.data(), dims, options);
}
void write_dataset(hid_t loc, const std::string& name, std::span<const int> data,
                   const std::vector<hsize_t>& dims, const DatasetOptions& options) {
  write_raw(loc, name, H5T_STD_I32LE, H5T_NATIVE_INT, data.data(), dims, options);
}
void write_dataset(hid_t loc, const std::string& name, std::span<const std::int16_t> data,
                   const std::vector<hsize_t>& dims, const DatasetOptions& options) {
  write_raw(loc, name, H5T_STD_I16LE, H5T_NATIVE_INT16, data.data(), dims, options);
}
void write_dataset(hid_t loc, const std::string& name, std::span<const std::int8_t> data,
                   const std::vector<hsize_t>& dims, const DatasetOptions& options) {
  write_raw(loc, name, H5T_STD_I8LE, H5T_NATIVE_INT8, data.data(), dims, options);
}

void write_strings(hid_t loc, const std::string& name, std::span<const std::string> data,
                   const DatasetOptions& options) {
  std::vector<const char*> pointers;
  pointers.reserve(data.size());
  for (const std::string& text : data) pointers.push_back(text.c_str());
  const Handle type = utf8_string_type();
  write_raw(loc, name, type.get(), type.get(), pointers.data(), {static_cast<hsize_t>(data.size())}, options);
}

namespace {
// An attribute read into one value must hold exactly one (a scalar or an array of one element).
void require_single_value(hid_t attribute, const std::string& name, const std::string& source) {
  Handle space(H5Aget_space(attribute), H5Sclose);
  const hssize_t n = space.valid() ? H5Sget_simple_extent_npoints(space.get()) : -1;
  if (n != 1)
    throw std::invalid_argument(source + ": attribute '" + name + "': expected a single value, got " +
                                std::to_string(n) + " values");
}
}  // namespace

std::vector<std::string> member_names(hid_t group) {
  std::vector<std::string> names;
  H5Literate(group, H5_INDEX_NAME, H5_ITER_NATIVE, nullptr,
              [](hid_t, const char* name, const H5L_info_t*, void* out) -> herr_t {
                static_cast<std::vector<std::string>*>(out)->emplace_back(name);
                return 0;
              },
              &names);
  return names;
}

std::optional<std::string> read_string_attribute(hid_t loc, const std::string& name, const std::string& source) {
  if (H5Aexists(loc, name.c_str()) <= 0) return std::nullopt;
  Handle a(H5Aopen(loc, name.c_str(), H5P_DEFAULT), H5Aclose);
  Handle type(H5Aget_type(a.get()), H5Tclose);
  if (H5Tget_class(type.get()) != H5T_STRING)
    throw std::invalid_argument(source + ": attribute '" + name + "': expected a string");
  require_single_value(a.get(), name, source);
  Handle mem(H5Tcopy(H5T_C_S1), H5Tclose);
  H5Tset_cset(mem.get(), H5Tget_cset(type.get()));  // HDF5 converts no UTF-8 string to ASCII (PyTables writes UTF-8)
  if (H5Tis_variable_str(type.get()) > 0) {
    H5Tset_size(mem.get(), H5T_VARIABLE);
    char* s = nullptr;
    if (H5Aread(a.get(), mem.get(), &s) < 0)
      throw std::invalid_argument(source + ": attribute '" + name + "': unreadable");
    std::string out = s ? s : "";
    H5free_memory(s);
    return out;
  }
  const std::size_t size = H5Tget_size(type.get());
  H5Tset_size(mem.get(), size + 1);
  std::string buf(size + 1, '\0');
  if (H5Aread(a.get(), mem.get(), buf.data()) < 0)
    throw std::invalid_argument(source + ": attribute '" + name + "': unreadable");
  return std::string(buf.c_str());
}

std::optional<std::string> read_string_attribute_bytes(hid_t loc, const std::string& name,
                                                      const std::string& source) {
  if (H5Aexists(loc, name.c_str()) <= 0) return std::nullopt;
  Handle a(H5Aopen(loc, name.c_str(), H5P_DEFAULT), H5Aclose);
  Handle type(H5Aget_type(a.get()), H5Tclose);
  if (H5Tget_class(type.get()) != H5T_STRING || H5Tis_variable_str(type.get()) > 0)
    return read_string_attribute(loc, name, source);
  require_single_value(a.get(), name, source);
  const std::size_t size = H5Tget_size(type.get());
  if (size > limits::max_array_elements)
    throw std::invalid_argument(source + ": attribute '" + name + "': more than " +
                                std::to_string(limits::max_array_elements) + " bytes (docs/formats.md, \"Limits\")");
  std::string buf(size, '\0');
  if (size > 0 && H5Aread(a.get(), type.get(), buf.data()) < 0)  // the file type itself: no conversion, every byte
    throw std::invalid_argument(source + ": attribute '" + name + "': unreadable");
  return buf;
}

std::vector<double> read_table_member(hid_t loc, const std::string& dataset, const std::string& member,
                                      std::size_t& width, const std::string& source) {
  const std::string what = source + ": table '" + dataset + "', member '" + member + "'";
  Handle d(H5Dopen2(loc, dataset.c_str(), H5P_DEFAULT), H5Dclose);
  if (!d.valid()) throw std::invalid_argument(source + ": table '" + dataset + "' is missing");
  Handle space(H5Dget_space(d.get()), H5Sclose);
  if (H5Sget_simple_extent_ndims(space.get()) != 1)
    throw std::invalid_argument(source + ": table '" + dataset + "': expected one dimension of rows");
  hsize_t rows = 0;
  H5Sget_simple_extent_dims(space.get(), &rows, nullptr);
  Handle type(H5Dget_type(d.get()), H5Tclose);
  if (H5Tget_class(type.get()) != H5T_COMPOUND)
    throw std::invalid_argument(source + ": table '" + dataset + "': expected a compound (table) type");
  const int index = H5Tget_member_index(type.get(), member.c_str());
  if (index < 0) throw std::invalid_argument(what + ": missing");
  Handle member_type(H5Tget_member_type(type.get(), unsigned(index)), H5Tclose);
  hsize_t columns = 1;
  H5T_class_t cls = H5Tget_class(member_type.get());
  if (cls == H5T_ARRAY) {
    if (H5Tget_array_ndims(member_type.get()) != 1)
      throw std::invalid_argument(what + ": expected a one-dimensional array per row");
    H5Tget_array_dims2(member_type.get(), &columns);
    Handle base(H5Tget_super(member_type.get()), H5Tclose);
    cls = H5Tget_class(base.get());
  }
  if (cls != H5T_FLOAT && cls != H5T_INTEGER) throw std::invalid_argument(what + ": not numeric");
  if (columns == 0 || rows > limits::max_array_elements || columns > limits::max_array_elements / std::max<hsize_t>(rows, 1))
    throw std::invalid_argument(what + ": " + std::to_string(rows) + " x " + std::to_string(columns) +
                                " values (at most " + std::to_string(limits::max_array_elements) +
                                ", docs/formats.md, \"Limits\")");
  width = static_cast<std::size_t>(columns);
  // A memory compound of just this member, as doubles: HDF5 converts it by name from every row.
  Handle value_type(columns == 1 ? H5Tcopy(H5T_NATIVE_DOUBLE) : H5Tarray_create2(H5T_NATIVE_DOUBLE, 1, &columns),
                    H5Tclose);
  const std::size_t row_bytes = sizeof(double) * width;
  Handle memory(H5Tcreate(H5T_COMPOUND, row_bytes), H5Tclose);
  if (!value_type.valid() || !memory.valid() || H5Tinsert(memory.get(), member.c_str(), 0, value_type.get()) < 0)
    throw std::invalid_argument(what + ": unreadable type");
  std::vector<double> data(static_cast<std::size_t>(rows) * width);
  if (!data.empty() && H5Dread(d.get(), memory.get(), H5S_ALL, H5S_ALL, H5P_DEFAULT, data.data()) < 0)
    throw std::invalid_argument(what + ": cannot read the table");
  return data;
}

std::optional<double> read_double_attribute(hid_t loc, const std::string& name, const std::string& source) {
  if (H5Aexists(loc, name.c_str()) <= 0) return std::nullopt;
  Handle a(H5Aopen(loc, name.c_str(), H5P_DEFAULT), H5Aclose);
  Handle type(H5Aget_type(a.get()), H5Tclose);
  const H5T_class_t cls = H5Tget_class(type.get());
  if (cls != H5T_FLOAT && cls != H5T_INTEGER)
    throw std::invalid_argument(source + ": attribute '" + name + "': expected a number");
  require_single_value(a.get(), name, source);
  double v = 0.0;
  if (H5Aread(a.get(), H5T_NATIVE_DOUBLE, &v) < 0)
    throw std::invalid_argument(source + ": attribute '" + name + "': unreadable");
  return v;
}

void write_string_attribute(hid_t loc, const std::string& name, const std::string& value) {
  const Handle type = utf8_string_type();
  Handle space(H5Screate(H5S_SCALAR), H5Sclose);
  Handle a(H5Acreate2(loc, name.c_str(), type.get(), space.get(), H5P_DEFAULT, H5P_DEFAULT), H5Aclose);
  const char* text = value.c_str();
  if (!a.valid() || H5Awrite(a.get(), type.get(), &text) < 0)
    throw std::runtime_error("cannot write HDF5 attribute '" + name + "'");
}

void write_double_attribute(hid_t loc, const std::string& name, double value) {
  Handle space(H5Screate(H5S_SCALAR), H5Sclose);
  Handle a(H5Acreate2(loc, name.c_str(), H5T_IEEE_F64LE, space.get(), H5P_DEFAULT, H5P_DEFAULT), H5Aclose);
  if (!a.valid() || H5Awrite(a.get(), H5T_NATIVE_DOUBLE, &value) < 0)
    throw std::runtime_error("cannot write HDF5 attribute '" + name + "'");
}

void make_dimension_scale(hid_t loc, const std::string& name) {
  Handle d(H5Dopen2(loc, name.c_str(), H5P_DEFAULT), H5Dclose);
  if (!d.valid() || H5DSset_scale(d.get(), name.substr(name.rfind('/') + 1).c_str()) < 0)
    throw std::runtime_error("cannot make HDF5 dataset '" + name + "' a dimension scale");
}

void attach_dimension_scale(hid_t loc, const std::string& name, unsigned index, hid_t scale_loc,
                            const std::string& scale) {
  Handle d(H5Dopen2(loc, name.c_str(), H5P_DEFAULT), H5Dclose);
  Handle s(H5Dopen2(scale_loc, scale.c_str(), H5P_DEFAULT), H5Dclose);
  if (!d.valid() || !s.valid() || H5DSattach_scale(d.get(), s.get(), index) < 0)
    throw std::runtime_error("cannot attach dimension scale '" + scale + "' to HDF5 dataset '" + name + "'");
}

}  // namespace vibrissa::io::h5
