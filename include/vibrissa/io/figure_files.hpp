#pragma once
// Names of the figures the tools draw beside their outputs (scripts in figures/), in one place: the CLI
// passes them to the scripts, and the output writers remove those of an older run when new results land
// (with or without --no-figures), so a directory never mixes figures of one run with data of another.
#include <array>
#include <filesystem>
#include <span>
#include <string_view>

namespace vibrissa::io {

/// `vibrissa trial`: one folder of PNGs (figures/trial_figures.py).
inline constexpr std::string_view kTrialFiguresFolder = "figures";
inline constexpr std::array<std::string_view, 1> kTrialFigures = {kTrialFiguresFolder};

/// `vibrissa array`: traces, animation (MP4 or GIF) with its still frame, the head-pitch sweep and the viewer.
inline constexpr std::string_view kArrayTracesFigure = "array_traces.png";
inline constexpr std::string_view kArrayAnimationMp4 = "array_animation.mp4";
inline constexpr std::string_view kArrayAnimationGif = "array_animation.gif";
inline constexpr std::string_view kArrayAnimationStill = "array_animation_frame.png";  ///< named by the script
inline constexpr std::string_view kArrayPitchSweepFigure = "pitch_sweep.png";
/// The interactive 3D viewer, one self-contained HTML page (python/vibrissa/viewer.py, docs/viewer.md).
inline constexpr std::string_view kArrayViewer = "view.html";
inline constexpr std::array<std::string_view, 6> kArrayFigures = {kArrayTracesFigure,   kArrayAnimationMp4,
                                                                  kArrayAnimationGif,   kArrayAnimationStill,
                                                                  kArrayPitchSweepFigure, kArrayViewer};

/// Removes each name (file or folder) from `dir` if present; throws std::runtime_error naming the path.
void remove_figures(const std::filesystem::path& dir, std::span<const std::string_view> names);

}  // namespace vibrissa::io
