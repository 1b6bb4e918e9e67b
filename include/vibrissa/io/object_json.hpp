#pragma once
// Objects in JSON (docs/formats.md, "Objects"): the same description in `vibrissa solve` cases (SI names:
// "radius") and array configurations (lengths in mm: "radius_mm"), and the self-contained description outputs
// record (SI), from which a viewer or a figure draws the object again.
//   {"type": "cylinder", "point": [3], "axis": [3], "radius": R, "length": l}    (length omitted: infinite)
//   {"type": "plane", "point": [3], "normal": [3]}
//   {"type": "sphere", "centre": [3], "radius": R}
//   {"type": "box", "centre": [3], "half_extents": [3], "rotation": [[3], [3], [3]]}   (rows; default identity)
//   {"type": "mesh", "file": "bunny.stl", "file_unit": "m" | "mm" | "um", "translation": [3], "rotation": [[..]]}
#include <filesystem>
#include <memory>
#include <string>

#include <nlohmann/json.hpp>

#include "vibrissa/objects/shape.hpp"

namespace vibrissa::io {

/// How lengths are written in the JSON being read: SI ("radius") or millimetres ("radius_mm").
enum class LengthKeys { metres, millimetres };

/// The shape of an object description; `where` names it in messages ("load.object", "objects[2]"), relative mesh
/// files are taken from `base_dir`. Unknown keys are errors. Keys other than the shape's (e.g. "frame") are
/// allowed if listed in `extra_keys`.
std::shared_ptr<const Shape> shape_from_json(const nlohmann::json& j, const std::string& where, LengthKeys keys,
                                             const std::filesystem::path& base_dir = {},
                                             std::initializer_list<const char*> extra_keys = {});

/// The description outputs record (SI; ShapeDescription's values, a mesh's file).
nlohmann::json shape_to_json(const Shape& shape);

}  // namespace vibrissa::io
