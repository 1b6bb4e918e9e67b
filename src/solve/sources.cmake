target_sources(vibrissa PRIVATE
  ${CMAKE_CURRENT_LIST_DIR}/status.cpp
  ${CMAKE_CURRENT_LIST_DIR}/contact_evaluations.cpp
  ${CMAKE_CURRENT_LIST_DIR}/contact_problem.cpp
  ${CMAKE_CURRENT_LIST_DIR}/solution_check.cpp
  ${CMAKE_CURRENT_LIST_DIR}/edge_problem.cpp
  ${CMAKE_CURRENT_LIST_DIR}/force_mode.cpp
  ${CMAKE_CURRENT_LIST_DIR}/point_mode.cpp
  ${CMAKE_CURRENT_LIST_DIR}/edge_mode.cpp
  ${CMAKE_CURRENT_LIST_DIR}/frictional_edge.cpp
  ${CMAKE_CURRENT_LIST_DIR}/object_problem.cpp
  ${CMAKE_CURRENT_LIST_DIR}/object_mode.cpp
  ${CMAKE_CURRENT_LIST_DIR}/two_contact.cpp
  ${CMAKE_CURRENT_LIST_DIR}/frictional_object.cpp
  ${CMAKE_CURRENT_LIST_DIR}/base_wrench.cpp)
