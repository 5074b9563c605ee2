// Exact integration of the source measures over convex cells.
#include "Transport/PlanarSource.h"
#include "Transport/SemiDiscreteOT.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

using namespace otparam;

namespace
{
constexpr double Pi = 3.14159265358979323846;

PowerCell box(Vec2 lo, Vec2 hi)
{
  PowerCell c;
  c.vertices = { lo, { hi.x, lo.y }, hi, { lo.x, hi.y } };
  c.neighbor = { 0, 1, 2, 3 };
  return c;
}
} // namespace

TEST(UnitDiskSource, HalfPlaneCellIsHalfDisk)
{
  auto disk = makeUnitDiskSource();
  CellIntegrals out;
  disk->integrate(box({ 0.0, -2.0 }, { 2.0, 2.0 }), out);
  EXPECT_NEAR(out.mass, Pi / 2, 1e-15);
  // Centroid of a half disk: 4 / (3 pi) from the centre.
  EXPECT_NEAR(out.moment.x / out.mass, 4.0 / (3.0 * Pi), 1e-15);
  EXPECT_NEAR(out.moment.y, 0.0, 1e-15);
  // Only the edge on x = 0 crosses the disk; its length inside is 2.
  ASSERT_EQ(out.edgeMass.size(), 1u);
  EXPECT_EQ(out.edgeMass[0].first, 3);
  EXPECT_NEAR(out.edgeMass[0].second, 2.0, 1e-15);
}

TEST(UnitDiskSource, CircularSegmentAndInteriorSquare)
{
  auto disk = makeUnitDiskSource();
  CellIntegrals out;
  // Segment cut by the chord x = 0.5: area = acos(d) - d sqrt(1 - d^2).
  disk->integrate(box({ 0.5, -2.0 }, { 2.0, 2.0 }), out);
  const double d = 0.5;
  EXPECT_NEAR(out.mass, std::acos(d) - d * std::sqrt(1 - d * d), 1e-15);
  // A square well inside the disk is integrated as a polygon.
  disk->integrate(box({ 0.1, 0.2 }, { 0.3, 0.5 }), out);
  EXPECT_NEAR(out.mass, 0.06, 1e-16);
  EXPECT_NEAR(out.moment.x / out.mass, 0.2, 1e-15);
  EXPECT_NEAR(out.moment.y / out.mass, 0.35, 1e-15);
  // A cell containing the whole disk, and one missing it.
  disk->integrate(box({ -3, -3 }, { 3, 3 }), out);
  EXPECT_NEAR(out.mass, Pi, 1e-15);
  disk->integrate(box({ 2, 2 }, { 3, 3 }), out);
  EXPECT_EQ(out.mass, 0.0);
}

TEST(UnitDiskSource, TinySegmentsKeepRelativeAccuracy)
{
  // A thin circular segment: chord at distance 1 - 1e-6 from the centre.
  auto disk = makeUnitDiskSource();
  CellIntegrals out;
  const double d = 1.0 - 1e-6;
  disk->integrate(box({ d, -2.0 }, { 2.0, 2.0 }), out);
  // acos(d) - d sqrt(1-d^2) with a series in e = 1 - d: (4 sqrt(2)/3) e^{3/2} (1 - 3e/20 ...)
  const double e = 1e-6;
  const double exact = 4.0 * std::sqrt(2.0) / 3.0 * std::pow(e, 1.5) * (1.0 - 0.15 * e);
  EXPECT_NEAR(out.mass / exact, 1.0, 1e-6);
}

