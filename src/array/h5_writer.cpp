#include "h5_writer.hpp"

#include <algorithm>
#include <cstring>
#include <stdexcept>

namespace vibrissa::array::h5 {

Id::Id(hid_t id, herr_t (*close)(hid_t), const std::string& what) : id_(id), close_(close) {
  if (id_ < 0) throw std::runtime_error("HDF5: cannot " + what);
}
Id::~Id() {
  if (id_ >= 0 && close_) close_(id_);
}

Writer::Writer(const std::string& path)
    : file_(H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT), H5Fclose, "create '" + path + "'") {}

Id Writer::group(const std::string& name) {
  return Id(H5Gcreate2(file_.get(), name.c_str(), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT), H5Gclose,
            "create group " + name);
}

void Writer::write_raw(hid_t loc, const std::string& name, hid_t type, const void* data,
                       const std::vector<hsize_t>& dims, const std::string& units) {
  const Id space(H5Screate_simple(static_cast<int>(dims.size()), dims.data(), nullptr), H5Sclose,
                 "create dataspace for " + name);
  // Chunked + deflate for big arrays keeps the file small (most frames hold zeros).
  const Id plist(H5Pcreate(H5P_DATASET_CREATE), H5Pclose, "create property list");
  hsize_t total = 1;
  for (hsize_t d : dims) total *= d;
  if (total > 4096 && !dims.empty()) {
    std::vector<hsize_t> chunk(dims);
    for (std::size_t i = 0; i + 1 < chunk.size() && total > 65536; ++i) {
      total /= chunk[i];
      chunk[i] = 1;
    }
    H5Pset_chunk(plist.get(), static_cast<int>(chunk.size()), chunk.data());
    H5Pset_deflate(plist.get(), 4);
  }
  const Id set(H5Dcreate2(loc, name.c_str(), type, space.get(), H5P_DEFAULT, plist.get(), H5P_DEFAULT), H5Dclose,
               "create dataset " + name);
  if (H5Dwrite(set.get(), type, H5S_ALL, H5S_ALL, H5P_DEFAULT, data) < 0)
    throw std::runtime_error("HDF5: cannot write dataset " + name);
  if (!units.empty()) attribute(set.get(), "units", units);
}

void Writer::write(hid_t loc, const std::string& name, const std::vector<double>& v, const std::vector<hsize_t>& dims,
                   const std::string& units) {
  write_raw(loc, name, H5T_NATIVE_DOUBLE, v.data(), dims, units);
}
void Writer::write(hid_t loc, const std::string& name, const std::vector<float>& v, const std::vector<hsize_t>& dims,
                   const std::string& units) {
  write_raw(loc, name, H5T_NATIVE_FLOAT, v.data(), dims, units);
}
void Writer::write(hid_t loc, const std::string& name, const std::vector<std::int8_t>& v,
                   const std::vector<hsize_t>& dims, const std::string& units) {
  write_raw(loc, name, H5T_NATIVE_INT8, v.data(), dims, units);
}
void Writer::write(hid_t loc, const std::string& name, const std::vector<std::int16_t>& v,
                   const std::vector<hsize_t>& dims, const std::string& units) {
  write_raw(loc, name, H5T_NATIVE_INT16, v.data(), dims, units);
}
void Writer::write(hid_t loc, const std::string& name, const std::vector<int>& v, const std::vector<hsize_t>& dims,
                   const std::string& units) {
  write_raw(loc, name, H5T_NATIVE_INT, v.data(), dims, units);
}

void Writer::write_strings(hid_t loc, const std::string& name, const std::vector<std::string>& v) {
  std::size_t width = 1;
  for (const auto& s : v) width = std::max(width, s.size() + 1);
  std::vector<char> buffer(width * std::max<std::size_t>(v.size(), 1), '\0');
  for (std::size_t i = 0; i < v.size(); ++i) std::memcpy(&buffer[i * width], v[i].data(), v[i].size());
  const Id type(H5Tcopy(H5T_C_S1), H5Tclose, "copy string type");
  H5Tset_size(type.get(), width);
  H5Tset_strpad(type.get(), H5T_STR_NULLTERM);
  const std::vector<hsize_t> dims{static_cast<hsize_t>(v.size())};
  write_raw(loc, name, type.get(), buffer.data(), dims, "");
}

void Writer::attribute(hid_t loc, const std::string& name, const std::string& value) {
  const Id type(H5Tcopy(H5T_C_S1), H5Tclose, "copy string type");
  H5Tset_size(type.get(), std::max<std::size_t>(value.size(), 1));
  const Id space(H5Screate(H5S_SCALAR), H5Sclose, "create scalar space");
  const Id attr(H5Acreate2(loc, name.c_str(), type.get(), space.get(), H5P_DEFAULT, H5P_DEFAULT), H5Aclose,
                "create attribute " + name);
  const std::string padded = value.empty() ? std::string(1, '\0') : value;
  H5Awrite(attr.get(), type.get(), padded.data());
}

void Writer::attribute(hid_t loc, const std::string& name, double value) {
  const Id space(H5Screate(H5S_SCALAR), H5Sclose, "create scalar space");
  const Id attr(H5Acreate2(loc, name.c_str(), H5T_NATIVE_DOUBLE, space.get(), H5P_DEFAULT, H5P_DEFAULT), H5Aclose,
                "create attribute " + name);
  H5Awrite(attr.get(), H5T_NATIVE_DOUBLE, &value);
}

}  // namespace vibrissa::array::h5
