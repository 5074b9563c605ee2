// Step 3a of the composition (DiskComposition.h): the area correction at the samples' scale,
// before the per-vertex sweeps. Private to the composition stage.
#ifndef OTPARAM_COMPOSITION_SAMPLESCALECORRECTION_H
#define OTPARAM_COMPOSITION_SAMPLESCALECORRECTION_H

#include "Composition/Composition.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <numeric>
#include <vector>

namespace otparam
{
namespace composition
{

// The interpolation leaves an error at the samples' scale (the cell centroids are not exactly
// T^-1 of the samples): on face_choi_bff_17k a third of its mean |log area ratio| survives
// averaging over the samples' stars. Per-vertex sweeps spread such an error over tens of
// sweeps, drifting along shears meanwhile. Here one sample image moves at a time, carried to
// the mesh points by the interpolant's hat function of that sample (each point of its star
// moves by its weight times the displacement): a Gauss-Newton step on the mesh's own merit
// sum_t A*_t log(A_t / A*_t)^2, kept only if it lowers sum_t A*_t (r + 1/r - 2) over the
// triangles it moves with all of them positive (as the per-vertex sweeps do). A triangle's area
// is affine in such a displacement (its corners move parallel), so the line search reads it
// off two numbers per triangle. Measured (docs/design.md): the first sweep halves
// face_choi_bff_17k's interpolated error (0.080 -> 0.038); after the per-vertex sweeps the mean
// angle distortion is lower on all 11 shared disk meshes.
class SampleScaleCorrection
{
public:
  // `corners`: one per mesh point, kept by reference (points that must not move, such as those
  // on the circle, have no samples); `movable`: per sample (the samples on the circle are not:
  // their images stay there).
  SampleScaleCorrection(const std::vector<Triangle>& triangles,
    const std::vector<SampleCorners>& corners, const std::vector<char>& movable,
    const std::vector<double>& surfaceFraction)
    : Triangles(triangles)
    , Corners(corners)
    , Movable(movable)
    , Fraction(surfaceFraction)
  {
    this->listPoints();
    this->listTriangles();
  }

  // One sweep, colour class by colour class: samples of one class share no triangle, so they
  // move in parallel with exactly the result of moving them in turn. `totalArea`: the
  // domain's, which the targets share. Returns the number of samples moved.
  // Dynamic chunks: a sample's star holds from a few to hundreds of mesh points.
  std::int64_t sweep(std::vector<Vec2>& uv, double totalArea) const
  {
    std::int64_t moved = 0;
#pragma omp parallel reduction(+ : moved)
    {
      Scratch scratch;
      for (size_t c = 0; c + 1 < this->ClassStarts.size(); ++c)
      {
        const std::int64_t first = this->ClassStarts[c], last = this->ClassStarts[c + 1];
#pragma omp for schedule(dynamic, 8)
        for (std::int64_t k = first; k < last; ++k)
        {
          moved += this->move(this->Order[k], uv, totalArea, scratch);
        }
      }
    }
    return moved;
  }

private:
  struct Scratch
  {
    std::vector<double> area, target;
    std::vector<Vec2> slope, before;
  };

  // The weight of `sample` at mesh point v (0 outside its star, or where the sample does not
  // carry v: the moves and their predicted areas read the same weights).
  double weight(int v, int sample) const
  {
    const SampleCorners& c = this->Corners[v];
    for (int k = 0; k < 3; ++k)
    {
      if (c.sample[k] == sample && this->carries(v, k))
      {
        return c.weight[k];
      }
    }
    return 0.0;
  }

  bool carries(int v, int k) const
  {
    const SampleCorners& c = this->Corners[v];
    return c.sample[k] >= 0 && this->Movable[c.sample[k]] && c.weight[k] > 0.0;
  }

  // The movable samples that move some corner of t (at most nine), written to `out`; returns
  // their count.
  int samplesMoving(const Triangle& t, int* out) const
  {
    int count = 0;
    for (int v : t)
    {
      for (int k = 0; k < 3; ++k)
      {
        const int s = this->Corners[v].sample[k];
        if (this->carries(v, k) && std::find(out, out + count, s) == out + count)
        {
          out[count++] = s;
        }
      }
    }
    return count;
  }

  // Each sample's points (compressed rows).
  void listPoints()
  {
    const size_t samples = this->Movable.size();
    this->PointOffsets.assign(samples + 1, 0);
    for (size_t v = 0; v < this->Corners.size(); ++v)
    {
      for (int k = 0; k < 3; ++k)
      {
        this->PointOffsets[this->Corners[v].sample[k] + 1] += this->carries(v, k);
      }
    }
    std::partial_sum(
      this->PointOffsets.begin(), this->PointOffsets.end(), this->PointOffsets.begin());
    this->Points.resize(this->PointOffsets.back());
    std::vector<int> fill(this->PointOffsets.begin(), this->PointOffsets.end() - 1);
    for (size_t v = 0; v < this->Corners.size(); ++v)
    {
      for (int k = 0; k < 3; ++k)
      {
        if (this->carries(v, k))
        {
          this->Points[fill[this->Corners[v].sample[k]]++].point = static_cast<int>(v);
        }
      }
    }
  }

