set(VIBRISSA_TEST_SOURCES
  ${CMAKE_CURRENT_LIST_DIR}/geometry_test.cpp
  ${CMAKE_CURRENT_LIST_DIR}/tracks_test.cpp
  ${CMAKE_CURRENT_LIST_DIR}/pickled_value_test.cpp
  ${CMAKE_CURRENT_LIST_DIR}/reconstruct_test.cpp
  ${CMAKE_CURRENT_LIST_DIR}/reprojection_test.cpp
  ${CMAKE_CURRENT_LIST_DIR}/input_checks_test.cpp
  ${CMAKE_CURRENT_LIST_DIR}/multi_view_test.cpp)
