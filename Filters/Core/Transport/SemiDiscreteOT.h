// Semi-discrete optimal transport by the variational principle (method.md, Algorithm 1) with the
// Kitagawa–Mérigot–Thibert damped Newton step rule.
#ifndef OTPARAM_TRANSPORT_SEMIDISCRETEOT_H
#define OTPARAM_TRANSPORT_SEMIDISCRETEOT_H

#include "Common/Geometry.h"
#include "Transport/PlanarSource.h"

#include <functional>
#include <string>
#include <vector>

namespace otparam
{

// How a Newton solve went; OTResult adds the transport's fields.
struct NewtonReport
{
  bool converged = false;
  bool aborted = false;
  int iterations = 0;
  double relativeError = 0.0;              // max_i |cellMass_i - mass_i| / mass_i
  std::vector<double> gradientNormHistory; // |cellMass - mass|_2 before each Newton step
  std::vector<double> stepLengthHistory;   // accepted damping factor of each Newton step
  std::string message;                     // why it stopped
  // Seconds spent per stage, summed over the run.
  double secondsTriangulation = 0, secondsIntegration = 0, secondsAssembly = 0, secondsSolve = 0;
};

struct OTOptions
{
  double tolerance = 1e-10;            // largest relative cell-mass error accepted
  int maximumNumberOfIterations = 200; // Newton iterations
  // Start from a coarse problem (MultiscaleStart.h; unit-disk source, from 2e4 Diracs up, masses
  // of high contrast): far fewer fine Newton iterations than from the shrunk Voronoi diagram
  // (docs/design.md).
  bool coarseToFineStart = true;
  // Where the Diracs crowd towards the circle (unit-disk source), also try the radial map's
  // start (SemiDiscreteOT.cxx) and keep it when it is nearer the solution.
  bool radialStart = true;
  // Newton steps aimed at sqrt(mass) for cells far below their masses (NewtonOptions).
  bool squareRootGrowth = true;
  // Called once per Newton iteration with (iteration, relative error); return false to abort.
  std::function<bool(int, double)> progress;
};

// The transport's result: the Newton report (convergence, histories, timings) and the cells.
struct OTResult : NewtonReport
{
  std::vector<double> mass;     // target masses after rescaling to the source's total
  std::vector<double> heights;  // h_i
  std::vector<double> cellMass; // achieved cell measure
  std::vector<Vec2> centroids;  // barycentre of each clipped power cell (density-weighted)
};

// The masses scaled so that they sum to `total` (the source's mass) to the last bit that
// matters: the transport's gauge cell absorbs any difference.
std::vector<double> massesScaledTo(const std::vector<double>& masses, double total);

// What is wrong with a value of the options or the arcs' angle (named as the filters'
// properties), or "".
std::string checkTransportOptions(const OTOptions& options, double maximumArcAngle);

// Validates diracs/masses (finite, |y|^2 finite, positive, distinct) and returns an empty
// string or a message naming the offending ids.
std::string validateDiracs(const std::vector<Vec2>& diracs, const std::vector<double>& masses);

// Solves for heights h such that every power cell W_i(h) ∩ domain has source measure masses[i]
// (masses are rescaled to the source's total). Diracs may lie outside the domain; Diracs all
// far from it are solved moved over it (the same cells under the same heights).
OTResult solveSemiDiscreteOT(const SourceMeasure& source, const std::vector<Vec2>& diracs,
  const std::vector<double>& masses, const OTOptions& options = OTOptions());

// Measure and barycentre of every power cell W_i(h) ∩ domain (an empty cell has mass 0 and its
// Dirac as centroid). With h_i = |y_i|^2 / 2 these are the clipped Voronoi cells.
struct CellMeasures
{
  std::vector<double> mass;
  std::vector<Vec2> centroid;
};
CellMeasures computeCellMeasures(
  const SourceMeasure& source, const std::vector<Vec2>& diracs, const std::vector<double>& heights);
// The same in `diagram`, which keeps its triangulation for the next call: a Lloyd step's moved
// Diracs are then triangulated by flips (PowerDiagram::build).
class PowerDiagram;
CellMeasures computeCellMeasures(const SourceMeasure& source, const std::vector<Vec2>& diracs,
  const std::vector<double>& heights, PowerDiagram& diagram);

// Geometry of the power diagram for given heights, for display and for the VTK outputs.
struct PowerDiagramGeometry
{
  std::vector<std::vector<Vec2>> cells; // clipped cell boundaries (closed, CCW, arcs sampled)
  std::vector<int> cellDirac;           // Dirac of each entry of cells
  std::vector<Triangle> triangles;      // weighted Delaunay triangles (Dirac ids)
  struct Edge
  {
    Vec2 a, b; // the part of the shared power edge inside the domain
    int i, j;  // the two Diracs
  };
  std::vector<Edge> edges;
};

// Largest angle (radians) of the pieces the arcs of the unit circle are drawn with.
constexpr double DefaultMaximumArcAngle = 0.05;

PowerDiagramGeometry computePowerDiagramGeometry(const SourceMeasure& source,
  const std::vector<Vec2>& diracs, const std::vector<double>& heights,
  double maxArcAngle = DefaultMaximumArcAngle);

} // namespace otparam

#endif