  // Each triangle's moving samples (the triangles independent, so in parallel), then each
  // sample's triangles, those with a corner among its points, their weights, and the samples'
  // colours.
  void listTriangles()
  {
    const auto triangles = static_cast<std::int64_t>(this->Triangles.size());
    std::vector<std::array<int, 9>> movers(triangles);
    std::vector<int> count(triangles);
#pragma omp parallel for schedule(static)
    for (std::int64_t t = 0; t < triangles; ++t)
    {
      count[t] = this->samplesMoving(this->Triangles[t], movers[t].data());
    }
    const size_t samples = this->Movable.size();
    this->TriangleOffsets.assign(samples + 1, 0);
    for (std::int64_t t = 0; t < triangles; ++t)
    {
      for (int k = 0; k < count[t]; ++k)
      {
        ++this->TriangleOffsets[movers[t][k] + 1];
      }
    }
    std::partial_sum(
      this->TriangleOffsets.begin(), this->TriangleOffsets.end(), this->TriangleOffsets.begin());
    this->TrianglesOf.resize(this->TriangleOffsets.back());
    std::vector<int> fill(this->TriangleOffsets.begin(), this->TriangleOffsets.end() - 1);
    for (std::int64_t t = 0; t < triangles; ++t)
    {
      for (int k = 0; k < count[t]; ++k)
      {
        this->TrianglesOf[fill[movers[t][k]]++].triangle = static_cast<int>(t);
      }
    }
    this->weighEntries();
    this->colourSamples(movers, count);
  }

  // The weights of each sample's triangle corners and points (in float: they only steer the
  // moves, which measure the areas in double), each sample's in turn (in parallel).
  void weighEntries()
  {
    const auto samples = static_cast<std::int64_t>(this->Movable.size());
#pragma omp parallel for schedule(static)
    for (std::int64_t s = 0; s < samples; ++s)
    {
      for (int e = this->TriangleOffsets[s]; e < this->TriangleOffsets[s + 1]; ++e)
      {
        const Triangle& t = this->Triangles[this->TrianglesOf[e].triangle];
        for (int k = 0; k < 3; ++k)
        {
          this->TrianglesOf[e].weight[k] =
            static_cast<float>(this->weight(t[k], static_cast<int>(s)));
        }
      }
      for (int e = this->PointOffsets[s]; e < this->PointOffsets[s + 1]; ++e)
      {
        this->Points[e].weight =
          static_cast<float>(this->weight(this->Points[e].point, static_cast<int>(s)));
      }
    }
  }

  // Greedy colouring of the samples that move something: two that move a common triangle get
  // different colours. Order lists them colour by colour.
  void colourSamples(const std::vector<std::array<int, 9>>& movers, const std::vector<int>& count)
  {
    const int samples = static_cast<int>(this->Movable.size());
    std::vector<int> colour(samples, -1), classSizes;
    std::vector<char> taken;
    for (int s = 0; s < samples; ++s)
    {
      if (this->TriangleOffsets[s] == this->TriangleOffsets[s + 1])
      {
        continue;
      }
      taken.assign(classSizes.size(), 0);
      for (int e = this->TriangleOffsets[s]; e < this->TriangleOffsets[s + 1]; ++e)
      {
        const int t = this->TrianglesOf[e].triangle;
        for (int m = 0; m < count[t]; ++m)
        {
          const int c = colour[movers[t][m]];
          if (c >= 0)
          {
            taken[c] = 1;
          }
        }
      }
      const int c = static_cast<int>(std::find(taken.begin(), taken.end(), 0) - taken.begin());
      colour[s] = c;
      classSizes.resize(std::max(classSizes.size(), static_cast<size_t>(c) + 1), 0);
      ++classSizes[c];
    }
    this->ClassStarts.assign(classSizes.size() + 1, 0);
    std::partial_sum(classSizes.begin(), classSizes.end(), this->ClassStarts.begin() + 1);
    std::vector<int> next(this->ClassStarts.begin(), this->ClassStarts.end() - 1);
    this->Order.resize(this->ClassStarts.back());
    for (int s = 0; s < samples; ++s)
    {
      if (colour[s] >= 0)
      {
        this->Order[next[colour[s]]++] = s;
      }
    }
  }

