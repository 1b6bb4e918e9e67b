# Sources of the recon layer: from 2D whisker tracks in two camera views to 3D shapes and trials
# (docs/reconstruction.md). Track and calibration formats live here too.
target_sources(vibrissa PRIVATE
  ${CMAKE_CURRENT_LIST_DIR}/camera.cpp
  ${CMAKE_CURRENT_LIST_DIR}/correspondences.cpp
  ${CMAKE_CURRENT_LIST_DIR}/curve_fit.cpp
  ${CMAKE_CURRENT_LIST_DIR}/curve_reprojection.cpp
  ${CMAKE_CURRENT_LIST_DIR}/dlc_files.cpp
  ${CMAKE_CURRENT_LIST_DIR}/dlc_h5.cpp
  ${CMAKE_CURRENT_LIST_DIR}/geometry.cpp
  ${CMAKE_CURRENT_LIST_DIR}/pickled_value.cpp
  ${CMAKE_CURRENT_LIST_DIR}/reconstruct.cpp
  ${CMAKE_CURRENT_LIST_DIR}/reconstruct_files.cpp
  ${CMAKE_CURRENT_LIST_DIR}/text_cells.cpp
  ${CMAKE_CURRENT_LIST_DIR}/tracks_csv.cpp
  ${CMAKE_CURRENT_LIST_DIR}/whisk_files.cpp)
# Calibration files of other tools (calibration_files.cpp): anipose's TOML and OpenCV's FileStorage YAML/JSON.
find_package(tomlplusplus REQUIRED)
find_package(yaml-cpp REQUIRED)
target_sources(vibrissa PRIVATE ${CMAKE_CURRENT_LIST_DIR}/calibration_files.cpp)
target_link_libraries(vibrissa PRIVATE tomlplusplus::tomlplusplus yaml-cpp)
