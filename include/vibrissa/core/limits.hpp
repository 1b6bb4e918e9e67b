#pragma once
// Upper bounds on every size an input can ask for (docs/formats.md, "Limits"). Readers, validate()
// functions, CLI flags and Python arguments check against these, so that no input — careless or hostile —
// can exhaust memory, threads or the stack. Values beyond them are rejected with std::invalid_argument.
#include <cstddef>
#include <cstdint>

namespace vibrissa::limits {

/// Rigid links of a whisker model (the spec uses 100).
inline constexpr int max_links = 200'000;
/// Points in a rest shape (whisker.points, a trial's rest_shape, a tracked shape per frame).
inline constexpr std::size_t max_shape_points = 100'000;
/// Levenberg-Marquardt iterations per attempt.
inline constexpr int max_iterations = 1'000'000;
/// Frames of one trial (1000 s at 1 kHz).
inline constexpr std::size_t max_trial_frames = 1'000'000;
/// Edges of a trial's object, objects of an array scene.
inline constexpr std::size_t max_edges = 10'000;
/// Whiskers of a morphology table.
inline constexpr std::size_t max_whiskers = 10'000;
/// Frames of an array run (time.frames or time.times_s).
inline constexpr std::size_t max_array_frames = 1'000'000;
/// Whisker-frame samples of one array run: frames x whiskers x pitches.
inline constexpr std::size_t max_array_samples = 10'000'000;
/// Entries of any other list read from a file (pitches, series, radii, moduli).
inline constexpr std::size_t max_list_length = 1'000'000;
/// OpenMP threads a run may ask for.
inline constexpr int max_threads = 1024;
/// Nesting depth of a JSON document (objects and arrays).
inline constexpr int max_json_depth = 64;
/// Size of a JSON file (case or array config) [bytes].
inline constexpr std::uintmax_t max_json_file_bytes = 64ull << 20;
/// Size of a CSV file (trial, morphology table) [bytes].
inline constexpr std::uintmax_t max_csv_file_bytes = 1ull << 30;
/// Length of one CSV line [bytes].
inline constexpr std::size_t max_csv_line_bytes = 4u << 20;
/// Elements of one HDF5 or MATLAB array.
inline constexpr std::size_t max_array_elements = 64'000'000;
/// Links of a whisker in dynamics (docs/dynamics.md): the mass matrix and the modes are dense in 3N.
inline constexpr int max_dynamics_links = 2'000;
/// Range of a whisker's arc length [m] (beyond it the model's scaling over- or underflows; lengths outside
/// 1 mm - 200 mm only draw a plausibility warning).
inline constexpr double min_whisker_length_m = 1e-6;
inline constexpr double max_whisker_length_m = 1e3;
/// Range of radii [m], Young's moduli [Pa] and taper ratios accepted by the model.
inline constexpr double min_radius_m = 1e-9;
inline constexpr double max_radius_m = 1.0;
inline constexpr double min_youngs_modulus_Pa = 1.0;
inline constexpr double max_youngs_modulus_Pa = 1e15;
inline constexpr double max_taper_ratio = 1e4;
/// Range of the elastic base's rotational stiffness [N m/rad] (a rat whisker's own EI/L is ~1e-5; beyond the
/// range the base compliance 1/k over- or underflows the solver's scaling).
inline constexpr double min_base_stiffness_Nm_per_rad = 1e-12;
inline constexpr double max_base_stiffness_Nm_per_rad = 1e12;
/// Characters of an input value quoted in an error message; longer values are cut.
inline constexpr std::size_t max_quoted_chars = 200;

}  // namespace vibrissa::limits
