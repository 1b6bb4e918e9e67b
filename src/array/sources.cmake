# Sources of the array layer (rat array morphology, whisking kinematics, scenes, simulation). Its files
# (config JSON, morphology tables, outputs) are read and written by the io layer.
target_sources(vibrissa PRIVATE
  ${CMAKE_CURRENT_LIST_DIR}/morphology.cpp
  ${CMAKE_CURRENT_LIST_DIR}/kinematics.cpp
  ${CMAKE_CURRENT_LIST_DIR}/head.cpp
  ${CMAKE_CURRENT_LIST_DIR}/objects.cpp
  ${CMAKE_CURRENT_LIST_DIR}/error_bound.cpp
  ${CMAKE_CURRENT_LIST_DIR}/simulation.cpp
  ${CMAKE_CURRENT_LIST_DIR}/sweep.cpp)
