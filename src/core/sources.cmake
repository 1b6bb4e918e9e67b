target_sources(vibrissa PRIVATE
  ${CMAKE_CURRENT_LIST_DIR}/checks.cpp
  ${CMAKE_CURRENT_LIST_DIR}/plausibility.cpp
  ${CMAKE_CURRENT_LIST_DIR}/pose.cpp
  ${CMAKE_CURRENT_LIST_DIR}/rest_curve.cpp
  ${CMAKE_CURRENT_LIST_DIR}/simple_curve.cpp
  ${CMAKE_CURRENT_LIST_DIR}/whisker.cpp
  ${CMAKE_CURRENT_LIST_DIR}/chain.cpp
  ${CMAKE_CURRENT_LIST_DIR}/chain_jacobian.cpp
  ${CMAKE_CURRENT_LIST_DIR}/cubic_spline.cpp
  ${CMAKE_CURRENT_LIST_DIR}/published_chain.cpp)
