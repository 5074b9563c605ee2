#include "Transport/PlanarSource.h"

#include "Common/BoxTree.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <limits>
#include <sstream>
#include <unordered_map>

namespace otparam
{
namespace
{
constexpr double Pi = 3.14159265358979323846;

// ---------------------------------------------------------------------------------------------
// Unit disk, density 1.

// A point in long double: cell vertices with their corrections, and the points where cell edges
// cross the circle.
struct PreciseVec2
{
  long double x = 0.0L, y = 0.0L;
  Vec2 rounded() const { return { static_cast<double>(x), static_cast<double>(y) }; }
};

struct ChordPiece
{
  PreciseVec2 a, b; // the part of a cell edge inside the disk
  int neighbor;
  bool enters; // a is on the circle (the boundary comes in from an arc)
  bool exits;  // b is on the circle
};

// pq has no direction (a zero-length cell edge): no piece of it is inside.
bool isPoint(PreciseVec2 p, PreciseVec2 q)
{
  const long double dx = q.x - p.x, dy = q.y - p.y;
  return dx * dx + dy * dy == 0.0L;
}

// Part of segment p->q inside the unit disk: the points where it enters (pIn) and leaves (qIn),
// each p or q itself when that end lies inside. Each crossing is measured from the nearer end:
// cell edges reach power vertices ~100 away (nearly flat faces by the hull), and a crossing
// found as p + t (q - p) from such an end carries its rounding (~1e-14 along the circle) into the
// mass of the thin cell beside it.
bool segmentInsideUnitDisk(
  PreciseVec2 p, PreciseVec2 q, PreciseVec2& pIn, PreciseVec2& qIn, bool& pOut, bool& qOut)
{
  using LD = long double;
  if (isPoint(p, q))
  {
    return false;
  }
  const LD dx = q.x - p.x, dy = q.y - p.y;
  const LD a = dx * dx + dy * dy;
  // |p + t d|^2 = 1  <=>  a t^2 + 2 b t + c = 0
  const LD b = p.x * dx + p.y * dy;
  const LD c = p.x * p.x + p.y * p.y - 1.0L;
  const LD disc = b * b - a * c;
  if (disc <= 0.0L)
  {
    return false;
  }
  const LD root = std::sqrt(disc);
  // Numerically stable roots.
  const LD qq = -(b + std::copysign(root, b));
  LD r0 = qq / a;
  LD r1 = (qq != 0.0L) ? c / qq : -r0;
  if (r0 > r1)
  {
    std::swap(r0, r1);
  }
  if (!(std::max(r0, 0.0L) < std::min(r1, 1.0L)))
  {
    return false;
  }
  auto crossing = [&](LD t)
  {
    // 1 - t is exact for t in [1/2, 1].
    const LD x = t <= 0.5L ? p.x + t * dx : q.x - (1.0L - t) * dx;
    const LD y = t <= 0.5L ? p.y + t * dy : q.y - (1.0L - t) * dy;
    const LD r = std::sqrt(x * x + y * y);
    return PreciseVec2{ x / r, y / r };
  };
  pOut = r0 > 0.0L;
  qOut = r1 < 1.0L;
  pIn = pOut ? crossing(r0) : p;
  qIn = qOut ? crossing(r1) : q;
  return true;
}

// theta - sin(theta), accurate for small angles (circular segments of tiny cells).
double thetaMinusSin(double theta)
{
  if (theta < 1e-2)
  {
    const double t2 = theta * theta;
    return theta * t2 / 6.0 * (1.0 - t2 / 20.0 * (1.0 - t2 / 42.0));
  }
  return theta - std::sin(theta);
}

bool insideConvex(const PowerCell& cell, Vec2 p)
{
  const size_t n = cell.vertices.size();
  for (size_t k = 0; k < n; ++k)
  {
    const Vec2 a = cell.vertices[k];
    const Vec2 b = cell.vertices[(k + 1) % n];
    if (cross(b - a, p - a) < 0.0)
    {
      return false;
    }
  }
  return true;
}

// Counter-clockwise angle from direction e to direction s on the unit circle, in [0, 2 pi).
// An arc of the clipped cell lies inside the cell; a tiny negative angle from rounding (exit and
// entry at the same vertex on the circle) must not turn into a full turn.
double arcAngle(Vec2 e, Vec2 s, const PowerCell& cell)
{
  double theta = std::atan2(cross(e, s), dot(e, s));
  if (theta < 0.0)
  {
    theta += 2.0 * Pi;
  }
  if (theta > Pi)
  {
    const double mid = std::atan2(e.y, e.x) + 0.5 * theta;
    if (!insideConvex(cell, { std::cos(mid), std::sin(mid) }))
    {
      return 0.0;
    }
  }
  return theta;
}

class UnitDiskSource final : public SourceMeasure
{
public:
  double totalMass() const override { return Pi; }
  bool isUnitDisk() const override { return true; }
  void bounds(Vec2& lo, Vec2& hi) const override
  {
    lo = { -1.0, -1.0 };
    hi = { 1.0, 1.0 };
  }
  void innerDisk(Vec2& center, double& radius) const override
  {
    center = { 0.0, 0.0 };
    radius = 1.0;
  }

