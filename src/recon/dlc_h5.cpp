// DeepLabCut HDF5 tracks (docs/reconstruction.md, "Track files"): the pandas "table" format DeepLabCut writes
// with df.to_hdf(path, "df_with_missing", format="table"). PyTables lays it out as a group with a compound
// dataset "table" (an "index" member, the frame, and one array member per block of same-typed columns,
// "values_block_0", ...) and pickled attributes: the group's "non_index_axes" holds the column MultiIndex as
// [(1, [(scorer, [individual,] bodypart, coord), ...])], "values_cols" the block names, and the table's
// "<block>_kind" the labels of each block's columns.
#include <cmath>
#include <map>
#include <stdexcept>

#include "../io/h5_file.hpp"
#include "dlc_columns.hpp"
#include "pickled_value.hpp"
#include "text_cells.hpp"
#include "vibrissa/recon/tracks.hpp"

namespace vibrissa::recon {

namespace {

namespace h5 = vibrissa::io::h5;
using Kind = PickledValue::Kind;

std::string attribute_name(const std::string& path, const std::string& node, const std::string& name) {
  return path + ": " + node + " attribute '" + name + "'";
}

PickledValue read_pickled_attribute(hid_t loc, const std::string& path, const std::string& node,
                                    const std::string& name) {
  const auto bytes = h5::read_string_attribute_bytes(loc, name, path);
  if (!bytes) throw std::invalid_argument(attribute_name(path, node, name) + ": missing (not a pandas table?)");
  return read_pickle(*bytes, attribute_name(path, node, name));
}

const PickledValue& expect(const PickledValue& v, Kind kind, const std::string& where) {
  if (v.kind != kind)
    throw std::invalid_argument(where + ": expected a " + kind_name(kind) + ", got a " + kind_name(v.kind));
  return v;
}

/// A column label: a tuple of 3 (scorer, bodypart, coord) or 4 (scorer, individual, bodypart, coord) strings.
std::vector<std::string> label_of(const PickledValue& v, const std::string& where) {
  if (v.kind == Kind::string)
    throw std::invalid_argument(where + ": the columns are not a MultiIndex (scorer, [individuals,] bodyparts, "
                                        "coords): '" + v.string + "'");
  expect(v, Kind::tuple, where);
  if (v.items.size() != 3 && v.items.size() != 4)
    throw std::invalid_argument(where + ": a column label has " + std::to_string(v.items.size()) +
                                " levels; DeepLabCut writes 3 (scorer, bodyparts, coords) or 4 (with individuals)");
  std::vector<std::string> out;
  for (const auto& level : v.items) out.push_back(expect(*level, Kind::string, where).string);
  return out;
}

std::vector<std::vector<std::string>> labels_of(const PickledValue& list, const std::string& where) {
  std::vector<std::vector<std::string>> out;
  for (const auto& item : expect(list, Kind::list, where).items) out.push_back(label_of(*item, where));
  return out;
}

}  // namespace

Tracks2D read_dlc_h5(const std::string& path, const std::vector<std::string>& bodyparts,
                     const std::string& individual) {
  const h5::QuietErrors quiet;
  const h5::Handle file = h5::open_file_read(path);
  std::string key = "df_with_missing";
  if (!h5::has_dataset(file.get(), key)) {
    const auto names = h5::member_names(file.get());
    if (names.size() != 1)
      throw std::invalid_argument(path + ": no pandas table 'df_with_missing' (and not exactly one other key)");
    key = names.front();
  }
  const h5::Handle group(H5Gopen2(file.get(), key.c_str(), H5P_DEFAULT), H5Gclose);
  if (!group.valid()) throw std::invalid_argument(path + ": '" + key + "' is not a group (not a pandas table)");
  const std::string node = "group '" + key + "'";
  if (const auto type = h5::read_string_attribute(group.get(), "pandas_type", path); type != "frame_table")
    throw std::invalid_argument(path + ": " + node + " attribute 'pandas_type': '" + type.value_or("") +
                                "', expected 'frame_table' (write with to_hdf(..., format=\"table\"))");

  // The columns, in file order.
  const std::string axes_where = attribute_name(path, node, "non_index_axes");
  const PickledValue axes = read_pickled_attribute(group.get(), path, node, "non_index_axes");
  if (expect(axes, Kind::list, axes_where).items.size() != 1)
    throw std::invalid_argument(axes_where + ": expected one axis of columns");
  const PickledValue& axis = expect(*axes.items[0], Kind::tuple, axes_where);
  if (axis.items.size() != 2 || axis.items[0]->kind != Kind::integer || axis.items[0]->integer != 1)
    throw std::invalid_argument(axes_where + ": expected (1, [column labels])");
  const auto labels = labels_of(*axis.items[1], axes_where);
  if (labels.empty()) throw std::invalid_argument(axes_where + ": no columns");
  const std::size_t levels = labels.front().size();

  // Where each label lives: block and column within the block.
  const std::string table = key + "/table";
  const h5::Handle table_set(H5Dopen2(file.get(), table.c_str(), H5P_DEFAULT), H5Dclose);
  if (!table_set.valid()) throw std::invalid_argument(path + ": dataset '" + table + "' is missing");
  const std::string blocks_where = attribute_name(path, node, "values_cols");
  const PickledValue blocks = read_pickled_attribute(group.get(), path, node, "values_cols");
  std::map<std::vector<std::string>, std::pair<std::size_t, std::size_t>> place;
  std::vector<std::vector<double>> block_values;
  std::vector<std::size_t> block_width;
  std::size_t rows = 0;
  for (const auto& block : expect(blocks, Kind::list, blocks_where).items) {
    const std::string& name = expect(*block, Kind::string, blocks_where).string;
    const std::string kind_where = attribute_name(path, "dataset '" + table + "'", name + "_kind");
    const auto kinds = labels_of(read_pickled_attribute(table_set.get(), path, "dataset '" + table + "'", name + "_kind"),
                                 kind_where);
    std::size_t width = 0;
    block_values.push_back(h5::read_table_member(file.get(), table, name, width, path));
    block_width.push_back(width);
    if (kinds.size() != width)
      throw std::invalid_argument(kind_where + ": " + std::to_string(kinds.size()) + " labels for " +
                                  std::to_string(width) + " columns");
    rows = block_values.back().size() / width;
    for (std::size_t c = 0; c < width; ++c)
      if (!place.emplace(kinds[c], std::make_pair(block_values.size() - 1, c)).second)
        throw std::invalid_argument(kind_where + ": column label repeated");
  }
  std::vector<DlcColumn> columns;
  std::vector<std::pair<std::size_t, std::size_t>> source;
  for (const auto& l : labels) {
    if (l.size() != levels) throw std::invalid_argument(axes_where + ": column labels of different lengths");
    const auto it = place.find(l);
    if (it == place.end())
      throw std::invalid_argument(axes_where + ": column (" + l[levels - 2] + ", " + l[levels - 1] +
                                  ") is in no values block");
    if (block_values[it->second.first].size() / block_width[it->second.first] != rows)
      throw std::invalid_argument(path + ": values blocks of different lengths");
    columns.push_back({levels == 4 ? l[1] : std::string(), l[levels - 2], l[levels - 1]});
    source.push_back(it->second);
  }
  const DlcColumns selection = select_dlc_columns(columns, bodyparts, individual, path);

  // The frame index: integers ("index" member); any other index (image paths) keeps the row order.
  std::vector<double> index;
  {
    std::size_t width = 0;
    try {
      index = h5::read_table_member(file.get(), table, "index", width, path);
    } catch (const std::invalid_argument&) {
      index.clear();
    }
    if (width != 1 || index.size() != rows) index.clear();
  }
  Tracks2D t;
  t.source = path;
  std::vector<double> values(columns.size());
  for (std::size_t r = 0; r < rows; ++r) {
    std::int64_t frame = std::int64_t(r);
    if (!index.empty()) {
      const double f = index[r];
      if (!(f >= 0.0 && f <= 9.0e15) || f != std::floor(f))
        throw std::invalid_argument(cell_message(path, 0, "index", "row " + std::to_string(r) + ": " +
                                                                       std::to_string(f) +
                                                                       " is not a non-negative integer frame"));
      frame = std::int64_t(f);
    }
    for (std::size_t c = 0; c < columns.size(); ++c) {
      const auto [b, k] = source[c];
      const double v = block_values[b][r * block_width[b] + k];
      if (std::isinf(v))
        throw std::invalid_argument(cell_message(path, 0, columns[c].bodypart + "." + columns[c].coord,
                                                 "frame " + std::to_string(frame) + ": not a finite number"));
      values[c] = v;
    }
    append_dlc_frame(t, frame, values, selection, 0);
  }
  return t;
}

}  // namespace vibrissa::recon
