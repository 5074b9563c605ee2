// Tutte's embedding of a disk patch: every inner point at the mean of its neighbours, the
// boundary's points where the caller put them. With the boundary on a convex polygon in its
// order, no triangle flips (Tutte 1963, Floater 2003), whatever the patch's shape; it is not
// conformal, so it serves only as a start that a transport corrects (Pipeline/LiftedDiskStart).
#ifndef OTPARAM_CONFORMAL_TUTTEEMBEDDING_H
#define OTPARAM_CONFORMAL_TUTTEEMBEDDING_H

#include "Common/Geometry.h"

#include <string>
#include <vector>

namespace otparam
{

// `uv`: one per point, read where `fixed` is 1, written at the other points the triangles use.
// "" or what went wrong (a patch with no fixed point, a singular system).
std::string tutteEmbedding(
  const std::vector<Triangle>& triangles, const std::vector<char>& fixed, std::vector<Vec2>& uv);

} // namespace otparam

#endif
