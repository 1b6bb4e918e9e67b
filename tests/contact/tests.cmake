set(VIBRISSA_TEST_SOURCES
  ${CMAKE_CURRENT_LIST_DIR}/test_crossing.cpp
  ${CMAKE_CURRENT_LIST_DIR}/test_tracker.cpp
  ${CMAKE_CURRENT_LIST_DIR}/test_tracker_objects.cpp)
