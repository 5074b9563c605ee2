// The filtered power test (Common/PowerTestKernel.h): every sign it certifies is the exact one,
// it leaves exact ties and near ties to the exact predicate, and regular triangulations built
// with it are the ones CGAL's kernel builds, stored in the same order.
#include "Common/PowerTestKernel.h"

#include <CGAL/Regular_triangulation_2.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <random>
#include <vector>

namespace otparam
{
namespace
{
using WeightedPoint = CGAL::Epick::Weighted_point_2;

struct Site
{
  double x, y, w;
};

// CGAL's own answer (interval arithmetic, then exact numbers).
int exactSign(const Site& p, const Site& q, const Site& r, const Site& t)
{
  const auto test = CGAL::Epick().power_side_of_oriented_power_circle_2_object();
  const auto point = [](const Site& s)
  { return WeightedPoint(CGAL::Epick::Point_2(s.x, s.y), s.w); };
  return static_cast<int>(test(point(p), point(q), point(r), point(t)));
}

int filteredSign(const Site& p, const Site& q, const Site& r, const Site& t)
{
  return certifiedPowerTestSign(p.x, p.y, p.w, q.x, q.y, q.w, r.x, r.y, r.w, t.x, t.y, t.w);
}

// Counts how often the filter decides, and fails the test on any decision that differs from
// the exact sign.
struct Tally
{
  int decided = 0;
  int total = 0;
  void check(const Site& p, const Site& q, const Site& r, const Site& t)
  {
    const int filtered = filteredSign(p, q, r, t);
    ++total;
    if (filtered != 0)
    {
      ++decided;
      ASSERT_EQ(filtered, exactSign(p, q, r, t))
        << "p (" << p.x << ", " << p.y << ", " << p.w << ") q (" << q.x << ", " << q.y << ", "
        << q.w << ") r (" << r.x << ", " << r.y << ", " << r.w << ") t (" << t.x << ", " << t.y
        << ", " << t.w << ")";
    }
  }
};

TEST(PowerTestKernel, CertifiedSignsOfRandomWeightedPointsAreExact)
{
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  for (double weightScale : { 0.0, 1e-3, 1.0, 1e3 })
  {
    Tally tally;
    for (int k = 0; k < 20000; ++k)
    {
      std::array<Site, 4> s;
      for (Site& site : s)
      {
        site = { unit(rng), unit(rng), weightScale * unit(rng) };
      }
      tally.check(s[0], s[1], s[2], s[3]);
    }
    EXPECT_GT(tally.decided, 0.99 * tally.total) << "weights of scale " << weightScale;
  }
}

TEST(PowerTestKernel, LeavesExactTiesToTheExactPredicate)
{
  // Four corners of a unit square, unweighted (cocircular), and the same lifted by equal
  // weights, and a square translated far from the origin: the exact answer is a tie.
  for (double shift : { 0.0, 1e6 })
  {
    for (double w : { 0.0, 0.25 })
    {
      const Site p{ shift, shift, w }, q{ shift + 1, shift, w }, r{ shift + 1, shift + 1, w },
        t{ shift, shift + 1, w };
      EXPECT_EQ(exactSign(p, q, r, t), 0);
      EXPECT_EQ(filteredSign(p, q, r, t), 0) << "shift " << shift << ", weight " << w;
    }
  }
  // Weights that make a non-cocircular quadruple a tie: t's weight raised by its power
  // distance to the circle through p, q, r (exact in binary here).
  const Site p{ 0, 0, 0 }, q{ 2, 0, 0 }, r{ 0, 2, 0 }, t{ 3, 3, 6 };
  EXPECT_EQ(exactSign(p, q, r, t), 0);
  EXPECT_EQ(filteredSign(p, q, r, t), 0);
}

TEST(PowerTestKernel, CertifiedSignsOfNearTiesAreExact)
{
  // Points on a circle about the origin rounded to double, with weights that are zero or tiny:
  // each quadruple is a tie up to the last bits, where only exact arithmetic decides.
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> angle(0.0, 6.283185307179586);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  for (double radius : { 1.0, 1e-9 })
  {
    Tally tally;
    for (int k = 0; k < 20000; ++k)
    {
      std::array<Site, 4> s;
      for (Site& site : s)
      {
        const double a = angle(rng);
        const double w = k % 2 ? 0.0 : 1e-17 * radius * radius * unit(rng);
        site = { radius * std::cos(a), radius * std::sin(a), w };
      }
      tally.check(s[0], s[1], s[2], s[3]);
    }
    EXPECT_GT(tally.decided, 0) << "radius " << radius;
    EXPECT_LT(tally.decided, tally.total) << "radius " << radius;
  }
  // Far from the origin: eight points exactly on a circle of radius 5 / 1024 about
  // (1e6, -3e5) (from 3-4-5 triangles), one coordinate moved by a unit in the last place or
  // not at all.
  const double h = 1.0 / 1024.0, cx = 1e6, cy = -3e5;
  const std::array<std::pair<int, int>, 8> onCircle{ { { 5, 0 }, { 4, 3 }, { 0, 5 }, { -3, 4 },
    { -5, 0 }, { -4, -3 }, { 0, -5 }, { 3, -4 } } };
  std::uniform_int_distribution<int> pick(0, 7), nudge(-1, 1);
  Tally tally;
  for (int k = 0; k < 20000; ++k)
  {
    std::array<Site, 4> s;
    for (Site& site : s)
    {
      const auto [i, j] = onCircle[pick(rng)];
      site = { cx + i * h, cy + j * h, 0.0 };
    }
    if (s[0].x == s[1].x && s[0].y == s[1].y)
    {
      continue; // a repeated point
    }
    const int step = nudge(rng);
    s[3].x = step == 0 ? s[3].x : std::nextafter(s[3].x, step * INFINITY);
    tally.check(s[0], s[1], s[2], s[3]);
  }
  EXPECT_GT(tally.decided, 0);
  EXPECT_LT(tally.decided, tally.total);
}

TEST(PowerTestKernel, LeavesExtremeInputsToTheExactPredicate)
{
  // Differences where products could underflow or overflow, huge weights and NaN: undecided.
  const Site q{ 1, 0, 0 }, r{ 0, 1, 0 }, t{ 0, 0, 0 };
  EXPECT_EQ(filteredSign({ 1e-70, 2e-70, 0 }, q, r, t), 0);
  EXPECT_EQ(filteredSign({ 1e61, 0.5, 0 }, q, r, t), 0);
  EXPECT_EQ(filteredSign({ 0.5, 0.5, 1e121 }, q, r, t), 0);
  EXPECT_EQ(filteredSign({ NAN, 0.5, 0 }, q, r, t), 0);
  EXPECT_EQ(filteredSign({ 0.5, 0.5, NAN }, q, r, t), 0);
  // Within range it decides: (0.5, 0.5) is inside the circle through q, r and t.
  EXPECT_EQ(filteredSign({ 0.5, 0.5, 0 }, q, r, t), exactSign({ 0.5, 0.5, 0 }, q, r, t));
  EXPECT_NE(filteredSign({ 0.5, 0.5, 0 }, q, r, t), 0);
}

template <class Kernel>
std::vector<std::array<int, 3>> regularFaces(const std::vector<Site>& sites)
{
  using Vb = CGAL::Triangulation_vertex_base_with_info_2<int, Kernel,
    CGAL::Regular_triangulation_vertex_base_2<Kernel>>;
  using Tds =
    CGAL::Triangulation_data_structure_2<Vb, CGAL::Regular_triangulation_face_base_2<Kernel>>;
  using Regular = CGAL::Regular_triangulation_2<Kernel, Tds>;
  std::vector<std::pair<typename Regular::Weighted_point, int>> points;
  for (int i = 0; i < static_cast<int>(sites.size()); ++i)
  {
    points.emplace_back(typename Regular::Weighted_point(
                          typename Kernel::Point_2(sites[i].x, sites[i].y), sites[i].w),
      i);
  }
  Regular rt(points.begin(), points.end());
  // In storage order, each face's vertices as stored: the cells are built and integrated in
  // this order, so the same order means the same bits downstream.
  std::vector<std::array<int, 3>> faces;
  for (auto f = rt.finite_faces_begin(); f != rt.finite_faces_end(); ++f)
  {
    faces.push_back({ f->vertex(0)->info(), f->vertex(1)->info(), f->vertex(2)->info() });
  }
  return faces;
}

TEST(PowerTestKernel, RegularTriangulationsAreCGALs)
{
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::vector<Site> random, lattice;
  for (int k = 0; k < 20000; ++k)
  {
    random.push_back({ unit(rng), unit(rng), 1e-4 * unit(rng) });
  }
  // A lattice (every square's corners cocircular) with equal weights, and a few heavier points
  // that hide their neighbours.
  for (int i = 0; i < 100; ++i)
  {
    for (int j = 0; j < 100; ++j)
    {
      lattice.push_back({ 0.01 * i, 0.01 * j, (i * 100 + j) % 997 == 0 ? 1e-3 : 0.0 });
    }
  }
  for (const auto* sites : { &random, &lattice })
  {
    const auto expected = regularFaces<CGAL::Epick>(*sites);
    EXPECT_GT(expected.size(), sites->size());
    EXPECT_EQ(regularFaces<PowerTestKernel>(*sites), expected);
  }
}

} // namespace
} // namespace otparam
