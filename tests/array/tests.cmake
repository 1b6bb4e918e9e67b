set(VIBRISSA_TEST_SOURCES
  ${CMAKE_CURRENT_LIST_DIR}/test_morphology.cpp
  ${CMAKE_CURRENT_LIST_DIR}/test_kinematics.cpp
  ${CMAKE_CURRENT_LIST_DIR}/test_objects.cpp
  ${CMAKE_CURRENT_LIST_DIR}/test_simulation.cpp)
