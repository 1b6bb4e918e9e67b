set(VIBRISSA_TEST_SOURCES ${CMAKE_CURRENT_LIST_DIR}/test_contact_modes.cpp
  ${CMAKE_CURRENT_LIST_DIR}/test_base_wrench.cpp
  ${CMAKE_CURRENT_LIST_DIR}/test_solver_policy_sweep.cpp
  ${CMAKE_CURRENT_LIST_DIR}/test_warm_start_record.cpp
  ${CMAKE_CURRENT_LIST_DIR}/solution_contract_test.cpp
  ${CMAKE_CURRENT_LIST_DIR}/test_object_contact.cpp
  ${CMAKE_CURRENT_LIST_DIR}/test_object_mesh_agreement.cpp
  ${CMAKE_CURRENT_LIST_DIR}/test_two_contact.cpp)