  // Cell ∩ disk = polygon through the chord pieces + one circular segment per arc.
  void integrate(const PowerCell& cell, CellIntegrals& out) const override
  {
    out.mass = 0.0;
    out.moment = { 0.0, 0.0 };
    out.edgeMass.clear();
    // One buffer per thread: a cell's pieces were an allocation per cell and evaluation.
    thread_local std::vector<ChordPiece> pieces;
    pieces.clear();
    chordPieces(cell, pieces);
    if (pieces.empty())
    {
      if (!cell.vertices.empty() && insideConvex(cell, { 0.0, 0.0 }))
      {
        out.mass = Pi; // the cell contains the whole disk
      }
      return;
    }
    for (const ChordPiece& p : pieces)
    {
      if (p.neighbor >= 0)
      {
        out.edgeMass.emplace_back(p.neighbor, norm(p.b.rounded() - p.a.rounded()));
      }
    }
    // Polygon part, in coordinates local to its first point and in long double: the cells
    // share their vertices bitwise, so these areas tile exactly up to this rounding, and the
    // largest cell (the gauge) collects the rounding of all the others; in double that is
    // ~1e-10 of a cell at 1e5 cells.
    using LD = long double;
    const PreciseVec2 o = pieces.front().a;
    LD area2 = 0.0L, mx6 = 0.0L, my6 = 0.0L;
    auto addTriangleEdge = [&](PreciseVec2 p, PreciseVec2 q)
    {
      const LD px = p.x - o.x, py = p.y - o.y, qx = q.x - o.x, qy = q.y - o.y;
      const LD c = px * qy - py * qx;
      area2 += c;
      mx6 += c * (px + qx);
      my6 += c * (py + qy);
    };
    const size_t m = pieces.size();
    for (size_t k = 0; k < m; ++k)
    {
      const ChordPiece& p = pieces[k];
      const ChordPiece& next = pieces[(k + 1) % m];
      addTriangleEdge(p.a, p.b);
      addTriangleEdge(p.b, next.a);
    }
    double area = static_cast<double>(area2 / 2);
    Vec2 moment = { static_cast<double>(mx6 / 6 + area2 / 2 * o.x),
      static_cast<double>(my6 / 6 + area2 / 2 * o.y) };
    // Circular segments between an exit point and the next entry point.
    for (size_t k = 0; k < m; ++k)
    {
      const ChordPiece& p = pieces[k];
      const ChordPiece& next = pieces[(k + 1) % m];
      if (!p.exits || !next.enters)
      {
        continue;
      }
      const double theta = arcAngle(p.b.rounded(), next.a.rounded(), cell);
      if (theta <= 0.0)
      {
        continue;
      }
      const double segArea = 0.5 * thetaMinusSin(theta);
      const double mid =
        std::atan2(static_cast<double>(p.b.y), static_cast<double>(p.b.x)) + 0.5 * theta;
      const double s = std::sin(0.5 * theta);
      const double segMoment = (2.0 / 3.0) * s * s * s;
      area += segArea;
      moment = moment + segMoment * Vec2{ std::cos(mid), std::sin(mid) };
    }
    out.mass = area;
    out.moment = moment;
  }

