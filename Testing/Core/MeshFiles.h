// Small OBJ/OFF readers for the tests and benchmarks of the core (positions and triangles).
#ifndef OTPARAM_TESTING_MESHFILES_H
#define OTPARAM_TESTING_MESHFILES_H

#include "Mesh/SurfaceMesh.h"

#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>

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

SurfaceMesh readMesh(const std::string& path);

// The file as a soup (the pipeline's input: unreferenced points are its to drop).
inline TriangleSoup readSoup(const std::string& path)
{
  const SurfaceMesh mesh = readMesh(path);
  TriangleSoup soup;
  soup.points = mesh.points;
  for (const Triangle& t : mesh.triangles)
  {
    soup.triangles.push_back({ t[0], t[1], t[2] });
  }
  return soup;
}

inline SurfaceMesh readMesh(const std::string& path)
{
  std::ifstream in(path);
  if (!in)
  {
    throw std::runtime_error("cannot open " + path);
  }
  SurfaceMesh mesh;
  auto addFace = [&](const std::vector<int>& f)
  {
    for (size_t k = 1; k + 1 < f.size(); ++k)
    {
      mesh.triangles.push_back({ f[0], f[k], f[k + 1] });
    }
  };
  if (path.size() > 4 && path.substr(path.size() - 4) == ".off")
  {
    std::string header;
    in >> header;
    size_t nv = 0, nf = 0, ne = 0;
    in >> nv >> nf >> ne;
    mesh.points.resize(nv);
    for (auto& p : mesh.points)
    {
      in >> p.x >> p.y >> p.z;
    }
    for (size_t f = 0; f < nf; ++f)
    {
      int k = 0;
      in >> k;
      std::vector<int> face(k);
      for (int& v : face)
      {
        in >> v;
      }
      addFace(face);
    }
    return mesh;
  }
  std::string line;
  while (std::getline(in, line))
  {
    std::istringstream words(line);
    std::string tag;
    words >> tag;
    if (tag == "v")
    {
      Vec3 p;
      words >> p.x >> p.y >> p.z;
      mesh.points.push_back(p);
    }
    else if (tag == "f")
    {
      std::vector<int> face;
      std::string token;
      while (words >> token)
      {
        const int i = std::stoi(token.substr(0, token.find('/')));
        face.push_back(i > 0 ? i - 1 : static_cast<int>(mesh.points.size()) + i);
      }
      addFace(face);
    }
  }
  return mesh;
}

} // namespace testing
} // namespace otparam

#endif
