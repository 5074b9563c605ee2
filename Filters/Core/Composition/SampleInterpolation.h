// Step 1 of the composition (DiskComposition.h): the sample images interpolated at every mesh
// point over the samples' regular triangulation under the transport's weights (Delaunay without
// them). Private to the composition stage.
#ifndef OTPARAM_COMPOSITION_SAMPLEINTERPOLATION_H
#define OTPARAM_COMPOSITION_SAMPLEINTERPOLATION_H

#include "Common/PowerTestKernel.h"
#include "Composition/Composition.h"
#include "Composition/Untangling.h"

#include <CGAL/Regular_triangulation_2.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>

#include <complex>

namespace otparam
{
namespace composition
{

using K = PowerTestKernel;
using Point = K::Weighted_point_2;
using Vb = CGAL::Triangulation_vertex_base_with_info_2<int, K,
  CGAL::Regular_triangulation_vertex_base_2<K>>; // info: sample index
using Fb = CGAL::Regular_triangulation_face_base_2<K>;
using Tds = CGAL::Triangulation_data_structure_2<Vb, Fb>;
using RT = CGAL::Regular_triangulation_2<K, Tds>;

// Step 1: piecewise-linear interpolation of the sample images at every mesh point.
//
// Over the samples' regular triangulation under the transport's weights w_i = |y_i|^2 - 2 h_i,
// the dual of its power diagram: three samples make a triangle where their cells meet at a
// power vertex, and the centroids of those cells (their images) lie around that vertex in the
// same order. The Delaunay triangulation (all weights equal: a staged transport's stages, or no
// heights given) also pairs samples whose cells do not touch where the weights vary, i.e. where
// the density is crowded: hand_choi_53k's interpolation flipped 688 mesh triangles over it and
// 416 over the regular one (mean |log area ratio| interpolated 0.30 -> 0.20, corrected 0.0159
// -> 0.0132; docs/design.md).
class SampleInterpolant
{
public:
  // `weights`: one per sample, or empty for the Delaunay triangulation.
  SampleInterpolant(const std::vector<Vec2>& samples, const std::vector<Vec2>& images,
    const std::vector<double>& weights = {})
    : Images(images)
  {
    std::vector<std::pair<Point, int>> points;
    points.reserve(samples.size());
    for (size_t i = 0; i < samples.size(); ++i)
    {
      points.emplace_back(
        Point(K::Point_2(samples[i].x, samples[i].y), weights.empty() ? 0.0 : weights[i]),
        static_cast<int>(i));
      if (onCircle(samples[i]))
      {
        // T maps the circle onto the circle: a boundary sample's preimage is on it too.
        this->Images[i] = normalized(images[i]);
      }
    }
    this->Triangulation.insert(points.begin(), points.end());
    if (this->Triangulation.number_of_hidden_vertices() > 0)
    {
      // A hidden sample (its cell empty: a transport stopped before converging) would have no
      // place in the interpolant: the Delaunay triangulation instead.
      this->Triangulation.clear();
      for (auto& point : points)
      {
        point.first = Point(point.first.point(), 0.0);
      }
      this->Triangulation.insert(points.begin(), points.end());
    }
    this->PinnedSimilarity = this->similarityAtPinnedSample();
  }

