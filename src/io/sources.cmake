# Sources of the io layer: every file the tools read or write (case_json.cpp is listed in case_sources.cmake).
target_sources(vibrissa PRIVATE
  ${CMAKE_CURRENT_LIST_DIR}/atomic_file.cpp
  ${CMAKE_CURRENT_LIST_DIR}/output_target.cpp
  ${CMAKE_CURRENT_LIST_DIR}/output_folder.cpp
  ${CMAKE_CURRENT_LIST_DIR}/temporary_files.cpp
  ${CMAKE_CURRENT_LIST_DIR}/json_file.cpp
  ${CMAKE_CURRENT_LIST_DIR}/json_input.cpp
  ${CMAKE_CURRENT_LIST_DIR}/csv_cells.cpp
  ${CMAKE_CURRENT_LIST_DIR}/nan_reasons.cpp
  ${CMAKE_CURRENT_LIST_DIR}/figure_files.cpp
  ${CMAKE_CURRENT_LIST_DIR}/h5_file.cpp
  ${CMAKE_CURRENT_LIST_DIR}/labelled_h5.cpp
  ${CMAKE_CURRENT_LIST_DIR}/guarded_read.cpp
  ${CMAKE_CURRENT_LIST_DIR}/code_tables.cpp
  ${CMAKE_CURRENT_LIST_DIR}/trial_arrays.cpp
  ${CMAKE_CURRENT_LIST_DIR}/trial_csv.cpp
  ${CMAKE_CURRENT_LIST_DIR}/trial_h5.cpp
  ${CMAKE_CURRENT_LIST_DIR}/trial_io.cpp
  ${CMAKE_CURRENT_LIST_DIR}/trial_mat.cpp
  ${CMAKE_CURRENT_LIST_DIR}/trial_outputs.cpp
  ${CMAKE_CURRENT_LIST_DIR}/trial_results.cpp
  ${CMAKE_CURRENT_LIST_DIR}/morphology_table.cpp
  ${CMAKE_CURRENT_LIST_DIR}/object_json.cpp
  ${CMAKE_CURRENT_LIST_DIR}/array_config.cpp
  ${CMAKE_CURRENT_LIST_DIR}/array_outputs.cpp
  ${CMAKE_CURRENT_LIST_DIR}/dynamics_case.cpp)
