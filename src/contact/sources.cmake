# Sources of the contact layer: edges, onset by crossing, contact geometry and the per-frame contact tracker.
target_sources(vibrissa PRIVATE
  ${CMAKE_CURRENT_LIST_DIR}/contact_geometry.cpp
  ${CMAKE_CURRENT_LIST_DIR}/crossing.cpp
  ${CMAKE_CURRENT_LIST_DIR}/tracker.cpp)
