set(VIBRISSA_TEST_SOURCES
  ${CMAKE_CURRENT_LIST_DIR}/test_air_drag.cpp
  ${CMAKE_CURRENT_LIST_DIR}/test_contact_dynamics.cpp
  ${CMAKE_CURRENT_LIST_DIR}/test_deflected_modes.cpp
  ${CMAKE_CURRENT_LIST_DIR}/test_modes.cpp
  ${CMAKE_CURRENT_LIST_DIR}/test_simulate.cpp
  ${CMAKE_CURRENT_LIST_DIR}/test_surface_dynamics.cpp)