  // The triangles of the samples' triangulation whose images are flipped (the cell centroids
  // are not always in the order of the samples around them: hand_choi_53k, 270 of 9492) each
  // carry the flip into every mesh triangle inside them: untangled here, on the samples, where
  // it is cheap and one fix serves all those mesh triangles. The hull samples (on the circle)
  // stay on it. Returns {flipped sample triangles before, after}; nothing is done (and {n, n}
  // returned) when a hull sample is off the circle.
  std::pair<std::int64_t, std::int64_t> untangleImages()
  {
    SurfaceMesh mesh;
    mesh.points.resize(this->Images.size());
    for (auto v = this->Triangulation.finite_vertices_begin();
         v != this->Triangulation.finite_vertices_end(); ++v)
    {
      mesh.points[v->info()] = { v->point().x(), v->point().y(), 0.0 };
    }
    for (auto f = this->Triangulation.finite_faces_begin();
         f != this->Triangulation.finite_faces_end(); ++f)
    {
      mesh.triangles.push_back(
        { f->vertex(0)->info(), f->vertex(1)->info(), f->vertex(2)->info() });
    }
    const auto before =
      static_cast<std::int64_t>(flippedTriangles(mesh.triangles, this->Images).size());
    // Hull edges, counter-clockwise: an infinite face (inf, a, b) has the hull edge b -> a.
    std::vector<std::pair<int, int>> hullEdges;
    auto face = this->Triangulation.incident_faces(this->Triangulation.infinite_vertex()),
         done = face;
    do
    {
      const int k = face->index(this->Triangulation.infinite_vertex());
      hullEdges.emplace_back(face->vertex(RT::cw(k))->info(), face->vertex(RT::ccw(k))->info());
    } while (++face != done);
    std::vector<int> hull, next(this->Images.size(), -1);
    for (const auto& [a, b] : hullEdges)
    {
      next[a] = b;
    }
    for (int v = hullEdges.empty() ? -1 : hullEdges.front().first;
         v >= 0 && hull.size() < hullEdges.size(); v = next[v])
    {
      if (!onCircle(this->Images[v]))
      {
        return { before, before };
      }
      hull.push_back(v);
    }
    if (before == 0 || hull.size() != hullEdges.size())
    {
      return { before, before };
    }
    const VertexStars stars(mesh.points.size(), mesh.triangles);
    Untangler(mesh, hull, stars).run(this->Images);
    return { before,
      static_cast<std::int64_t>(flippedTriangles(mesh.triangles, this->Images).size()) };
  }

  // Returns the image of p; `outsideHull` tells whether p lay outside the samples' hull.
  // `corners`, when given, receives the samples of p's triangle and their weights (left
  // untouched outside the hull).
  Vec2 operator()(Vec2 p, bool& outsideHull, SampleCorners* corners = nullptr)
  {
    RT::Locate_type type;
    int li = 0;
    const Point q(K::Point_2(p.x, p.y), 0.0);
    RT::Face_handle face = this->Triangulation.locate(q, type, li, this->Hint);
    outsideHull = false;
    if (type == RT::VERTEX)
    {
      this->Hint = face;
      if (corners)
      {
        corners->sample = { face->vertex(li)->info(), -1, -1 };
        corners->weight = { 1.0, 0.0, 0.0 };
      }
      return this->Images[face->vertex(li)->info()];
    }
    if (this->Triangulation.is_infinite(face) && type == RT::EDGE)
    {
      face = face->neighbor(li); // on a hull edge: use the finite side
    }
    if (!this->Triangulation.is_infinite(face))
    {
      this->Hint = face;
      const Vec2 a = this->position(face, 0), b = this->position(face, 1),
                 c = this->position(face, 2);
      const double area = cross(b - a, c - a);
      double w[3] = { cross(b - p, c - p) / area, cross(c - p, a - p) / area,
        cross(a - p, b - p) / area };
      // The weights sum to 1 through the last corner's, or through that of a corner pinned at
      // the origin (a staged transport's protrusion tip, SamplerOptions::sampleAtOrigin): the
      // other two, cross products with p, then keep their relative precision at points
      // 1e-100 from it, which 1 minus two weights near 1 and 0 would round away.
      const int k = this->pinnedAtOrigin(face, 0) ? 0 : (this->pinnedAtOrigin(face, 1) ? 1 : 2);
      w[k] = 1.0 - w[(k + 1) % 3] - w[(k + 2) % 3];
      if (corners)
      {
        for (int j = 0; j < 3; ++j)
        {
          corners->sample[j] = face->vertex(j)->info();
          corners->weight[j] = w[j];
        }
      }
      const Vec2 linear =
        w[0] * this->image(face, 0) + w[1] * this->image(face, 1) + w[2] * this->image(face, 2);
      if (!this->pinnedAtOrigin(face, k))
      {
        return linear;
      }
      // Around the pinned sample the map goes over from the fan's piecewise-linear map (on the
      // far edges) to one similarity (at the origin): the protrusion's rings, all inside the
      // fan, keep their shape. Linear over the fan, each stage would bend them by its fan's
      // sectors and the bends would compound, stage after stage, into folds (TestCrowding's
      // finger at L / rho = 100 folded at stage 4).
      const Vec2 similar = { this->PinnedSimilarity.real() * p.x -
          this->PinnedSimilarity.imag() * p.y,
        this->PinnedSimilarity.imag() * p.x + this->PinnedSimilarity.real() * p.y };
      return (1.0 - w[k]) * linear + w[k] * similar;
    }
    outsideHull = true;
    const int infiniteIndex = face->index(this->Triangulation.infinite_vertex());
    const int ia = RT::ccw(infiniteIndex), ib = RT::cw(infiniteIndex);
    this->Hint = face->neighbor(infiniteIndex);
    return this->beyondHullEdge(p, this->position(face, ia), this->position(face, ib),
      this->image(face, ia), this->image(face, ib));
  }

private:
  Vec2 position(RT::Face_handle f, int k) const
  {
    const Point& q = f->vertex(k)->point();
    return { q.x(), q.y() };
  }
  Vec2 image(RT::Face_handle f, int k) const { return this->Images[f->vertex(k)->info()]; }
  // The conformal part of the fan's linear maps around the sample pinned at the origin (with
  // its image), each weighted by its angle there; 0 without such a sample.
  std::complex<double> similarityAtPinnedSample() const
  {
    std::complex<double> sum = 0.0;
    double angles = 0.0;
    for (auto f = this->Triangulation.finite_faces_begin();
         f != this->Triangulation.finite_faces_end(); ++f)
    {
      for (int k = 0; k < 3; ++k)
      {
        if (!this->pinnedAtOrigin(f, k))
        {
          continue;
        }
        const Vec2 a = this->position(f, RT::ccw(k)), b = this->position(f, RT::cw(k));
        const Vec2 ia = this->image(f, RT::ccw(k)), ib = this->image(f, RT::cw(k));
        // B with B a = ia, B b = ib: B = [ia ib] [a b]^-1.
        const double det = cross(a, b);
        const double b00 = (ia.x * b.y - ib.x * a.y) / det, b01 = (ib.x * a.x - ia.x * b.x) / det;
        const double b10 = (ia.y * b.y - ib.y * a.y) / det, b11 = (ib.y * a.x - ia.y * b.x) / det;
        const double angle = std::atan2(det, dot(a, b));
        sum += angle * std::complex<double>(0.5 * (b00 + b11), 0.5 * (b10 - b01));
        angles += angle;
      }
    }
    return angles > 0.0 ? sum / angles : 0.0;
  }

