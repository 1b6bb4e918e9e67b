#pragma once
// Minimal RAII writer over the HDF5 C API, private to the array layer (datasets of double, float, int8,
// int16, fixed-length strings; string and double attributes).
#include <hdf5.h>

#include <cstdint>
#include <string>
#include <vector>

namespace vibrissa::array::h5 {

class Id {
 public:
  Id(hid_t id, herr_t (*close)(hid_t), const std::string& what);
  Id(const Id&) = delete;
  Id& operator=(const Id&) = delete;
  ~Id();
  [[nodiscard]] hid_t get() const { return id_; }

 private:
  hid_t id_;
  herr_t (*close_)(hid_t);
};

class Writer {
 public:
  explicit Writer(const std::string& path);
  [[nodiscard]] hid_t root() const { return file_.get(); }
  /// Creates group `name` under `parent` (or the root) and returns its id wrapper.
  Id group(const std::string& name);

  void write(hid_t loc, const std::string& name, const std::vector<double>& v, const std::vector<hsize_t>& dims,
             const std::string& units = "");
  void write(hid_t loc, const std::string& name, const std::vector<float>& v, const std::vector<hsize_t>& dims,
             const std::string& units = "");
  void write(hid_t loc, const std::string& name, const std::vector<std::int8_t>& v, const std::vector<hsize_t>& dims,
             const std::string& units = "");
  void write(hid_t loc, const std::string& name, const std::vector<std::int16_t>& v,
             const std::vector<hsize_t>& dims, const std::string& units = "");
  void write(hid_t loc, const std::string& name, const std::vector<int>& v, const std::vector<hsize_t>& dims,
             const std::string& units = "");
  void write_strings(hid_t loc, const std::string& name, const std::vector<std::string>& v);
  void attribute(hid_t loc, const std::string& name, const std::string& value);
  void attribute(hid_t loc, const std::string& name, double value);

 private:
  void write_raw(hid_t loc, const std::string& name, hid_t type, const void* data, const std::vector<hsize_t>& dims,
                 const std::string& units);
  Id file_;
};

}  // namespace vibrissa::array::h5
