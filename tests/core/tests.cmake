set(VIBRISSA_TEST_SOURCES
  ${CMAKE_CURRENT_LIST_DIR}/test_closed_form.cpp
  ${CMAKE_CURRENT_LIST_DIR}/test_chain_jacobian.cpp
  ${CMAKE_CURRENT_LIST_DIR}/test_published_chain.cpp
  ${CMAKE_CURRENT_LIST_DIR}/test_whisker.cpp
  ${CMAKE_CURRENT_LIST_DIR}/checks_test.cpp)
