// The sphere's last resort for a crowded closed surface (parameterizeSphere): a start on the
// sphere made from the disk pipeline, which reaches further than the sphere's staged transports.
#ifndef OTPARAM_PIPELINE_LIFTEDDISKSTART_H
#define OTPARAM_PIPELINE_LIFTEDDISKSTART_H

#include "Pipeline/AreaPreservingPipeline.h"

#include <string>
#include <vector>

namespace otparam
{

// A closed surface's conformal sphere map collapses a long protrusion below the absolute
// precision of unit vectors (~1e-16: the closed finger at L / rho = 64 leaves 3712 of its 12576
// triangles not positive), while the disk's staged transports keep a protrusion's tip at the
// origin in relative precision (GreenDiskMap.h). So:
// - a patch of the surface's body is cut out (bodyPatch: not on a protrusion, around which a
//   disk map's boundary loop would be short and squeeze the rest), LiftedPatchShares in turn;
// - the rest is mapped onto the disk area-preservingly by parameterizeDisk, the patch by Tutte's
//   embedding with its boundary where the rest's map put it;
// - the rest's disk is lifted onto a cap around the north pole by the gnomonic projection (edges
//   to great circles: the rest's long thin ring triangles cannot fold), the patch's onto the
//   rest of the sphere by Lambert's equal-area projection.
// The last transport on the sphere then corrects that start's areas.
struct LiftedDiskStart
{
  std::string error;        // why there is no start ("" when `sphere` holds it)
  bool aborted = false;     // the progress callback asked to stop (then no error)
  std::vector<Vec3> sphere; // one per point of the mesh
  int patchCentre = -1;
  double patchShare = 0.0; // of the surface's area
  int diskStages = 0;      // the disk map's staged transports
};

// The patch's shares of the area tried in turn (bodyPatch grows it while it stays a disk).
// Measured on TestCrowdingSphere's closed finger at L / rho = 64 (docs/design.md): a point's
// star alone (0.04%) crowds the rest's disk map (a small boundary loop squeezes the whole
// surface, SmallHoleFraction), whose stages failed; with 10% of the area the rest's share did
// not fit in the gnomonic cap, and the last composition folded 3967 triangles (the map fell back
// to the start, corrected: 0.20); with 45% it mapped (0.046); with 32% the rest's disk map
// failed.
constexpr double LiftedPatchShares[] = { 0.5, 0.45, 0.4, 0.3 };
// The largest cap the gnomonic projection fills well: the disk's rim at 10 times the cap's
// inner radius (a cap of 90 degrees, a hemisphere, needs an infinite plane).
constexpr double GnomonicLargestShare = 0.45;

// `options`: the sphere run's (their progress callback is kept at the sampling stage's start).
LiftedDiskStart liftedDiskStart(const AreaPreservingOptions& options, const SurfaceMesh& mesh);

} // namespace otparam

#endif