  std::vector<Vec2> clippedBoundary(const PowerCell& cell, double maxArcAngle) const override
  {
    std::vector<Vec2> boundary;
    std::vector<ChordPiece> pieces;
    chordPieces(cell, pieces);
    if (pieces.empty())
    {
      if (!cell.vertices.empty() && insideConvex(cell, { 0.0, 0.0 }))
      {
        appendArc(boundary, { 1.0, 0.0 }, 2.0 * Pi, maxArcAngle, false);
      }
      return boundary;
    }
    const size_t m = pieces.size();
    for (size_t k = 0; k < m; ++k)
    {
      const ChordPiece& p = pieces[k];
      const ChordPiece& next = pieces[(k + 1) % m];
      boundary.push_back(p.a.rounded());
      boundary.push_back(p.b.rounded());
      if (p.exits && next.enters)
      {
        appendArc(boundary, p.b.rounded(), arcAngle(p.b.rounded(), next.a.rounded(), cell),
          maxArcAngle, true);
      }
    }
    // Drop consecutive duplicates (a piece ends where the next starts).
    std::vector<Vec2> unique;
    for (const Vec2& q : boundary)
    {
      if (unique.empty() || norm(q - unique.back()) > 1e-15)
      {
        unique.push_back(q);
      }
    }
    while (unique.size() > 1 && norm(unique.front() - unique.back()) <= 1e-15)
    {
      unique.pop_back();
    }
    return unique;
  }

private:
  static void appendArc(
    std::vector<Vec2>& out, Vec2 from, double theta, double maxArcAngle, bool skipEnds)
  {
    const int steps = std::max(1, static_cast<int>(std::ceil(theta / maxArcAngle)));
    const double start = std::atan2(from.y, from.x);
    const int first = skipEnds ? 1 : 0;
    const int last = skipEnds ? steps - 1 : steps - 1;
    for (int s = first; s <= last; ++s)
    {
      const double a = start + theta * s / steps;
      out.push_back({ std::cos(a), std::sin(a) });
    }
  }

  static PreciseVec2 precise(const PowerCell& cell, size_t k)
  {
    PreciseVec2 v{ cell.vertices[k].x, cell.vertices[k].y };
    if (k < cell.correction.size())
    {
      v.x += cell.correction[k].x;
      v.y += cell.correction[k].y;
    }
    return v;
  }