TEST(TriangulatedSource, LinearDensityOnSquare)
{
  // [0,1]^2 split into 2 x 2 squares, each cut along a diagonal; f = 1 + x + 2 y.
  std::vector<Vec2> pts;
  for (int j = 0; j <= 2; ++j)
    for (int i = 0; i <= 2; ++i)
      pts.push_back({ 0.5 * i, 0.5 * j });
  std::vector<Triangle> tris;
  for (int j = 0; j < 2; ++j)
    for (int i = 0; i < 2; ++i)
    {
      const int a = j * 3 + i, b = a + 1, c = a + 4, d = a + 3;
      tris.push_back({ a, b, c });
      tris.push_back({ a, c, d });
    }
  std::vector<double> f;
  for (const Vec2& p : pts)
    f.push_back(1 + p.x + 2 * p.y);
  std::string error;
  auto src = makeTriangulatedSource(pts, tris, f, error);
  ASSERT_TRUE(src) << error;
  EXPECT_NEAR(src->totalMass(), 2.5, 1e-15);
  // A cell that is the strip x <= c (edge on x = c shared with neighbour 7).
  const double c = 0.3;
  PowerCell cell;
  cell.vertices = { { -1, -1 }, { c, -1 }, { c, 2 }, { -1, 2 } };
  cell.neighbor = { -1, 7, -1, -1 };
  CellIntegrals out;
  src->integrate(cell, out);
  EXPECT_NEAR(out.mass, 2 * c + c * c / 2, 1e-15);
  EXPECT_NEAR(out.moment.x, c * c + c * c * c / 3, 1e-15);
  EXPECT_NEAR(out.moment.y, 7.0 / 6.0 * c + c * c / 4, 1e-15);
  // The shared edge: integral of f along x = c, y in [0,1] = 1 + c + 1.
  ASSERT_EQ(out.edgeMass.size(), 1u);
  EXPECT_EQ(out.edgeMass[0].first, 7);
  EXPECT_NEAR(out.edgeMass[0].second, 2 + c, 1e-14);
  // An edge lying exactly on mesh edges (x = 0.5) is counted once.
  cell.vertices = { { -1, -1 }, { 0.5, -1 }, { 0.5, 2 }, { -1, 2 } };
  src->integrate(cell, out);
  ASSERT_EQ(out.edgeMass.size(), 1u);
  EXPECT_NEAR(out.edgeMass[0].second, 2.5, 1e-14);
}

TEST(TriangulatedSource, MappedDensityEqualsAFreshBuild)
{
  // A fan of 12 triangles around (0.1, 0.2), listed with mixed orientations, f = 2 + x^2 + y.
  std::vector<Vec2> pts = { { 0.1, 0.2 } };
  std::vector<Triangle> tris;
  for (int k = 0; k < 12; ++k)
  {
    pts.push_back({ std::cos(k * Pi / 6), std::sin(k * Pi / 6) });
    tris.push_back(
      k % 2 ? Triangle{ 0, 1 + k, 1 + (k + 1) % 12 } : Triangle{ 0, 1 + (k + 1) % 12, 1 + k });
  }
  std::vector<double> f, squared;
  for (const Vec2& p : pts)
  {
    f.push_back(2 + p.x * p.x + p.y);
    squared.push_back(std::pow(f.back(), 2.0));
  }
  std::string error;
  const auto source = makeTriangulatedSource(pts, tris, f, error);
  ASSERT_TRUE(source) << error;
  const auto fresh = makeTriangulatedSource(pts, tris, squared, error);
  ASSERT_TRUE(fresh) << error;
  const auto mapped = withMappedDensity(
    *source, [](double g) { return std::pow(g, 2.0); }, error);
  ASSERT_TRUE(mapped) << error;
  EXPECT_EQ(mapped->totalMass(), fresh->totalMass());
  EXPECT_NE(mapped->totalMass(), source->totalMass());
  PowerCell cell;
  cell.vertices = { { -0.3, -2 }, { 0.4, -2 }, { 0.7, 2 }, { -0.3, 2 } };
  cell.neighbor = { -1, 3, -1, 5 };
  CellIntegrals a, b;
  mapped->integrate(cell, a);
  fresh->integrate(cell, b);
  EXPECT_EQ(a.mass, b.mass);
  EXPECT_EQ(a.moment.x, b.moment.x);
  EXPECT_EQ(a.moment.y, b.moment.y);
  ASSERT_EQ(a.edgeMass.size(), b.edgeMass.size());
  for (size_t k = 0; k < a.edgeMass.size(); ++k)
  {
    EXPECT_EQ(a.edgeMass[k], b.edgeMass[k]);
  }
  // The original keeps its density.
  CellIntegrals c;
  source->integrate(cell, c);
  EXPECT_LT(c.mass, a.mass);
  // Refused: a mapped value that is not positive, and a source that is not triangulated.
  EXPECT_FALSE(withMappedDensity(
    *source, [](double g) { return 1.0 - g; }, error));
  EXPECT_NE(error.find("must be finite and positive"), std::string::npos) << error;
  EXPECT_TRUE(withMappedDensity(
    *source, [](double) { return 0.0; }, error, true))
    << error;
  EXPECT_FALSE(withMappedDensity(
    *makeUnitDiskSource(), [](double g) { return g; }, error));
}

