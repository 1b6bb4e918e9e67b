# Sources of the dynamics layer (docs/dynamics.md): inertia, damping, modes and time integration of the chain.
target_sources(vibrissa PRIVATE
  ${CMAKE_CURRENT_LIST_DIR}/air_drag.cpp
  ${CMAKE_CURRENT_LIST_DIR}/chain_kinematics.cpp
  ${CMAKE_CURRENT_LIST_DIR}/contact.cpp
  ${CMAKE_CURRENT_LIST_DIR}/deflected_modes.cpp
  ${CMAKE_CURRENT_LIST_DIR}/linear_model.cpp
  ${CMAKE_CURRENT_LIST_DIR}/modes.cpp
  ${CMAKE_CURRENT_LIST_DIR}/nonlinear_simulate.cpp
  ${CMAKE_CURRENT_LIST_DIR}/simulate.cpp
  ${CMAKE_CURRENT_LIST_DIR}/surface_contact.cpp)