  static void chordPieces(const PowerCell& cell, std::vector<ChordPiece>& pieces)
  {
    const size_t n = cell.vertices.size();
    for (size_t k = 0; k < n; ++k)
    {
      const size_t k1 = (k + 1) % n;
      const Vec2 p = cell.vertices[k];
      const Vec2 q = cell.vertices[k1];
      // The two cells sharing an edge walk it in opposite directions; intersect it with the
      // circle in one canonical direction so that both get bitwise the same points (the cells
      // then tile the disk exactly).
      const bool forward = p.x < q.x || (p.x == q.x && p.y < q.y);
      const PreciseVec2 pp = precise(cell, k), pq = precise(cell, k1);
      const PreciseVec2 a = forward ? pp : pq, b = forward ? pq : pp;
      PreciseVec2 ca = a, cb = b;
      bool aOut = false, bOut = false;
      // An edge whose ends are both clearly inside lies inside (the disk is convex): what
      // segmentInsideUnitDisk returns for it, without its long double roots (most cells).
      const bool inside = dot(p, p) < 1.0 - 1e-9 && dot(q, q) < 1.0 - 1e-9;
      if (inside ? isPoint(a, b) : !segmentInsideUnitDisk(a, b, ca, cb, aOut, bOut))
      {
        continue;
      }
      ChordPiece piece;
      piece.neighbor = cell.neighbor[k];
      piece.enters = forward ? aOut : bOut;
      piece.exits = forward ? bOut : aOut;
      piece.a = forward ? ca : cb;
      piece.b = forward ? cb : ca;
      pieces.push_back(piece);
    }
  }
};

// ---------------------------------------------------------------------------------------------
// Convex triangulated domain with a piecewise-linear density.

// Keeps the part of a convex polygon where cross(b - a, x - a) >= 0 (left of a->b).
void clipLeftOf(const std::vector<Vec2>& in, Vec2 a, Vec2 b, std::vector<Vec2>& out)
{
  out.clear();
  const size_t n = in.size();
  const Vec2 d = b - a;
  for (size_t k = 0; k < n; ++k)
  {
    const Vec2 p = in[k];
    const Vec2 q = in[(k + 1) % n];
    const double sp = cross(d, p - a);
    const double sq = cross(d, q - a);
    if (sp >= 0.0)
    {
      out.push_back(p);
    }
    if ((sp >= 0.0) != (sq >= 0.0))
    {
      const double t = sp / (sp - sq);
      out.push_back(p + t * (q - p));
    }
  }
}

// Integrals of 1, x, y, x^2, xy, y^2 over a polygon, in coordinates relative to o.
struct Moments
{
  double m0 = 0, mx = 0, my = 0, mxx = 0, mxy = 0, myy = 0;
};

Moments polygonMoments(const std::vector<Vec2>& poly, Vec2 o)
{
  Moments m;
  const size_t n = poly.size();
  for (size_t k = 0; k < n; ++k)
  {
    const Vec2 p = poly[k] - o;
    const Vec2 q = poly[(k + 1) % n] - o;
    const double c = cross(p, q);
    m.m0 += c;
    m.mx += c * (p.x + q.x);
    m.my += c * (p.y + q.y);
    m.mxx += c * (p.x * p.x + p.x * q.x + q.x * q.x);
    m.myy += c * (p.y * p.y + p.y * q.y + q.y * q.y);
    m.mxy += c * (2 * p.x * p.y + p.x * q.y + q.x * p.y + 2 * q.x * q.y);
  }
  m.m0 /= 2;
  m.mx /= 6;
  m.my /= 6;
  m.mxx /= 12;
  m.myy /= 12;
  m.mxy /= 24;
  return m;
}

// The domain of a triangulated source: shared by sources that differ in their density only
// (the sampler integrates g and g^2 over one large triangulation).
struct TriangulatedDomain
{
  std::vector<Triangle> triangles; // counter-clockwise, in the caller's order (density ids)
  std::vector<Vec2> hull;          // domain boundary, CCW
  Vec2 lo, hi;
  BoxTree triangleBoxes; // overlap queries (triangles of conformal images span 1e10 in size)
  // The triangles' corners in the box tree's slot order (triangle t in slot slotOf[t]): a cell's
  // integral reads its triangles leaf by leaf from one stretch of memory, not gathered across
  // the mesh by id (1.09M-point face: 2.2M density triangles, 5 integrations in the sampler).
  std::vector<std::array<Vec2, 3>> corners;
  std::vector<int> slotOf;
  Vec2 innerCenter;
  double innerRadius = 0.0;
};

class TriangulatedSource final : public SourceMeasure
{
public:
  std::shared_ptr<const TriangulatedDomain> domain;
  std::vector<double> density; // per point
  // Linear density per triangle, in the domain's slot order: f(x) = c0 + cx * x + cy * y.
  struct Linear
  {
    double c0, cx, cy;
  };
  std::vector<Linear> linear;
  double total = 0.0;

  double totalMass() const override { return total; }
  void bounds(Vec2& l, Vec2& h) const override
  {
    l = domain->lo;
    h = domain->hi;
  }
  void innerDisk(Vec2& center, double& radius) const override
  {
    center = domain->innerCenter;
    radius = domain->innerRadius;
  }

  // The linear pieces and the total mass of `density` over the domain; "" or what is wrong
  // with the density.
  std::string interpolate(bool allowZeroDensity)
  {
    const auto& triangles = domain->triangles;
    linear.resize(triangles.size());
    total = 0.0;
    // In the caller's order, so that the total's rounding does not depend on the tree.
    for (size_t t = 0; t < triangles.size(); ++t)
    {
      const Triangle& tri = triangles[t];
      const int slot = domain->slotOf[t];
      for (int k = 0; k < 3; ++k)
      {
        const double f = density[tri[k]];
        if (!(std::isfinite(f) && (f > 0.0 || (allowZeroDensity && f == 0.0))))
        {
          std::ostringstream s;
          s << "source density at point " << tri[k] << " is " << f
            << "; it must be finite and positive";
          return s.str();
        }
      }
      const auto& [pa, pb, pc] = domain->corners[slot];
      const double fa = density[tri[0]], fb = density[tri[1]], fc = density[tri[2]];
      const double det = cross(pb - pa, pc - pa);
      const double cx = ((fb - fa) * (pc.y - pa.y) - (fc - fa) * (pb.y - pa.y)) / det;
      const double cy = ((fc - fa) * (pb.x - pa.x) - (fb - fa) * (pc.x - pa.x)) / det;
      linear[slot] = { fa - cx * pa.x - cy * pa.y, cx, cy };
      total += det / 6.0 * (fa + fb + fc);
    }
    return {};
  }