TEST(TriangulatedSource, CellWithTwoVerticesOneUpToRounding)
{
  // A cell 1e-6 across with two vertices 1e-14 apart whose tiny edge points the wrong way (the
  // rounding noise that power diagrams of samples 1e-6 apart produce): that edge once put
  // every triangle "outside" and gave the cell mass 0.
  const Vec2 o = { 0.6, 0.3 };
  const double h = 1e-6;
  const std::vector<Vec2> pts = { { o.x + 0.2 * h, o.y + 0.2 * h },
    { o.x + 0.8 * h, o.y + 0.2 * h }, { o.x + 0.5 * h, o.y + 0.8 * h } };
  std::string error;
  auto src = makeTriangulatedSource(pts, { { 0, 1, 2 } }, {}, error);
  ASSERT_TRUE(src) << error;
  PowerCell cell;
  cell.vertices = { o, { o.x - 1.8e-14, o.y + 3e-15 }, { o.x + h, o.y }, { o.x + h, o.y + h },
    { o.x, o.y + h } };
  cell.neighbor = { 1, 2, 3, 4, 5 };
  CellIntegrals out;
  out.wantEdgeMass = false;
  src->integrate(cell, out);
  EXPECT_NEAR(out.mass, 0.18 * h * h, 1e-9 * h * h);
}

TEST(TriangulatedSource, FingerTipCellWithRoundingEdge)
{
  // A Voronoi cell of a sample at a finger tip of hand_stein_810's conformal image (density
  // 1.4e10, cell 4e-7 across), vertices as the power diagram computed them: the third and the
  // fourth are one point up to rounding (7e-14 apart, 1.9e-7 of the cell). Its mass came out 0.
  const std::vector<Vec2> cellVertices = { { -0.02036911175249553, -0.0099194702727914003 },
    { -0.020369118840983903, -0.00991930043289517 },
    { -0.020369378718527769, -0.0099192650985339519 },
    { -0.020369378718475203, -0.0099192650984860839 },
    { -0.020369367781866647, -0.0099195271391871523 } };
  const Vec2 c = cellVertices[0];
  double area = 0.0; // relative to a vertex: absolute coordinates would cancel to 1e-6
  for (size_t k = 0; k < cellVertices.size(); ++k)
  {
    area += 0.5 * cross(cellVertices[k] - c, cellVertices[(k + 1) % cellVertices.size()] - c);
  }
  // A density triangle 1e-5 across around it, density 1.
  std::string error;
  auto src = makeTriangulatedSource(
    { { c.x - 1e-5, c.y - 1e-5 }, { c.x + 1e-5, c.y - 1e-5 }, { c.x, c.y + 1e-5 } },
    { { 0, 1, 2 } }, {}, error);
  ASSERT_TRUE(src) << error;
  PowerCell cell;
  cell.vertices = cellVertices;
  cell.neighbor = { 1, 2, 3, 4, 5 };
  CellIntegrals out;
  out.wantEdgeMass = false;
  src->integrate(cell, out);
  EXPECT_NEAR(out.mass, std::abs(area), 1e-9 * std::abs(area));
}

