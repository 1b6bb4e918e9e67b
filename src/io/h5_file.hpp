#pragma once
// The one RAII wrapper of the HDF5 C API (private to the library), used by trial files, trial results, array
// outputs and the DeepLabCut HDF5 reader (src/recon/dlc_h5.cpp). Numeric data are read as native double (HDF5
// converts integer datasets on read) and written little-endian in the type of the vector; strings are written
// as variable-length UTF-8 (netCDF-4's "string": h5py, xarray's netCDF4 and h5netcdf engines and MATLAB read
// them as text) and read in either form. Dimension scales (hdf5_hl) name the dimensions of datasets, so that
// netCDF-4 readers see named dimensions with coordinates (io/labelled_data.hpp).
#include <hdf5.h>

#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <utility>
#include <vector>

namespace vibrissa::io::h5 {

/// Owns one hid_t and closes it with the matching H5?close.
class Handle {
 public:
  Handle() = default;
  Handle(hid_t id, herr_t (*close)(hid_t)) : id_(id), close_(close) {}
  Handle(const Handle&) = delete;
  Handle& operator=(const Handle&) = delete;
  Handle(Handle&& o) noexcept : id_(o.id_), close_(o.close_) { o.id_ = H5I_INVALID_HID; }
  Handle& operator=(Handle&& o) noexcept;
  ~Handle() { reset(); }
  void reset();
  [[nodiscard]] hid_t get() const { return id_; }
  [[nodiscard]] bool valid() const { return id_ >= 0; }
  /// Gives up ownership (the caller closes the id).
  [[nodiscard]] hid_t release();

 private:
  hid_t id_ = H5I_INVALID_HID;
  herr_t (*close_)(hid_t) = nullptr;
};

/// Turns off HDF5's automatic error printing for the lifetime of the object.
class QuietErrors {
 public:
  QuietErrors();
  ~QuietErrors();
  QuietErrors(const QuietErrors&) = delete;
  QuietErrors& operator=(const QuietErrors&) = delete;

 private:
  H5E_auto2_t func_ = nullptr;
  void* data_ = nullptr;
};

/// A new HDF5 file for `path`, built in memory: nothing is written until close_file.
Handle create_file(const std::string& path);
Handle open_file_read(const std::string& path);
/// Writes a file made by create_file to its path and closes it; reports failure (a full disk shows here) with
/// the system's reason; `path` names it in the error. Close every group and dataset of the file first.
void close_file(Handle& file, const std::string& path);
Handle create_group(hid_t parent, const std::string& name);

bool has_dataset(hid_t loc, const std::string& name);
/// Names of the links (datasets, groups) in a group or file.
std::vector<std::string> member_names(hid_t group);
/// Dimensions of dataset `name`; nullopt if absent.
std::optional<std::vector<hsize_t>> dataset_dims(hid_t loc, const std::string& name);
/// Reads a dataset as doubles (row-major) and its dimensions. Throws naming `source` and `name`, also for
/// more than limits::max_array_elements values (checked before reading).
std::vector<double> read_doubles(hid_t loc, const std::string& name, std::vector<hsize_t>& dims,
                                 const std::string& source);

/// Every dataset written states its units (docs/formats.md, "Units and codes"): "1" dimensionless, "rad",
/// "code" for enum codes (then `codes` gives the code table), "text" for strings.
struct DatasetOptions {
  DatasetOptions(std::string units_, bool compress_ = false, std::string codes_ = {}, std::string long_name_ = {})
      : units(std::move(units_)), compress(compress_), codes(std::move(codes_)), long_name(std::move(long_name_)) {}
  std::string units;      ///< the dataset's "units" attribute; required (std::logic_error when empty)
  bool compress = false;  ///< chunk + deflate datasets of more than 4096 values (mostly-zero arrays shrink)
  std::string codes;      ///< the "codes" attribute of a code dataset ("0 free, 1 contact, ...") unless empty
  std::string long_name;  ///< the "long_name" attribute (CF: what the values are, in words) unless empty
};
void write_dataset(hid_t loc, const std::string& name, std::span<const double> data,
                   const std::vector<hsize_t>& dims, const DatasetOptions& options);
void write_dataset(hid_t loc, const std::string& name, std::span<const float> data,
                   const std::vector<hsize_t>& dims, const DatasetOptions& options);
void write_dataset(hid_t loc, const std::string& name, std::span<const int> data,
                   const std::vector<hsize_t>& dims, const DatasetOptions& options);
void write_dataset(hid_t loc, const std::string& name, std::span<const std::int16_t> data,
                   const std::vector<hsize_t>& dims, const DatasetOptions& options);
void write_dataset(hid_t loc, const std::string& name, std::span<const std::int8_t> data,
                   const std::vector<hsize_t>& dims, const DatasetOptions& options);
/// One dimension of variable-length UTF-8 strings (units "text" unless `options` say otherwise).
void write_strings(hid_t loc, const std::string& name, std::span<const std::string> data,
                   const DatasetOptions& options);

std::optional<std::string> read_string_attribute(hid_t loc, const std::string& name, const std::string& source);
/// A fixed-length string attribute with every byte (embedded NULs and padding kept; a binary pickle);
/// variable-length strings as read_string_attribute.
std::optional<std::string> read_string_attribute_bytes(hid_t loc, const std::string& name,
                                                      const std::string& source);
/// One member of a one-dimensional compound dataset (a PyTables table), scalar or a one-dimensional array
/// per row, as doubles (rows x width, row-major); `width` is set to the array length (1 for a scalar).
/// Throws naming `source`, the dataset and the member, also for more than limits::max_array_elements values.
std::vector<double> read_table_member(hid_t loc, const std::string& dataset, const std::string& member,
                                      std::size_t& width, const std::string& source);
std::optional<double> read_double_attribute(hid_t loc, const std::string& name, const std::string& source);
/// A scalar variable-length UTF-8 string attribute.
void write_string_attribute(hid_t loc, const std::string& name, const std::string& value);
void write_double_attribute(hid_t loc, const std::string& name, double value);

/// Makes one-dimensional dataset `name` the dimension scale of the dimension of the same name: a netCDF
/// coordinate variable (docs/formats.md, "Labelled HDF5 outputs").
void make_dimension_scale(hid_t loc, const std::string& name);
/// Attaches dimension scale `scale` (a dataset path from `scale_loc`) to dimension `index` of dataset `name`.
void attach_dimension_scale(hid_t loc, const std::string& name, unsigned index, hid_t scale_loc,
                            const std::string& scale);

}  // namespace vibrissa::io::h5