  double densityAt(int slot, Vec2 p) const
  {
    const Linear& f = linear[slot];
    return f.c0 + f.cx * p.x + f.cy * p.y;
  }

  void integrate(const PowerCell& cell, CellIntegrals& out) const override
  {
    out.mass = 0.0;
    out.moment = { 0.0, 0.0 };
    out.edgeMass.clear();
    if (cell.vertices.size() < 3)
    {
      return;
    }
    Vec2 cl = cell.vertices[0], ch = cell.vertices[0];
    for (const Vec2& p : cell.vertices)
    {
      cl = { std::min(cl.x, p.x), std::min(cl.y, p.y) };
      ch = { std::max(ch.x, p.x), std::max(ch.y, p.y) };
    }
    thread_local std::vector<Vec2> piece;
    thread_local std::vector<size_t> usableEdges;
    usableEdgesOf(cell, norm(ch - cl), usableEdges);
    const size_t n = cell.vertices.size();
    std::vector<double> edgeIntegral(n, 0.0);
    const Vec2 o = cell.vertices[0];
    domain->triangleBoxes.forOverlappingSlots(cl, ch,
      [&](int slot)
      {
        if (!clipToCell(slot, cell, usableEdges, piece))
        {
          return;
        }
        const Moments m = polygonMoments(piece, o);
        if (m.m0 <= 0.0)
        {
          return;
        }
        // Density in local coordinates: f = d0 + cx * u + cy * v with x = o + (u, v).
        const Linear& f = linear[slot];
        const double d0 = f.c0 + f.cx * o.x + f.cy * o.y;
        const double mass = d0 * m.m0 + f.cx * m.mx + f.cy * m.my;
        const double mu = d0 * m.mx + f.cx * m.mxx + f.cy * m.mxy;
        const double mv = d0 * m.my + f.cx * m.mxy + f.cy * m.myy;
        out.mass += mass;
        out.moment = out.moment + Vec2{ mu + o.x * mass, mv + o.y * mass };
        if (out.wantEdgeMass)
        {
          addEdgeDensity(slot, piece, cell, o, edgeIntegral);
        }
      });
    for (size_t k = 0; k < n; ++k)
    {
      if (cell.neighbor[k] >= 0 && edgeIntegral[k] > 0.0)
      {
        out.edgeMass.emplace_back(cell.neighbor[k], edgeIntegral[k]);
      }
    }
  }

  // Two cell vertices that are one point up to rounding make an edge with no usable direction
  // that puts every triangle outside (measured: 1e-14 apart in a cell of 1e-7, and 7e-14 apart
  // in a cell of 4e-7 at a hand's finger tip, density 1e10). Leaving an edge shorter than 1e-6
  // of the cell out changes its area by O(1e-12) relatively.
  static void usableEdgesOf(const PowerCell& cell, double cellSize, std::vector<size_t>& usable)
  {
    const size_t n = cell.vertices.size();
    usable.clear();
    for (size_t k = 0; k < n; ++k)
    {
      if (norm(cell.vertices[(k + 1) % n] - cell.vertices[k]) > 1e-6 * cellSize)
      {
        usable.push_back(k);
      }
    }
  }

  // The triangle in `slot` clipped to the cell, in `piece`; false when nothing of it is left.
  bool clipToCell(int slot, const PowerCell& cell, const std::vector<size_t>& usableEdges,
    std::vector<Vec2>& piece) const
  {
    thread_local std::vector<Vec2> scratch;
    thread_local std::vector<size_t> crossing;
    const auto& [p0, p1, p2] = domain->corners[slot];
    const size_t n = cell.vertices.size();
    // Clip only against the cell edges that cut the triangle; most triangles are inside every
    // edge but one or two, or outside one edge (measured: 2x faster integration).
    crossing.clear();
    for (size_t k : usableEdges)
    {
      const Vec2 a = cell.vertices[k], d = cell.vertices[(k + 1) % n] - a;
      const bool in0 = cross(d, p0 - a) >= 0.0, in1 = cross(d, p1 - a) >= 0.0,
                 in2 = cross(d, p2 - a) >= 0.0;
      if (!in0 && !in1 && !in2)
      {
        return false;
      }
      if (!(in0 && in1 && in2))
      {
        crossing.push_back(k);
      }
    }
    piece = { p0, p1, p2 };
    for (size_t k : crossing)
    {
      clipLeftOf(piece, cell.vertices[k], cell.vertices[(k + 1) % n], scratch);
      piece.swap(scratch);
      if (piece.size() < 3)
      {
        return false;
      }
    }
    return true;
  }