TEST(TriangulatedSource, RejectsBadDomains)
{
  std::string error;
  const std::vector<Vec2> pts = { { 0, 0 }, { 1, 0 }, { 1, 1 }, { 0, 1 }, { 0.5, 0.2 } };
  // Non-convex: the square with a notch (triangles fan from the notch point miss a part).
  EXPECT_FALSE(makeTriangulatedSource(pts, { { 0, 4, 3 }, { 4, 1, 2 }, { 4, 2, 3 } }, {}, error));
  EXPECT_NE(error.find("not convex"), std::string::npos) << error;
  EXPECT_FALSE(makeTriangulatedSource(pts, {}, {}, error));
  EXPECT_FALSE(
    makeTriangulatedSource(pts, { { 0, 1, 2 }, { 0, 2, 3 } }, { 1, 1, -1, 1, 1 }, error));
  EXPECT_NE(error.find("positive"), std::string::npos) << error;
  EXPECT_FALSE(
    makeTriangulatedSource(pts, { { 0, 1, 2 }, { 0, 2, 3 } }, { 1, 1, NAN, 1, 1 }, error));
  EXPECT_FALSE(makeTriangulatedSource(pts, { { 0, 1, 1 } }, {}, error));
  EXPECT_NE(error.find("zero area"), std::string::npos) << error;
  EXPECT_TRUE(makeTriangulatedSource(pts, { { 0, 1, 2 }, { 0, 2, 3 } }, {}, error)) << error;
}

// Domains of many points, whose hull is computed after Akl and Toussaint's filter: a grid
// square (sides full of collinear points, two extreme directions per corner), an L of grid
// cells, a fan of a 200-gon.
TEST(TriangulatedSource, HullOfManyPoints)
{
  const auto grid = [](int n, bool notch, std::vector<Vec2>& pts, std::vector<Triangle>& tris)
  {
    for (int j = 0; j <= n; ++j)
    {
      for (int i = 0; i <= n; ++i)
      {
        pts.push_back({ static_cast<double>(i) / n, static_cast<double>(j) / n });
      }
    }
    for (int j = 0; j < n; ++j)
    {
      for (int i = 0; i < n; ++i)
      {
        if (notch && i >= n / 2 && j >= n / 2)
        {
          continue;
        }
        const int v = j * (n + 1) + i;
        tris.push_back({ v, v + 1, v + n + 2 });
        tris.push_back({ v, v + n + 2, v + n + 1 });
      }
    }
  };
  const auto area = [](const std::vector<Vec2>& polygon)
  {
    double twice = 0.0;
    for (size_t k = 0; k < polygon.size(); ++k)
    {
      twice += cross(polygon[k], polygon[(k + 1) % polygon.size()]);
    }
    return 0.5 * twice;
  };
  PowerCell everything;
  everything.vertices = { { -10, -10 }, { 10, -10 }, { 10, 10 }, { -10, 10 } };
  std::string error;

  std::vector<Vec2> pts;
  std::vector<Triangle> tris;
  grid(30, false, pts, tris);
  const auto square = makeTriangulatedSource(pts, tris, {}, error);
  ASSERT_TRUE(square) << error;
  const std::vector<Vec2> squareHull = square->clippedBoundary(everything, 0.1);
  EXPECT_EQ(squareHull.size(), 4u);
  EXPECT_NEAR(area(squareHull), 1.0, 1e-12);

  pts.clear();
  tris.clear();
  grid(30, true, pts, tris);
  EXPECT_FALSE(makeTriangulatedSource(pts, tris, {}, error));
  EXPECT_NE(error.find("not convex"), std::string::npos) << error;

  pts = { { 0.0, 0.0 } };
  tris.clear();
  const int sides = 200;
  for (int k = 0; k < sides; ++k)
  {
    const double angle = 2.0 * 3.141592653589793 * k / sides;
    pts.push_back({ std::cos(angle), std::sin(angle) });
    tris.push_back({ 0, 1 + k, 1 + (k + 1) % sides });
  }
  const auto fan = makeTriangulatedSource(pts, tris, {}, error);
  ASSERT_TRUE(fan) << error;
  const std::vector<Vec2> fanHull = fan->clippedBoundary(everything, 0.1);
  EXPECT_EQ(fanHull.size(), static_cast<size_t>(sides));
  EXPECT_NEAR(area(fanHull), fan->totalMass(), 1e-12);
}

