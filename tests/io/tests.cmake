set(VIBRISSA_TEST_SOURCES
  ${CMAKE_CURRENT_LIST_DIR}/trial_io_test.cpp
  ${CMAKE_CURRENT_LIST_DIR}/atomic_file_test.cpp
  ${CMAKE_CURRENT_LIST_DIR}/morphology_table_test.cpp
  ${CMAKE_CURRENT_LIST_DIR}/array_outputs_test.cpp
  ${CMAKE_CURRENT_LIST_DIR}/input_hardening_test.cpp
  ${CMAKE_CURRENT_LIST_DIR}/nan_reasons_test.cpp
  ${CMAKE_CURRENT_LIST_DIR}/guarded_read_test.cpp)