  bool pinnedAtOrigin(RT::Face_handle f, int k) const
  {
    return composition::pinnedAtOrigin(this->position(f, k), this->image(f, k));
  }

  // p lies beyond the hull edge ab. When a and b are on the circle, p is in the circular
  // segment they cut off: it goes along the chord like the interpolant (so the map stays
  // continuous) and radially from the image chord to the circle in the same proportion (so
  // points on the circle stay on it). Otherwise the nearest point of the edge is used.
  static Vec2 beyondHullEdge(Vec2 p, Vec2 a, Vec2 b, Vec2 imageA, Vec2 imageB)
  {
    const Vec2 ab = b - a;
    if (onCircle(a) && onCircle(b) && std::abs(cross(ab, p)) > 0.0)
    {
      const double scale = cross(ab, a) / cross(ab, p); // p * scale is on the chord
      const Vec2 onChord = scale * p;
      const double along = std::clamp(dot(onChord - a, ab) / dot(ab, ab), 0.0, 1.0);
      const Vec2 imageOnChord = (1.0 - along) * imageA + along * imageB;
      const double chordRadius = norm(onChord), imageChordRadius = norm(imageOnChord);
      const double blend = chordRadius < 1.0
        ? std::clamp((norm(p) - chordRadius) / (1.0 - chordRadius), 0.0, 1.0)
        : 1.0;
      const double radius = imageChordRadius + blend * (1.0 - imageChordRadius);
      return radius * normalized(imageOnChord);
    }
    const double along = std::clamp(dot(p - a, ab) / std::max(dot(ab, ab), 1e-300), 0.0, 1.0);
    return (1.0 - along) * imageA + along * imageB;
  }

  RT Triangulation;
  std::vector<Vec2> Images;
  std::complex<double> PinnedSimilarity = 0.0;
  RT::Face_handle Hint;
};

} // namespace composition
} // namespace otparam

#endif