TEST(UnitDiskSource, VoronoiAreasMatchAPixelCount)
{
  // Independent check of the clipped Voronoi cells: count pixel centres nearest to each site.
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-1, 1);
  std::vector<Vec2> y;
  while (y.size() < 20)
  {
    Vec2 p{ u(rng), u(rng) };
    if (dot(p, p) < 1)
      y.push_back(p);
  }
  std::vector<double> h;
  for (const Vec2& p : y)
    h.push_back(0.5 * dot(p, p));
  auto disk = makeUnitDiskSource();
  const CellMeasures cm = computeCellMeasures(*disk, y, h);
  const int res = 1500;
  const double px = 2.0 / res;
  std::vector<double> count(y.size(), 0.0);
  for (int j = 0; j < res; ++j)
    for (int i = 0; i < res; ++i)
    {
      const Vec2 x{ -1 + (i + 0.5) * px, -1 + (j + 0.5) * px };
      if (dot(x, x) > 1)
        continue;
      size_t best = 0;
      for (size_t k = 1; k < y.size(); ++k)
        if (norm(x - y[k]) < norm(x - y[best]))
          best = k;
      count[best] += px * px;
    }
  double total = 0;
  for (size_t k = 0; k < y.size(); ++k)
  {
    EXPECT_NEAR(cm.mass[k], count[k], 2e-3) << "cell " << k;
    total += cm.mass[k];
  }
  EXPECT_NEAR(total, Pi, 1e-13);
}

TEST(TriangulatedSource, HullFromCandidatesEqualsTheHullOfAllPoints)
{
  // A fan of 12 triangles around (0.1, 0.2), each with its own three points (as the sampler's
  // piecewise-constant sources have them); the candidates are the rim's 12 points only.
  std::vector<Vec2> rim, pts;
  std::vector<Triangle> tris;
  std::vector<double> f;
  for (int k = 0; k < 12; ++k)
  {
    rim.push_back({ std::cos(k * Pi / 6), std::sin(k * Pi / 6) });
  }
  for (int k = 0; k < 12; ++k)
  {
    const int first = static_cast<int>(pts.size());
    pts.insert(pts.end(), { { 0.1, 0.2 }, rim[k], rim[(k + 1) % 12] });
    tris.push_back({ first, first + 1, first + 2 });
    f.insert(f.end(), 3, 1.0 + k);
  }
  std::string error;
  const auto all = makeTriangulatedSource(pts, tris, f, error);
  ASSERT_TRUE(all) << error;
  const auto fromCandidates = makeTriangulatedSource(pts, tris, f, error, false, false, &rim);
  ASSERT_TRUE(fromCandidates) << error;
  Vec2 lo1, hi1, lo2, hi2, c1, c2;
  double r1 = 0.0, r2 = 0.0;
  all->bounds(lo1, hi1);
  fromCandidates->bounds(lo2, hi2);
  all->innerDisk(c1, r1);
  fromCandidates->innerDisk(c2, r2);
  EXPECT_EQ(lo1.x, lo2.x);
  EXPECT_EQ(hi1.y, hi2.y);
  EXPECT_EQ(c1.x, c2.x);
  EXPECT_EQ(c1.y, c2.y);
  EXPECT_EQ(r1, r2);
  EXPECT_EQ(all->totalMass(), fromCandidates->totalMass());
  PowerCell cell;
  cell.vertices = { { -0.3, -2 }, { 0.4, -2 }, { 0.7, 2 }, { -0.3, 2 } };
  cell.neighbor = { -1, 3, -1, 5 };
  const std::vector<Vec2> a = all->clippedBoundary(cell, 0.1);
  const std::vector<Vec2> b = fromCandidates->clippedBoundary(cell, 0.1);
  ASSERT_EQ(a.size(), b.size());
  for (size_t k = 0; k < a.size(); ++k)
  {
    EXPECT_EQ(a[k].x, b[k].x);
    EXPECT_EQ(a[k].y, b[k].y);
  }
  // Candidates that miss a corner give a smaller hull: the tiling no longer matches it.
  const std::vector<Vec2> partial(rim.begin(), rim.begin() + 11);
  EXPECT_FALSE(makeTriangulatedSource(pts, tris, f, error, false, false, &partial));
  EXPECT_NE(error.find("not convex"), std::string::npos) << error;
}
