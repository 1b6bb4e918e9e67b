# Sources of the io layer
target_sources(vibrissa PRIVATE
  ${CMAKE_CURRENT_LIST_DIR}/h5_file.cpp
  ${CMAKE_CURRENT_LIST_DIR}/trial_arrays.cpp
  ${CMAKE_CURRENT_LIST_DIR}/trial_csv.cpp
  ${CMAKE_CURRENT_LIST_DIR}/trial_h5.cpp
  ${CMAKE_CURRENT_LIST_DIR}/trial_io.cpp
  ${CMAKE_CURRENT_LIST_DIR}/trial_mat.cpp
  ${CMAKE_CURRENT_LIST_DIR}/trial_outputs.cpp
  ${CMAKE_CURRENT_LIST_DIR}/trial_results.cpp)
