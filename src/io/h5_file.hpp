#pragma once
// Small RAII helpers over the HDF5 C API (private to the io layer). Numeric data are read and written as
// native double (HDF5 converts integer datasets on read); strings as attributes.
#include <hdf5.h>

#include <optional>
#include <string>
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

Handle create_file(const std::string& path);
Handle open_file_read(const std::string& path);
Handle create_group(hid_t parent, const std::string& name);

bool has_dataset(hid_t loc, const std::string& name);
/// Reads a dataset as doubles (row-major) and its dimensions. Throws naming `source` and `name`.
std::vector<double> read_doubles(hid_t loc, const std::string& name, std::vector<hsize_t>& dims,
                                 const std::string& source);
void write_doubles(hid_t loc, const std::string& name, const std::vector<double>& data,
                   const std::vector<hsize_t>& dims);
void write_bytes(hid_t loc, const std::string& name, const std::vector<unsigned char>& data);
void write_strings(hid_t loc, const std::string& name, const std::vector<std::string>& data);

std::optional<std::string> read_string_attribute(hid_t loc, const std::string& name, const std::string& source);
std::optional<double> read_double_attribute(hid_t loc, const std::string& name, const std::string& source);
void write_string_attribute(hid_t loc, const std::string& name, const std::string& value);
void write_double_attribute(hid_t loc, const std::string& name, double value);

}  // namespace vibrissa::io::h5
