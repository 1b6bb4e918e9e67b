// MATLAB trial files (docs/trials.md): the arrays of the HDF5 layout as top-level variables, or as fields
// of one struct variable named `trial`. Read with matio (v5, v7.3 where matio was built with HDF5).
#include <matio.h>

#include <cstdint>
#include <cstring>
#include <fstream>
#include <memory>
#include <stdexcept>

#include "trial_arrays.hpp"
#include "vibrissa/core/limits.hpp"
#include "vibrissa/io/atomic_file.hpp"
#include "vibrissa/io/trial_io.hpp"

namespace vibrissa::io {

namespace {

struct MatCloser {
  void operator()(mat_t* m) const { Mat_Close(m); }
};
struct VarFreer {
  void operator()(matvar_t* v) const { Mat_VarFree(v); }
};
using MatPtr = std::unique_ptr<mat_t, MatCloser>;
using VarPtr = std::unique_ptr<matvar_t, VarFreer>;

template <class T>
void copy_as_double(const void* data, std::size_t count, std::vector<double>& out) {
  const T* p = static_cast<const T*>(data);
  out.resize(count);
  for (std::size_t i = 0; i < count; ++i) out[i] = static_cast<double>(p[i]);
}

/// Numeric contents of a variable, converted from MATLAB's column-major order to row-major.
NamedArray to_array(const matvar_t* v, const std::string& src, const std::string& name) {
  std::size_t count = 1;
  NamedArray a;
  for (int k = 0; k < v->rank; ++k) {
    a.dims.push_back(v->dims[k]);
    if (v->dims[k] > limits::max_array_elements || count * v->dims[k] > limits::max_array_elements)
      throw std::invalid_argument(src + ": column '" + name + "': more than " +
                                  std::to_string(limits::max_array_elements) + " values (docs/formats.md, \"Limits\")");
    count *= v->dims[k];
  }
  if (v->isComplex) throw std::invalid_argument(src + ": column '" + name + "': complex data are not supported");
  std::vector<double> col;
  if (count > 0 && v->data == nullptr)
    throw std::invalid_argument(src + ": column '" + name + "': variable has no data");
  switch (v->class_type) {
    case MAT_C_DOUBLE: copy_as_double<double>(v->data, count, col); break;
    case MAT_C_SINGLE: copy_as_double<float>(v->data, count, col); break;
    case MAT_C_INT8: copy_as_double<std::int8_t>(v->data, count, col); break;
    case MAT_C_UINT8: copy_as_double<std::uint8_t>(v->data, count, col); break;
    case MAT_C_INT16: copy_as_double<std::int16_t>(v->data, count, col); break;
    case MAT_C_UINT16: copy_as_double<std::uint16_t>(v->data, count, col); break;
    case MAT_C_INT32: copy_as_double<std::int32_t>(v->data, count, col); break;
    case MAT_C_UINT32: copy_as_double<std::uint32_t>(v->data, count, col); break;
    case MAT_C_INT64: copy_as_double<std::int64_t>(v->data, count, col); break;
    case MAT_C_UINT64: copy_as_double<std::uint64_t>(v->data, count, col); break;
    default: throw std::invalid_argument(src + ": column '" + name + "': variable is not a real numeric array");
  }
  // Column-major (MATLAB) -> row-major: element (i0, i1, ...) sits at i0 + d0 (i1 + d1 (...)).
  a.data.resize(count);
  const std::size_t rank = a.dims.size();
  std::vector<std::size_t> idx(rank, 0);
  for (std::size_t r = 0; r < count; ++r) {
    std::size_t cm = 0, stride = 1;
    for (std::size_t k = 0; k < rank; ++k) {
      cm += idx[k] * stride;
      stride *= a.dims[k];
    }
    a.data[r] = col[cm];
    for (std::size_t k = rank; k-- > 0;) {  // advance the row-major multi-index
      if (++idx[k] < a.dims[k]) break;
      idx[k] = 0;
    }
  }
  return a;
}

std::string to_text(const matvar_t* v, const std::string& src, const std::string& name) {
  if (v->class_type != MAT_C_CHAR || v->data == nullptr)
    throw std::invalid_argument(src + ": column '" + name + "': expected a character array");
  std::size_t count = 1;
  for (int k = 0; k < v->rank; ++k) count *= v->dims[k];
  std::string s;
  if (v->data_type == MAT_T_UINT16 || v->data_type == MAT_T_UTF16) {
    const auto* p = static_cast<const std::uint16_t*>(v->data);
    for (std::size_t i = 0; i < count; ++i) s.push_back(static_cast<char>(p[i] < 128 ? p[i] : '?'));
  } else {
    s.assign(static_cast<const char*>(v->data), count);
  }
  return s;
}

}  // namespace

trial::Trial read_trial_mat(const std::string& path) {
  MatPtr mat(Mat_Open(path.c_str(), MAT_ACC_RDONLY));
  if (!mat) throw std::invalid_argument(path + ": cannot open as a MATLAB .mat file");
  VarPtr container(Mat_VarRead(mat.get(), "trial"));
  const bool in_struct = container && container->class_type == MAT_C_STRUCT;
  // Variables stay alive until the trial is assembled.
  std::vector<VarPtr> owned;
  auto lookup = [&](const std::string& name) -> const matvar_t* {
    if (in_struct) return Mat_VarGetStructFieldByName(container.get(), name.c_str(), 0);
    owned.emplace_back(Mat_VarRead(mat.get(), name.c_str()));
    return owned.back().get();
  };
  ArrayReader r;
  r.source = path;
  r.array = [&](const std::string& name) -> std::optional<NamedArray> {
    const matvar_t* v = lookup(name);
    if (!v) return std::nullopt;
    return to_array(v, path, name);
  };
  r.text = [&](const std::string& name) -> std::optional<std::string> {
    const matvar_t* v = lookup(name);
    if (!v) return std::nullopt;
    return to_text(v, path, name);
  };
  r.number = [&](const std::string& name) -> std::optional<double> {
    const matvar_t* v = lookup(name);
    if (!v) return std::nullopt;
    const NamedArray a = to_array(v, path, name);
    if (a.data.size() != 1) throw std::invalid_argument(path + ": column '" + name + "': expected a scalar");
    return a.data[0];
  };
  return assemble_trial(r);
}

namespace {

// matio reports no failed write (1.5.23: a full disk or a file size limit leaves a truncated file and every
// call returns success), so the written file is checked: a MAT v5 file is a 128-byte header and then
// elements, each an 8-byte tag (type, byte count) and its bytes padded to 8; they must end exactly at the end
// of the file, and there must be `variables` of them.
void check_mat5_complete(const std::string& file, const std::string& target, std::size_t variables) {
  std::ifstream in(file, std::ios::binary | std::ios::ate);
  const auto size = static_cast<std::uint64_t>(in ? static_cast<std::streamoff>(in.tellg()) : 0);
  std::uint64_t offset = 128;
  std::size_t elements = 0;
  while (in && offset + 8 <= size) {
    unsigned char tag[8] = {};
    in.seekg(static_cast<std::streamoff>(offset));
    in.read(reinterpret_cast<char*>(tag), 8);
    const std::uint64_t bytes = std::uint64_t(tag[4]) | std::uint64_t(tag[5]) << 8 | std::uint64_t(tag[6]) << 16 |
                                std::uint64_t(tag[7]) << 24;  // little-endian, as matio writes on x86
    offset += 8 + (bytes + 7) / 8 * 8;
    ++elements;
  }
  if (!in || offset != size || elements != variables)
    throw std::runtime_error("cannot write '" + target + "': the .mat file came out incomplete (" +
                             std::to_string(size) + " bytes; disk full or a file size limit?)");
}

void write_trial_mat_variables(const TrialArrays& arrays, const std::string& tmp, const std::string& path) {
  {
    MatPtr mat(Mat_CreateVer(tmp.c_str(), nullptr, MAT_FT_MAT5));
    if (!mat) throw std::runtime_error(path + ": cannot create the .mat file");
    auto put = [&](const std::string& name, matio_classes cls, matio_types type, std::vector<std::size_t> dims,
                   void* data) {
      VarPtr v(Mat_VarCreate(name.c_str(), cls, type, static_cast<int>(dims.size()), dims.data(), data, 0));
      if (!v || Mat_VarWrite(mat.get(), v.get(), MAT_COMPRESSION_NONE) != 0)
        throw std::runtime_error(path + ": cannot write variable '" + name + "'");
    };
    for (const auto& [name, a] : arrays.arrays) {
      // Row-major -> column-major for MATLAB.
      std::vector<std::size_t> dims = a.dims;
      if (dims.size() == 1) dims = {dims[0], 1};
      std::size_t count = a.data.size();
      std::vector<double> col(count);
      const std::size_t rank = dims.size();
      std::vector<std::size_t> idx(rank, 0);
      for (std::size_t r = 0; r < count; ++r) {
        std::size_t cm = 0, stride = 1;
        for (std::size_t k = 0; k < rank; ++k) {
          cm += idx[k] * stride;
          stride *= dims[k];
        }
        col[cm] = a.data[r];
        for (std::size_t k = rank; k-- > 0;) {
          if (++idx[k] < dims[k]) break;
          idx[k] = 0;
        }
      }
      put(name, MAT_C_DOUBLE, MAT_T_DOUBLE, dims, col.data());
    }
    for (const auto& [name, s] : arrays.texts) {
      std::string copy = s;
      put(name, MAT_C_CHAR, MAT_T_UINT8, {1, copy.size()}, copy.data());
    }
    for (const auto& [name, v] : arrays.numbers) {
      double x = v;
      put(name, MAT_C_DOUBLE, MAT_T_DOUBLE, {1, 1}, &x);
    }
    // A struct `units` with one char field per array (units.theta = 'rad'), as HDF5's units attributes.
    std::vector<const char*> fields;
    for (const auto& entry : arrays.arrays) fields.push_back(entry.first.c_str());
    fields.push_back(nullptr);
    const std::size_t one[2] = {1, 1};
    VarPtr units(Mat_VarCreateStruct2("units", 2, one, fields.data()));
    if (!units) throw std::runtime_error(path + ": cannot create variable 'units'");
    for (const auto& [name, a] : arrays.arrays) {
      std::string text = a.units;
      std::size_t dims[2] = {1, text.size()};
      matvar_t* field = Mat_VarCreate(nullptr, MAT_C_CHAR, MAT_T_UINT8, 2, dims, text.data(), 0);
      if (!field) throw std::runtime_error(path + ": cannot write units." + name);
      if (matvar_t* previous = Mat_VarSetStructFieldByName(units.get(), name.c_str(), 0, field)) Mat_VarFree(previous);
    }
    if (Mat_VarWrite(mat.get(), units.get(), MAT_COMPRESSION_NONE) != 0)
      throw std::runtime_error(path + ": cannot write variable 'units'");
  }
}

}  // namespace

void write_trial_mat(const trial::Trial& t, const std::string& path) {
  const TrialArrays arrays = disassemble_trial(t);
  write_atomically(path, [&](const std::string& tmp) {
    write_trial_mat_variables(arrays, tmp, path);
    check_mat5_complete(tmp, path, arrays.arrays.size() + arrays.texts.size() + arrays.numbers.size() + 1);
  });
}

}  // namespace vibrissa::io
