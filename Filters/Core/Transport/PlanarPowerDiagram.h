// The power diagram of weighted Diracs, from CGAL's regular triangulation (exact predicates).
// CGAL stays inside PowerDiagram.cxx; callers see adjacency and convex cells only.
#ifndef OTPARAM_TRANSPORT_PLANARPOWERDIAGRAM_H
#define OTPARAM_TRANSPORT_PLANARPOWERDIAGRAM_H

#include "Common/Geometry.h"
#include "Transport/Height.h"
#include "Transport/PlanarSource.h"

#include <memory>
#include <vector>

namespace otparam
{

class PowerDiagram
{
public:
  PowerDiagram();
  ~PowerDiagram();
  PowerDiagram(PowerDiagram&&) noexcept;
  PowerDiagram& operator=(PowerDiagram&&) noexcept;

  // Cells W_i = {x : <x, y_i> - h_i >= <x, y_j> - h_j for all j}: the power diagram of y_i with
  // weights |y_i|^2 - 2 h_i.
  // What a build does when Diracs are hidden. A Newton trial that hides a Dirac is rejected
  // anyway, and what a whole diagram costs beyond finding one would be wasted: a new insertion
  // (the kept triangulation's flips stop at hidden Diracs), the power vertices and the rings.
  enum class WhenHidden
  {
    FindAll,    // the whole diagram, every hidden Dirac with its hiddenFace()
    ReportSome, // no cells; hidden() and hiddenFace() for the Diracs found certainly hidden
    StopAtFirst // no cells; hidden() for the first Dirac found certainly hidden
  };
  // A build for the Diracs of the last one under new heights flips its triangulation; so does
  // a build for the same number of Diracs moved a little (a Lloyd step), when the hull's Diracs
  // stay and no triangle turns over; anything else is inserted afresh.
  void build(const std::vector<Vec2>& diracs, const std::vector<Height>& heights,
    WhenHidden whenHidden = WhenHidden::FindAll);

  // Moves the other diagram's kept triangulation here (the other keeps its cells), so that the
  // next build of this one flips it: a Newton trial starts from the accepted diagram's
  // triangulation, and only one triangulation is alive per solve (1e6 Diracs: ~200 MiB each).
  void takeTriangulationFrom(PowerDiagram& other);

  // Frees the cells' geometry (power vertices, rings, triangles, sites and heights, hidden
  // Diracs' faces; no cell(), triangles() or hiddenFace() until the next build) and keeps the
  // adjacency, which Diracs are hidden and the triangulation: what a Newton step's search reads
  // of the current diagram (1e6 Diracs: ~170 MiB).
  void releaseCellGeometry();

  int size() const { return static_cast<int>(Sites.size()); }
  // A hidden Dirac has an empty cell in the whole plane.
  bool hidden(int i) const { return Hidden[i] != 0; }
  int hiddenCount() const { return HiddenCount; }
  // The finite face of the regular triangulation that contains a hidden Dirac's point (its
  // lifted point lies above that face's plane); {-1, -1, -1} when there is none.
  Triangle hiddenFace(int i) const { return HiddenFace[i]; }
  // Neighbours of Dirac i in the regular triangulation (one per power edge in the plane;
  // -1 stands for the infinite vertex around hull Diracs).
  const int* neighborsBegin(int i) const { return Adjacency.data() + Offsets[i]; }
  const int* neighborsEnd(int i) const { return Adjacency.data() + Offsets[i + 1]; }
  // Cell of Dirac i as a convex polygon (empty when hidden). Its parts outside the box [lo, hi],
  // which must contain the domain, are replaced by edges labelled -1 that stay outside the box.
  // Thread-safe.
  void cell(int i, Vec2 lo, Vec2 hi, PowerCell& out) const;
  // Finite faces of the regular (weighted Delaunay) triangulation, counter-clockwise.
  const std::vector<Triangle>& triangles() const { return Triangles; }

private:
  // The power vertex rounded to double, and what the rounding left out.
  void powerVertex(int a, int b, int c, Vec2& rounded, Vec2& correction) const;
  void ringCell(int i, Vec2 lo, Vec2 hi, PowerCell& out) const;
  void clearCells(int n);
  struct Triangulation;
  // build's steps. The regular triangulation of the new heights (Kept flipped, or a fresh
  // insertion held in `fresh` or moved into Kept); null when the flips stopped at a hidden Dirac
  // and the caller asked no more (Hidden and HiddenFace then set).
  Triangulation* triangulate(const std::vector<Vec2>& diracs, const std::vector<Height>& heights,
    WhenHidden whenHidden, std::unique_ptr<Triangulation>& fresh);
  void findHidden(const Triangulation& triangulation, int n);
  void buildPlanarCells(Triangulation& triangulation, int n); // dimension 2
  void buildLowDimensionalAdjacency(const Triangulation& triangulation, int n);

  // The last regular triangulation: a build for the same Diracs under new heights flips it
  // (a Newton step changes few edges) instead of inserting every Dirac again.
  std::unique_ptr<Triangulation> Kept;
  int Dimension = 0;
  std::vector<Vec2> PowerVertices; // one per finite face (weighted circumcentre)
  std::vector<Vec2> PowerVertexCorrections;
  std::vector<int> RingFace; // faces around each Dirac, CCW (-1: infinite), rows as Adjacency
  std::vector<Vec2> Sites;
  std::vector<Height> Heights;
  std::vector<int> Offsets, Adjacency;
  std::vector<char> Hidden;
  std::vector<Triangle> HiddenFace;
  std::vector<Triangle> Triangles;
  int HiddenCount = 0;
};

} // namespace otparam

#endif