  // Density along the cell's edges: pieces of the clipped boundary (`piece`) of the triangle in
  // `slot` that lie on cell edge k add to edgeIntegral[k]. A cell edge lying exactly on a mesh edge
  // is counted for the triangle on the cell's side only (a point nudged into the cell must be
  // inside the triangle).
  void addEdgeDensity(int slot, const std::vector<Vec2>& piece, const PowerCell& cell, Vec2 o,
    std::vector<double>& edgeIntegral) const
  {
    const size_t n = cell.vertices.size(), pm = piece.size();
    for (size_t e = 0; e < pm; ++e)
    {
      const Vec2 a = piece[e], b = piece[(e + 1) % pm];
      const double len = norm(b - a);
      if (len == 0.0)
      {
        continue;
      }
      for (size_t k = 0; k < n; ++k)
      {
        const int nb = cell.neighbor[k];
        if (nb < 0)
        {
          continue;
        }
        const Vec2 ca = cell.vertices[k], cb = cell.vertices[(k + 1) % n];
        const Vec2 dir = cb - ca;
        const double dl = norm(dir);
        const double tol = 1e-12 * (dl + norm(ca - o) + 1e-300);
        if (std::abs(cross(dir, a - ca)) > tol * dl || std::abs(cross(dir, b - ca)) > tol * dl)
        {
          continue;
        }
        const Vec2 mid = 0.5 * (a + b);
        const Vec2 inward = (1e-9 * len / dl) * Vec2{ -dir.y, dir.x };
        if (!insideTriangle(slot, mid + inward))
        {
          break;
        }
        edgeIntegral[k] += 0.5 * len * (densityAt(slot, a) + densityAt(slot, b));
        break;
      }
    }
  }

  bool insideTriangle(int slot, Vec2 p) const
  {
    const std::array<Vec2, 3>& corner = domain->corners[slot];
    for (int k = 0; k < 3; ++k)
    {
      const Vec2 a = corner[k], b = corner[(k + 1) % 3];
      if (cross(b - a, p - a) < 0.0)
      {
        return false;
      }
    }
    return true;
  }

