// Mesh files through assimp (libassimp-dev): OBJ, STL (ASCII and binary), PLY (ASCII and binary) and the other
// formats assimp reads. Every mesh of the file's scene is taken, with its node transforms applied.
#include <assimp/cimport.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <filesystem>

#include "vibrissa/core/checks.hpp"
#include "vibrissa/objects/mesh.hpp"
#include "../io/guarded_read.hpp"

namespace vibrissa {

namespace {

/// The triangles of every mesh in the file's scene, node transforms applied, in the file's units and frame.
TriangleSoup import_soup(const std::string& path) {
  const aiScene* scene = aiImportFile(path.c_str(), aiProcess_Triangulate | aiProcess_PreTransformVertices |
                                                        aiProcess_SortByPType | aiProcess_FindDegenerates);
  if (!scene) invalid_input("object.file: cannot read mesh '" + path + "': " + aiGetErrorString());
  TriangleSoup soup;
  for (unsigned m = 0; m < scene->mNumMeshes; ++m) {
    const aiMesh* mesh = scene->mMeshes[m];
    const int offset = static_cast<int>(soup.vertices.size());
    for (unsigned i = 0; i < mesh->mNumVertices; ++i) {
      const aiVector3D& v = mesh->mVertices[i];
      soup.vertices.emplace_back(v.x, v.y, v.z);
    }
    for (unsigned f = 0; f < mesh->mNumFaces; ++f) {
      const aiFace& face = mesh->mFaces[f];
      if (face.mNumIndices != 3) continue;  // points and lines
      soup.triangles.push_back({offset + static_cast<int>(face.mIndices[0]), offset + static_cast<int>(face.mIndices[1]),
                                offset + static_cast<int>(face.mIndices[2])});
    }
  }
  aiReleaseImport(scene);
  return soup;
}

}  // namespace

std::shared_ptr<const Mesh> Mesh::from_file(const std::string& path, double scale, const ObjectPose& pose) {
  require_positive(scale, "object.scale");
  require_finite(pose.p_WO, "object.translation");
  if (!std::filesystem::is_regular_file(path)) invalid_input("object.file: no such file: '" + path + "'");
  // assimp meets the file in a child process first (io/guarded_read.hpp): on malformed PLY files it aborts
  // (ai_assert), crashes (a face index of -1) or loops (a truncated header), found by mutating PLY/OBJ/STL
  // files (issue 23). The child gets 2 s plus 1 s per 2 MB of file.
  const double timeout_s = 2.0 + double(std::filesystem::file_size(path)) / 2e6;
  try {
    io::probe_in_child(path, "assimp", [](const void* p) { (void)import_soup(*static_cast<const std::string*>(p)); },
                       &path, timeout_s);
  } catch (const std::invalid_argument& e) {
    invalid_input(std::string("object.file: cannot read mesh: ") + e.what());
  }
  TriangleSoup soup = import_soup(path);
  for (auto& v : soup.vertices) v = pose.to_world(scale * v);
  return std::make_shared<const Mesh>(std::move(soup), path);
}

}  // namespace vibrissa
