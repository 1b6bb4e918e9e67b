# Sources of the trial layer
target_sources(vibrissa PRIVATE
  ${CMAKE_CURRENT_LIST_DIR}/analysis.cpp
  ${CMAKE_CURRENT_LIST_DIR}/filter.cpp
  ${CMAKE_CURRENT_LIST_DIR}/force_directions.cpp
  ${CMAKE_CURRENT_LIST_DIR}/format.cpp
  ${CMAKE_CURRENT_LIST_DIR}/friction_analysis.cpp
  ${CMAKE_CURRENT_LIST_DIR}/kinematic_prediction.cpp
  ${CMAKE_CURRENT_LIST_DIR}/outliers.cpp
  ${CMAKE_CURRENT_LIST_DIR}/pipeline.cpp
  ${CMAKE_CURRENT_LIST_DIR}/plausibility.cpp
  ${CMAKE_CURRENT_LIST_DIR}/preprocess.cpp
  ${CMAKE_CURRENT_LIST_DIR}/roll_regression.cpp
  ${CMAKE_CURRENT_LIST_DIR}/shape_error.cpp
  ${CMAKE_CURRENT_LIST_DIR}/statistics.cpp
  ${CMAKE_CURRENT_LIST_DIR}/synth.cpp
  ${CMAKE_CURRENT_LIST_DIR}/synth_parameters.cpp
  ${CMAKE_CURRENT_LIST_DIR}/trial_run.cpp
  ${CMAKE_CURRENT_LIST_DIR}/z_error.cpp)