  bool move(int s, std::vector<Vec2>& uv, double totalArea, Scratch& scratch) const
  {
    const int first = this->TriangleOffsets[s], count = this->TriangleOffsets[s + 1] - first;
    scratch.area.resize(count);
    scratch.slope.resize(count);
    scratch.target.resize(count);
    double gx = 0.0, gy = 0.0, hxx = 0.0, hxy = 0.0, hyy = 0.0, energy = 0.0;
    for (int k = 0; k < count; ++k)
    {
      const CornerWeights& entry = this->TrianglesOf[first + k];
      const int ti = entry.triangle;
      const Triangle& t = this->Triangles[ti];
      const Vec2 a = uv[t[0]], b = uv[t[1]], c = uv[t[2]];
      const double area = 0.5 * cross(b - a, c - a);
      if (!(area > 0.0))
      {
        return false; // only an untangled neighbourhood is corrected
      }
      // d(area) / d(displacement): each corner's area gradient times its weight.
      const Vec2 slope = 0.5 *
        (double(entry.weight[0]) * Vec2{ b.y - c.y, c.x - b.x } +
          double(entry.weight[1]) * Vec2{ c.y - a.y, a.x - c.x } +
          double(entry.weight[2]) * Vec2{ a.y - b.y, b.x - a.x });
      const double target = this->Fraction[ti] * totalArea;
      const double ax = slope.x / area, ay = slope.y / area;
      const double residual = logAreaRatio(area, target);
      gx += target * residual * ax;
      gy += target * residual * ay;
      hxx += target * ax * ax;
      hxy += target * ax * ay;
      hyy += target * ay * ay;
      energy += areaMerit(area, target);
      scratch.area[k] = area;
      scratch.slope[k] = slope;
      scratch.target[k] = target;
    }
    const double det = hxx * hyy - hxy * hxy;
    if (!(det > 1e-12 * (hxx * hyy)) || !(hxx > 0.0))
    {
      return false;
    }
    const Vec2 step = { -(hyy * gx - hxy * gy) / det, -(-hxy * gx + hxx * gy) / det };
    for (double lambda = 1.0; lambda > 1e-3; lambda *= 0.5)
    {
      double merit = 0.0;
      bool positive = true;
      for (int k = 0; k < count && positive; ++k)
      {
        const double area = scratch.area[k] + lambda * dot(scratch.slope[k], step);
        positive = area > 0.0;
        merit += areaMerit(area, scratch.target[k]);
      }
      if (positive && merit < energy)
      {
        return this->moveKeepingTrianglesPositive(s, lambda * step, uv, scratch);
      }
    }
    return false;
  }

  // Moves sample s's points by their weights times `displacement`. The line search predicted
  // every area positive; a triangle it predicted to shrink by half or more is measured again
  // after the move, and if rounding left one not positive, the move is taken back.
  bool moveKeepingTrianglesPositive(
    int s, Vec2 displacement, std::vector<Vec2>& uv, Scratch& scratch) const
  {
    scratch.before.clear();
    for (int e = this->PointOffsets[s]; e < this->PointOffsets[s + 1]; ++e)
    {
      const int v = this->Points[e].point;
      scratch.before.push_back(uv[v]);
      uv[v] = uv[v] + static_cast<double>(this->Points[e].weight) * displacement;
    }
    const int first = this->TriangleOffsets[s], count = this->TriangleOffsets[s + 1] - first;
    for (int k = 0; k < count; ++k)
    {
      if (scratch.area[k] + dot(scratch.slope[k], displacement) >= 0.5 * scratch.area[k])
      {
        continue;
      }
      const Triangle& t = this->Triangles[this->TrianglesOf[first + k].triangle];
      if (!(signedArea(uv[t[0]], uv[t[1]], uv[t[2]]) > 0.0))
      {
        for (int e = this->PointOffsets[s]; e < this->PointOffsets[s + 1]; ++e)
        {
          uv[this->Points[e].point] = scratch.before[e - this->PointOffsets[s]];
        }
        return false;
      }
    }
    return true;
  }

  const std::vector<Triangle>& Triangles;
  const std::vector<SampleCorners>& Corners;
  const std::vector<char> Movable;
  const std::vector<double>& Fraction;
  // A sample's triangle with its corners' weights, and a sample's point with its weight.
  struct CornerWeights
  {
    int triangle = -1;
    std::array<float, 3> weight = { 0.0f, 0.0f, 0.0f };
  };
  struct PointWeight
  {
    int point = -1;
    float weight = 0.0f;
  };
  std::vector<int> PointOffsets, TriangleOffsets, ClassStarts, Order;
  std::vector<PointWeight> Points;
  std::vector<CornerWeights> TrianglesOf;
};

} // namespace composition
} // namespace otparam

#endif