  std::vector<Vec2> clippedBoundary(const PowerCell& cell, double) const override
  {
    std::vector<Vec2> poly = cell.vertices, scratch;
    const auto& hull = domain->hull;
    const size_t n = hull.size();
    for (size_t k = 0; k < n && poly.size() >= 3; ++k)
    {
      clipLeftOf(poly, hull[k], hull[(k + 1) % n], scratch);
      poly.swap(scratch);
    }
    if (poly.size() < 3)
    {
      poly.clear();
    }
    return poly;
  }
};

// Akl and Toussaint's filter: the points clearly inside the octagon of the extreme points in
// eight directions cannot be hull vertices. On a triangulated disk that is nearly all of them:
// the sort below then orders a few thousand points instead of three per triangle (1.09M-point
// surface: ~1 s per source).
std::vector<Vec2> withoutOctagonInterior(const std::vector<Vec2>& p)
{
  if (p.size() < 64)
  {
    return p;
  }
  const std::array<Vec2, 8> directions = { Vec2{ 1, 0 }, Vec2{ 1, 1 }, Vec2{ 0, 1 }, Vec2{ -1, 1 },
    Vec2{ -1, 0 }, Vec2{ -1, -1 }, Vec2{ 0, -1 }, Vec2{ 1, -1 } };
  const auto same = [](Vec2 a, Vec2 b) { return a.x == b.x && a.y == b.y; };
  std::vector<Vec2> octagon; // counter-clockwise, repeated corners dropped
  for (const Vec2& direction : directions)
  {
    const Vec2 extreme = *std::max_element(
      p.begin(), p.end(), [&](Vec2 a, Vec2 b) { return dot(a, direction) < dot(b, direction); });
    if (octagon.empty() || !same(extreme, octagon.back()))
    {
      octagon.push_back(extreme);
    }
  }
  if (octagon.size() > 1 && same(octagon.front(), octagon.back()))
  {
    octagon.pop_back();
  }
  if (octagon.size() < 3)
  {
    return p;
  }
  std::vector<Vec2> kept;
  for (const Vec2& x : p)
  {
    bool inside = true;
    for (size_t k = 0; k < octagon.size() && inside; ++k)
    {
      const Vec2 a = octagon[k], d = octagon[(k + 1) % octagon.size()] - a, r = x - a;
      // Clearly inside: by more than any rounding of the cross product.
      inside =
        cross(d, r) > 1e-12 * (std::abs(d.x) + std::abs(d.y)) * (std::abs(r.x) + std::abs(r.y));
    }
    if (!inside)
    {
      kept.push_back(x);
    }
  }
  return kept;
}

// Andrew's monotone chain; returns the hull CCW without collinear points.
std::vector<Vec2> convexHull(const std::vector<Vec2>& points)
{
  std::vector<Vec2> p = withoutOctagonInterior(points);
  std::sort(
    p.begin(), p.end(), [](Vec2 a, Vec2 b) { return a.x < b.x || (a.x == b.x && a.y < b.y); });
  if (p.size() < 3)
  {
    return p;
  }
  std::vector<Vec2> h(2 * p.size());
  size_t k = 0;
  for (size_t i = 0; i < p.size(); ++i)
  {
    while (k >= 2 && cross(h[k - 1] - h[k - 2], p[i] - h[k - 2]) <= 0)
    {
      --k;
    }
    h[k++] = p[i];
  }
  for (size_t i = p.size() - 1, t = k + 1; i > 0; --i)
  {
    while (k >= t && cross(h[k - 1] - h[k - 2], p[i - 1] - h[k - 2]) <= 0)
    {
      --k;
    }
    h[k++] = p[i - 1];
  }
  h.resize(k - 1);
  return h;
}

} // namespace

std::unique_ptr<SourceMeasure> makeUnitDiskSource()
{
  return std::make_unique<UnitDiskSource>();
}

namespace
{
// The triangles' point ids and coordinates checked, each triangle stored counter-clockwise
// (orientation does not matter for a planar domain), the points used marked; "" or what is
// wrong. `area` gets the triangles' total area.
std::string checkAndOrient(const std::vector<Vec2>& points, TriangulatedDomain& domain,
  std::vector<char>& used, double& area)
{
  used.assign(points.size(), 0);
  area = 0.0;
  for (size_t t = 0; t < domain.triangles.size(); ++t)
  {
    Triangle& tri = domain.triangles[t];
    for (int k = 0; k < 3; ++k)
    {
      if (tri[k] < 0 || static_cast<size_t>(tri[k]) >= points.size())
      {
        return "source triangle " + std::to_string(t) + " refers to a point that does not exist";
      }
      const Vec2 p = points[tri[k]];
      if (!std::isfinite(p.x) || !std::isfinite(p.y))
      {
        return "source point " + std::to_string(tri[k]) + " has a non-finite coordinate";
      }
      used[tri[k]] = 1;
    }
    const Vec2 a = points[tri[0]], b = points[tri[1]], c = points[tri[2]];
    double twice = cross(b - a, c - a);
    if (twice < 0.0)
    {
      std::swap(tri[1], tri[2]);
      twice = -twice;
    }
    if (!(twice > 0.0))
    {
      return "source triangle " + std::to_string(t) + " has zero area";
    }
    area += 0.5 * twice;
  }
  return {};
}

// Relative to the first corner: absolute coordinates lose the area of a small domain far from
// the origin to cancellation.
double polygonArea(const std::vector<Vec2>& polygon)
{
  double twice = 0.0;
  for (size_t k = 0; k < polygon.size(); ++k)
  {
    twice += cross(polygon[k] - polygon[0], polygon[(k + 1) % polygon.size()] - polygon[0]);
  }
  return 0.5 * twice;
}

// The hull's bounding box, and the inner disk: centred at the hull's centroid, radius = the
// distance to the nearest hull edge.
void setBoundsAndInnerDisk(TriangulatedDomain& domain)
{
  const std::vector<Vec2>& hull = domain.hull;
  domain.lo = domain.hi = hull[0];
  Vec2 c = { 0.0, 0.0 };
  for (const Vec2& p : hull)
  {
    domain.lo = { std::min(domain.lo.x, p.x), std::min(domain.lo.y, p.y) };
    domain.hi = { std::max(domain.hi.x, p.x), std::max(domain.hi.y, p.y) };
    c = c + p;
  }
  c = (1.0 / hull.size()) * c;
  double r = std::numeric_limits<double>::max();
  for (size_t k = 0; k < hull.size(); ++k)
  {
    const Vec2 a = hull[k], b = hull[(k + 1) % hull.size()];
    r = std::min(r, cross(b - a, c - a) / norm(b - a));
  }
  domain.innerCenter = c;
  domain.innerRadius = r;
}

// The box tree over the (oriented) triangles, and their corners in its slot order.
void buildTriangleBoxes(const std::vector<Vec2>& points, TriangulatedDomain& domain)
{
  const size_t n = domain.triangles.size();
  std::vector<BoxTree::Item> boxes(n);
  for (size_t t = 0; t < n; ++t)
  {
    const Triangle& tri = domain.triangles[t];
    BoxTree::Item& box = boxes[t];
    box.lo = box.hi = points[tri[0]];
    for (int k = 1; k < 3; ++k)
    {
      const Vec2 p = points[tri[k]];
      box.lo = { std::min(box.lo.x, p.x), std::min(box.lo.y, p.y) };
      box.hi = { std::max(box.hi.x, p.x), std::max(box.hi.y, p.y) };
    }
    box.value = 0.0;
  }
  domain.triangleBoxes = BoxTree(std::move(boxes));
  domain.corners.resize(n);
  domain.slotOf.resize(n);
  for (size_t slot = 0; slot < n; ++slot)
  {
    const int t = domain.triangleBoxes.itemAt(static_cast<int>(slot));
    const Triangle& tri = domain.triangles[t];
    domain.corners[slot] = { points[tri[0]], points[tri[1]], points[tri[2]] };
    domain.slotOf[t] = static_cast<int>(slot);
  }
}
} // namespace

std::unique_ptr<SourceMeasure> makeTriangulatedSource(const std::vector<Vec2>& points,
  const std::vector<Triangle>& triangles, const std::vector<double>& density, std::string& error,
  bool allowZeroDensity, bool allowNonConvex, const std::vector<Vec2>* hullCandidates)
{
  error.clear();
  if (triangles.empty())
  {
    error = "the source domain has no triangles";
    return nullptr;
  }
  if (!density.empty() && density.size() != points.size())
  {
    error = "the source density must have one value per point";
    return nullptr;
  }
  auto domain = std::make_shared<TriangulatedDomain>();
  domain->triangles = triangles;
  std::vector<char> used;
  double area = 0.0;
  error = checkAndOrient(points, *domain, used, area);
  if (!error.empty())
  {
    return nullptr;
  }
  if (hullCandidates)
  {
    // The sampler's piecewise-constant densities give every triangle its own three points:
    // the hull of all of them took 0.26 s at 6.6M points.
    domain->hull = convexHull(*hullCandidates);
  }
  else
  {
    std::vector<Vec2> usedPoints;
    for (size_t i = 0; i < points.size(); ++i)
    {
      if (used[i])
      {
        usedPoints.push_back(points[i]);
      }
    }
    domain->hull = convexHull(usedPoints);
  }
  const double hullArea = polygonArea(domain->hull);
  if (!allowNonConvex && std::abs(hullArea - area) > 1e-9 * hullArea)
  {
    std::ostringstream s;
    s << "the source domain is not convex (or its triangles overlap): triangle area " << area
      << " differs from the area of its convex hull " << hullArea;
    error = s.str();
    return nullptr;
  }
  setBoundsAndInnerDisk(*domain);
  buildTriangleBoxes(points, *domain);
  auto src = std::make_unique<TriangulatedSource>();
  src->domain = std::move(domain);
  src->density = density.empty() ? std::vector<double>(points.size(), 1.0) : density;
  error = src->interpolate(allowZeroDensity);
  return error.empty() ? std::move(src) : nullptr;
}

std::unique_ptr<SourceMeasure> withMappedDensity(const SourceMeasure& triangulated,
  const std::function<double(double)>& map, std::string& error, bool allowZeroDensity)
{
  const auto* from = dynamic_cast<const TriangulatedSource*>(&triangulated);
  if (!from)
  {
    error = "withMappedDensity needs a triangulated source";
    return nullptr;
  }
  auto src = std::make_unique<TriangulatedSource>();
  src->domain = from->domain;
  src->density.resize(from->density.size());
  std::transform(from->density.begin(), from->density.end(), src->density.begin(), map);
  error = src->interpolate(allowZeroDensity);
  return error.empty() ? std::move(src) : nullptr;
}

} // namespace otparam
