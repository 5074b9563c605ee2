// A patch of a closed surface grown around a point, cut out so that the rest is a disk with a
// boundary loop long enough for a disk map (Pipeline/LiftedDiskStart.h).
#ifndef OTPARAM_MESH_DISKPATCH_H
#define OTPARAM_MESH_DISKPATCH_H

#include "Mesh/SurfaceMesh.h"

#include <vector>

namespace otparam
{

// The triangles with a corner within k edges of `centre` (per triangle, 1 inside), for the
// smallest k whose patch holds at least `share` of the surface's area, or the largest k whose
// patch is still a disk (connected, one boundary loop, Euler characteristic 1) if that one is
// not. Empty when there is none.
std::vector<char> growDiskPatch(const SurfaceMesh& mesh, int centre, double share);

// Of the disk patches growDiskPatch grows around `candidates` points spread over the surface
// (each the farthest along the edges from those before, the first the farthest from point 0)
// that reach 80% of `share`, the roundest (boundary length / sqrt(area)): one in the wide body
// of a surface. Around a protrusion's tip the patch is a tube, whose boundary is one short
// ring, and from a tube's side it stops growing where its rings would close around the tube.
// `centre` gets its point (-1 and an empty patch when no candidate grows such a disk).
std::vector<char> bodyPatch(const SurfaceMesh& mesh, double share, int& centre, int candidates = 8);

} // namespace otparam

#endif
