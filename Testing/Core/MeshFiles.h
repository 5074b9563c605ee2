// The shared meshes for the tests and benchmarks of the core, read by the core's own reader.
#ifndef OTPARAM_TESTING_MESHFILES_H
#define OTPARAM_TESTING_MESHFILES_H

#include "Mesh/MeshFile.h"
#include "Mesh/SurfaceMesh.h"

#include <cstdio>
#include <stdexcept>
#include <string>
#include <utility>

namespace otparam
{
namespace testing
{

#ifndef OTPARAM_SHARED_MESH_DIR
#error "OTPARAM_SHARED_MESH_DIR must name ../shared/data/meshes"
#endif

inline std::string sharedMesh(const std::string& name)
{
  return std::string(OTPARAM_SHARED_MESH_DIR) + "/" + name;
}

// Positions and triangles of an OFF or OBJ file; throws when it cannot be read.
inline SurfaceMesh readMesh(const std::string& path)
{
  MeshFileData data;
  const std::string error = readMeshFile(path, data);
  if (!error.empty())
  {
    throw std::runtime_error(path + ": " + error);
  }
  SurfaceMesh mesh;
  mesh.points = std::move(data.points);
  mesh.triangles = std::move(data.triangles);
  return mesh;
}

// The file as a soup (the pipeline's input: unreferenced points are its to drop).
inline TriangleSoup readSoup(const std::string& path)
{
  SurfaceMesh mesh = readMesh(path);
  TriangleSoup soup;
  soup.points = std::move(mesh.points);
  soup.triangles.reserve(mesh.triangles.size());
  for (const Triangle& t : mesh.triangles)
  {
    soup.triangles.push_back({ t[0], t[1], t[2] });
  }
  return soup;
}

// For the benchmark programs: `read(path)` (readMesh or readSoup) into `mesh`, or false with
// the reason printed to stderr (the program then exits with 2).
template <typename Mesh>
bool readOrReport(const std::string& path, Mesh (*read)(const std::string&), Mesh& mesh)
{
  try
  {
    mesh = read(path);
    return true;
  }
  catch (const std::exception& e)
  {
    std::fprintf(stderr, "%s\n", e.what());
    return false;
  }
}

} // namespace testing
} // namespace otparam

#endif
