// The density field's largest value over a triangle (Sampling/PlanarDensityField.h): the same
// as a scan of every point (per-point densities) or triangle centroid (per-triangle ones)
// inside it, whether the triangles around it answer (small triangles) or the box tree does.
#include "Sampling/PlanarDensityField.h"
#include "Sampling/PlanarSampler.h"

#include "RingDisk.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

namespace otparam
{
namespace
{
// The field's own test: barycentric coordinates in the counter-clockwise abc all >= 0.
bool inside(Vec2 x, Vec2 a, Vec2 b, Vec2 c)
{
  const double area = cross(b - a, c - a);
  const double la = cross(b - x, c - x) / area, lb = cross(c - x, a - x) / area;
  return la >= 0.0 && lb >= 0.0 && 1.0 - la - lb >= 0.0;
}

struct Case
{
  std::vector<Vec2> points;
  std::vector<Triangle> triangles;
  std::vector<double> perPoint, perTriangle;
};

// The ring disk, even or crowded towards its centre, with random densities per point or per
// triangle.
Case ringCase(bool crowded, bool perPoint)
{
  const testing::PlanarMesh disk = testing::makePlanarDisk(30, crowded ? 10.0 : 0.0);
  Case c;
  c.points = disk.points;
  c.triangles = disk.triangles;
  std::mt19937 random(11);
  // Largest in [0.5, 1): the field keeps such values as they are (relativeDensity scales by
  // even powers of two only beyond).
  std::uniform_real_distribution<double> value(0.1, 0.95);
  std::vector<double>& values = perPoint ? c.perPoint : c.perTriangle;
  values.resize(perPoint ? c.points.size() : c.triangles.size());
  for (double& v : values)
  {
    v = value(random);
  }
  return c;
}

// The largest value at the points or centroids inside abc, at abc's centre, and atLeast.
double scanMaximum(
  const DensityField& field, const Case& c, Vec2 a, Vec2 b, Vec2 cc, double atLeast)
{
  if (cross(b - a, cc - a) < 0.0)
  {
    std::swap(b, cc);
  }
  double largest = std::max(atLeast, field.value((1.0 / 3.0) * (a + b + cc)));
  if (!c.perPoint.empty())
  {
    for (size_t i = 0; i < c.points.size(); ++i)
    {
      if (inside(c.points[i], a, b, cc))
      {
        largest = std::max(largest, c.perPoint[i]);
      }
    }
    return largest;
  }
  for (size_t t = 0; t < c.triangles.size(); ++t)
  {
    const Triangle& tri = c.triangles[t];
    const Vec2 centroid = (1.0 / 3.0) * (c.points[tri[0]] + c.points[tri[1]] + c.points[tri[2]]);
    if (inside(centroid, a, b, cc))
    {
      largest = std::max(largest, c.perTriangle[t]);
    }
  }
  return largest;
}

// `walking`: the field readied for a sampling as large as its triangles, whose queries walk
// (and whose maxima over small triangles come from the triangles around them); else the box
// tree answers all.
void checkMaxima(bool crowded, bool perPoint, bool walking)
{
  const Case c = ringCase(crowded, perPoint);
  std::string error;
  const auto field = DensityField::create(c.points, c.triangles, c.perPoint, c.perTriangle, error);
  ASSERT_TRUE(field) << error;
  field->prepareForQueries(walking ? static_cast<long long>(c.triangles.size()) : 0);
  std::mt19937 random(5);
  std::uniform_real_distribution<double> unit(-1.0, 1.0), angle(0.0, 6.283185307179586);
  int queries = 0;
  // Triangles from a thousandth to the disk's size (crowded: also around the crowded centre),
  // some reaching over the circle; atLeast 0 or a corner's value.
  for (double size : { 1e-3, 1e-2, 0.05, 0.2, 1.0 })
  {
    for (int k = 0; k < 300; ++k)
    {
      const double scale = crowded && k % 2 ? 1e-3 : 1.0;
      const Vec2 centre = { scale * unit(random), scale * unit(random) };
      std::array<Vec2, 3> corner;
      for (Vec2& p : corner)
      {
        const double a = angle(random);
        p = centre +
          (scale * size * (0.3 + 0.7 * std::abs(unit(random)))) * Vec2{ std::cos(a), std::sin(a) };
      }
      const double atLeast = k % 3 == 0 ? field->value(corner[0]) : 0.0;
      EXPECT_EQ(field->maxInsideTriangle(corner[0], corner[1], corner[2], atLeast),
        scanMaximum(*field, c, corner[0], corner[1], corner[2], atLeast))
        << "size " << size << ", query " << k;
      ++queries;
    }
  }
  EXPECT_EQ(queries, 1500);
}

TEST(DensityField, LargestValueOverATrianglePerPoint)
{
  checkMaxima(false, true, true);
  checkMaxima(false, true, false);
}

TEST(DensityField, LargestValueOverATrianglePerTriangle)
{
  checkMaxima(false, false, true);
  checkMaxima(false, false, false);
}

TEST(DensityField, LargestValueOverATriangleCrowded)
{
  checkMaxima(true, true, true);
  checkMaxima(true, false, true);
}

// The same samples, to the bit, whether the field's queries walk or not (a sampling smaller
// than the triangles does not ready the walk by itself).
TEST(DensityField, WalkingQueriesGiveTheSameSamples)
{
  const Case c = ringCase(true, true);
  SamplerOptions options;
  options.numberOfSamples = 2000;
  ASSERT_LT(options.numberOfSamples, static_cast<long long>(c.triangles.size()));
  std::vector<std::vector<Vec2>> samples;
  for (long long prepared : { 0LL, static_cast<long long>(c.triangles.size()) })
  {
    std::string error;
    const auto field =
      DensityField::create(c.points, c.triangles, c.perPoint, c.perTriangle, error);
    ASSERT_TRUE(field) << error;
    field->prepareForQueries(prepared);
    const SamplerResult result = sampleDensity(*field, options);
    ASSERT_TRUE(result.status.ok()) << result.status.error;
    samples.push_back(result.samples);
  }
  ASSERT_EQ(samples[0].size(), samples[1].size());
  for (size_t i = 0; i < samples[0].size(); ++i)
  {
    ASSERT_EQ(samples[0][i].x, samples[1][i].x) << i;
    ASSERT_EQ(samples[0][i].y, samples[1][i].y) << i;
  }
}

} // namespace
} // namespace otparam
