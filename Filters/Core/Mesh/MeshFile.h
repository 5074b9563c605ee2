// Reading OFF and OBJ surface files (what real files contain), VTK-free.
//
// Both readers take what writers in the wild produce (comments anywhere, CRLF, polygons, OFF
// variants with colours or normals, OBJ statements other than v/vt/f) and refuse what cannot
// be a surface (unparsable or non-finite coordinates, out-of-range or repeated indices, faces
// of fewer than 3 corners, truncated files, binary data) with a message that names the
// physical line (1-based; a statement continued over several lines is named by its first).
// Vertex numbers in messages are those the file's faces use: 0-based in OFF, 1-based in OBJ.
#ifndef OTPARAM_MESH_MESHFILE_H
#define OTPARAM_MESH_MESHFILE_H

#include "Common/Geometry.h"

#include <istream>
#include <string>
#include <vector>

namespace otparam
{

struct MeshFileData
{
  std::vector<Vec3> points;        // every vertex of the file, in file order
  std::vector<Triangle> triangles; // faces; polygons fan-triangulated from their first corner
  // OBJ: one per point when every face corner that names a vt gives its point the same vt
  // (then size == points.size(); points no corner gives one get (0, 0)); empty otherwise.
  std::vector<Vec2> textureCoordinates;
  int polygons = 0; // faces with more than 3 corners (triangulated)
  // OBJ with vt lines: corners whose vt could not be kept per point (seams: a vt of other
  // (u, v) than the one their point got first) or named a missing vt.
  int texturedCornersIgnored = 0;
  std::string format; // "OFF" or "OBJ"
};

// "" on success, else a message naming the problem and its line ("line 12: ..."); out is then
// cleared.
std::string readOFF(std::istream& in, MeshFileData& out);
std::string readOBJ(std::istream& in, MeshFileData& out);

// By extension (.off / .obj, any case); other extensions: an error naming the supported ones.
// Opens the file (error when it cannot).
std::string readMeshFile(const std::string& path, MeshFileData& out);

} // namespace otparam

#endif
