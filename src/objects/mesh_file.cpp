// Mesh files through assimp (libassimp-dev): OBJ, STL (ASCII and binary), PLY (ASCII and binary) and the other
// formats assimp reads. Every mesh of the file's scene is taken, with its node transforms applied.
#include <assimp/cimport.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <filesystem>

#include "vibrissa/core/checks.hpp"
#include "vibrissa/objects/mesh.hpp"

namespace vibrissa {

std::shared_ptr<const Mesh> Mesh::from_file(const std::string& path, double scale, const ObjectPose& pose) {
  require_positive(scale, "object.scale");
  require_finite(pose.p_WO, "object.translation");
  if (!std::filesystem::is_regular_file(path)) invalid_input("object.file: no such file: '" + path + "'");
  const aiScene* scene = aiImportFile(path.c_str(), aiProcess_Triangulate | aiProcess_PreTransformVertices |
                                                        aiProcess_SortByPType | aiProcess_FindDegenerates);
  if (!scene) invalid_input("object.file: cannot read mesh '" + path + "': " + aiGetErrorString());
  TriangleSoup soup;
  for (unsigned m = 0; m < scene->mNumMeshes; ++m) {
    const aiMesh* mesh = scene->mMeshes[m];
    const int offset = static_cast<int>(soup.vertices.size());
    for (unsigned i = 0; i < mesh->mNumVertices; ++i) {
      const aiVector3D& v = mesh->mVertices[i];
      soup.vertices.push_back(pose.to_world(scale * Eigen::Vector3d(v.x, v.y, v.z)));
    }
    for (unsigned f = 0; f < mesh->mNumFaces; ++f) {
      const aiFace& face = mesh->mFaces[f];
      if (face.mNumIndices != 3) continue;  // points and lines
      soup.triangles.push_back({offset + static_cast<int>(face.mIndices[0]), offset + static_cast<int>(face.mIndices[1]),
                                offset + static_cast<int>(face.mIndices[2])});
    }
  }
  aiReleaseImport(scene);
  return std::make_shared<const Mesh>(std::move(soup), path);
}

}  // namespace vibrissa
