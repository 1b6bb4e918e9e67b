// Labelled HDF5 outputs (io/labelled_data.hpp): every dimension of every dataset has a dimension scale, its
// coordinate variable; strings are variable-length UTF-8; a table that would give a dimension no coordinate or
// two lengths is an internal error, not a file. The files' reading by xarray with both netCDF-4 engines is
// tested in python/tests/test_labelled_outputs.py.
#include <gtest/gtest.h>
#include <hdf5_hl.h>

#include <string>
#include <vector>

#include "fresh_dir.hpp"
#include "io/h5_file.hpp"
#include "vibrissa/core/checks.hpp"
#include "vibrissa/io/labelled_data.hpp"

namespace vibrissa::io {
namespace {

LabelledData small_table(const std::vector<double>& time, const std::vector<double>& force) {
  LabelledData d;
  d.variables.push_back({.name = "time", .dims = {"time"}, .shape = {time.size()}, .values = std::span(time),
                         .units = "s", .long_name = "time of the frame"});
  d.add_component_coordinate();
  d.variables.push_back({.name = "force_W", .dims = {"time", "component"}, .shape = {time.size(), 3},
                         .values = std::span(force), .units = "N", .long_name = "force, world frame"});
  d.add_owned({.name = "names", .dims = {"time"}, .shape = {time.size()}, .units = "text"},
              std::vector<std::string>{"a", "b\xc2\xb5"});  // UTF-8 kept as is
  d.add_index_coordinate("render", "node", 4, "node");
  d.add_owned({.name = "render/shape", .dims = {"time", "node", "component"}, .shape = {2, 4, 3}, .units = "m"},
              std::vector<double>(24, 1.0));
  d.attributes = {{"", "format", "test"}, {"render", "pitch_index", 0.0}};
  return d;
}

std::string scale_name(hid_t dataset, unsigned index) {
  std::string name;
  H5DSiterate_scales(
      dataset, index, nullptr,
      [](hid_t, unsigned, hid_t scale, void* out) -> herr_t {
        char buffer[64] = {};
        H5Iget_name(scale, buffer, sizeof buffer);
        *static_cast<std::string*>(out) = buffer;
        return 1;
      },
      &name);
  return name;
}

TEST(LabelledH5, EveryDimensionOfEveryDatasetHasItsCoordinateAsScale) {
  const std::vector<double> time{0.0, 0.5}, force{1, 2, 3, 4, 5, 6};
  const std::string path = (test::fresh_dir("labelled") / "l.h5").string();
  write_labelled_h5(small_table(time, force), path);

  h5::Handle file = h5::open_file_read(path);
  for (const char* scale : {"time", "component", "render/node"}) {
    h5::Handle d(H5Dopen2(file.get(), scale, H5P_DEFAULT), H5Dclose);
    EXPECT_GT(H5DSis_scale(d.get()), 0) << scale;
  }
  const std::pair<const char*, std::vector<std::string>> expected[] = {
      {"force_W", {"/time", "/component"}},
      {"names", {"/time"}},
      {"render/shape", {"/time", "/render/node", "/component"}}};
  for (const auto& [name, scales] : expected) {
    h5::Handle d(H5Dopen2(file.get(), name, H5P_DEFAULT), H5Dclose);
    EXPECT_EQ(H5DSis_scale(d.get()), 0) << name;
    for (unsigned i = 0; i < scales.size(); ++i) EXPECT_EQ(scale_name(d.get(), i), scales[i]) << name << " dim " << i;
  }
  // Strings: variable-length UTF-8, datasets and attributes alike.
  h5::Handle names(H5Dopen2(file.get(), "names", H5P_DEFAULT), H5Dclose);
  h5::Handle type(H5Dget_type(names.get()), H5Tclose);
  EXPECT_GT(H5Tis_variable_str(type.get()), 0);
  EXPECT_EQ(H5Tget_cset(type.get()), H5T_CSET_UTF8);
  h5::Handle attribute(H5Aopen(names.get(), "units", H5P_DEFAULT), H5Aclose);
  h5::Handle attribute_type(H5Aget_type(attribute.get()), H5Tclose);
  EXPECT_GT(H5Tis_variable_str(attribute_type.get()), 0);
  EXPECT_EQ(h5::read_string_attribute(names.get(), "units", path), "text");
  h5::Handle force_W(H5Dopen2(file.get(), "force_W", H5P_DEFAULT), H5Dclose);
  EXPECT_EQ(h5::read_string_attribute(force_W.get(), "long_name", path), "force, world frame");
  EXPECT_EQ(h5::read_string_attribute(file.get(), "format", path), "test");
  std::vector<hsize_t> dims;
  EXPECT_EQ(h5::read_doubles(file.get(), "force_W", dims, path), force);
  EXPECT_EQ(dims, (std::vector<hsize_t>{2, 3}));
}

TEST(LabelledH5, AnInconsistentTableIsAnInternalError) {
  const std::vector<double> time{0.0, 0.5}, force{1, 2, 3, 4, 5, 6}, three_times{0, 1, 2};
  const std::string path = (test::fresh_dir("labelled_bad") / "l.h5").string();
  {
    LabelledData d = small_table(time, force);
    d.variables.push_back({.name = "bare", .dims = {"sample"}, .shape = {3}, .values = std::span(three_times),
                           .units = "1"});  // no coordinate variable "sample"
    EXPECT_THROW(write_labelled_h5(d, path), InternalError);
  }
  {
    LabelledData d = small_table(time, force);
    d.variables.push_back({.name = "longer", .dims = {"time"}, .shape = {3}, .values = std::span(three_times),
                           .units = "1"});  // time has 2 values
    EXPECT_THROW(write_labelled_h5(d, path), InternalError);
  }
  {
    LabelledData d = small_table(time, force);
    d.variables.push_back({.name = "short", .dims = {"time", "component"}, .shape = {2, 3},
                           .values = std::span(three_times), .units = "1"});  // 3 values for 6
    EXPECT_THROW(write_labelled_h5(d, path), InternalError);
  }
}

}  // namespace
}  // namespace vibrissa::io
