# Sources of the objects layer (docs/objects.md): shapes behind one query interface. Meshes use CGAL's AABB tree
# (header-only, libcgal-dev) and assimp (libassimp-dev) for their files.
target_sources(vibrissa PRIVATE
  ${CMAKE_CURRENT_LIST_DIR}/box.cpp
  ${CMAKE_CURRENT_LIST_DIR}/clearance.cpp
  ${CMAKE_CURRENT_LIST_DIR}/cylinder.cpp
  ${CMAKE_CURRENT_LIST_DIR}/mesh.cpp
  ${CMAKE_CURRENT_LIST_DIR}/mesh_file.cpp
  ${CMAKE_CURRENT_LIST_DIR}/plane.cpp
  ${CMAKE_CURRENT_LIST_DIR}/shape.cpp
  ${CMAKE_CURRENT_LIST_DIR}/sphere.cpp)
