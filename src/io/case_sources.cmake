target_sources(vibrissa PRIVATE ${CMAKE_CURRENT_LIST_DIR}/case_json.cpp)
