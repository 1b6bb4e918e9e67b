set(VIBRISSA_TEST_SOURCES
  ${CMAKE_CURRENT_LIST_DIR}/test_shapes.cpp
  ${CMAKE_CURRENT_LIST_DIR}/test_mesh.cpp
  ${CMAKE_CURRENT_LIST_DIR}/test_clearance.cpp)
