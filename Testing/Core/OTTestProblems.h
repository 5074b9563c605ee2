// Problems with known answers, shared by the unit tests and the benchmark.
#ifndef OTPARAM_OTTESTPROBLEMS_H
#define OTPARAM_OTTESTPROBLEMS_H

#include "Common/Geometry.h"

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

namespace otparam
{
namespace testing
{
constexpr double Pi = 3.14159265358979323846;

inline std::vector<Vec2> randomInDisk(size_t n, unsigned seed, double radius = 1.0)
{
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(-radius, radius);
  std::vector<Vec2> y;
  y.reserve(n);
  while (y.size() < n)
  {
    const Vec2 p{ u(rng), u(rng) };
    if (dot(p, p) < radius * radius)
      y.push_back(p);
  }
  return y;
}

// Two Gaussian bumps over a floor: masses whose max / min is `contrast`.
inline std::vector<double> mixtureMasses(const std::vector<Vec2>& y, double contrast)
{
  const Vec2 c1{ 0.4, 0.3 }, c2{ -0.5, -0.2 };
  std::vector<double> m;
  m.reserve(y.size());
  for (const Vec2& p : y)
    m.push_back(
      std::exp(-dot(p - c1, p - c1) / 0.05) + 0.5 * std::exp(-dot(p - c2, p - c2) / 0.02));
  const double mx = *std::max_element(m.begin(), m.end());
  for (double& v : m)
    v = mx / contrast + v * (1 - 1 / contrast);
  return m;
}

// Uniform disk -> radial density rho(r) = (1 + a r^2) / (1 + a / 2). The optimal map is radial
// and monotone, x -> R(|x|) x / |x| with |x|^2 = F(R), F the target's radial CDF. The Diracs
// have equal masses and sit on a sunflower spiral in the target measure (F(|y_i|) = (i + 1/2) / n),
// so the centroid of cell i must lie at radius sqrt(F(|y_i|)).
struct RadialProblem
{
  std::vector<Vec2> diracs;
  std::vector<double> masses;
  std::vector<double> centroidRadius; // exact T^-1(y_i) radius
};

inline RadialProblem radialProblem(int n, double a = 3.0)
{
  RadialProblem p;
  const double golden = Pi * (3.0 - std::sqrt(5.0));
  for (int i = 0; i < n; ++i)
  {
    const double u = (i + 0.5) / n;
    const double r2 = (-1.0 + std::sqrt(1.0 + 2.0 * a * u * (1.0 + a / 2.0))) / a;
    const double R = std::sqrt(r2), phi = i * golden;
    p.diracs.push_back({ R * std::cos(phi), R * std::sin(phi) });
    p.masses.push_back(1.0);
    p.centroidRadius.push_back(std::sqrt(u));
  }
  return p;
}

inline double rmsRadiusError(const RadialProblem& p, const std::vector<Vec2>& centroids)
{
  double s = 0.0;
  for (size_t i = 0; i < centroids.size(); ++i)
  {
    const double e = norm(centroids[i]) - p.centroidRadius[i];
    s += e * e;
  }
  return std::sqrt(s / centroids.size());
}

} // namespace testing
} // namespace otparam

#endif
