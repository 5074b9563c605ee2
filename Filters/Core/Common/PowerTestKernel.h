// CGAL's Epick kernel with a statically filtered 2D power test, for the regular triangulations
// of the transport, the sampler and the composition.
//
// Written by hand because CGAL has none: Epick filters Side_of_oriented_circle_2 and the 3D
// power test with a floating-point error bound, but Power_side_of_oriented_power_circle_2 goes
// straight to interval arithmetic (a change of the FPU's rounding mode per call) and, when the
// intervals cannot decide, to exact numbers. That made a regular triangulation of 1e6 points
// take 1.6-2.0 s where a Delaunay triangulation of them takes 0.9-1.1 s. Here the determinant is
// evaluated in double with a bound on its rounding error; only where the bound cannot certify
// its sign does CGAL's own filtered predicate decide. A certified sign is the exact sign, so the
// triangulations, and everything computed from them, are the same to the last bit.
#ifndef OTPARAM_COMMON_POWERTESTKERNEL_H
#define OTPARAM_COMMON_POWERTESTKERNEL_H

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_structural_filtering_traits.h>

#include <cmath>

namespace otparam
{

// The sign of the power test of four weighted points in double, certified: +1 or -1, or 0 when
// the error bound does not decide (then the caller asks an exact predicate). The test is
// CGAL's power_side_of_oriented_power_circleC2: the sign of the determinant of the rows
// (dx, dy, dx^2 + dy^2 - w + w_t) of p, q, r relative to t.
//
// The bound (first order in the unit roundoff u = 2^-53): each dx, dy carries a relative error
// u; each third entry an absolute error at most 7 u M, M = dx^2 + dy^2 + |w| + |w_t| (two
// squares and three sums of terms at most M); each 2 x 2 minor an error at most 4 u of its
// terms' absolute sum A; so the three products M-entry x minor are off by at most 12 u M A
// each, and the two sums add 2 u of the permanent sum(M A). The bound used, 3e-15 of the
// permanent (27 u), leaves a margin for the second-order terms and the permanent's own
// rounding. That analysis holds while no intermediate product underflows or overflows: it
// decides only where every difference is 0 or within [1e-60, 1e60] and every weight within
// 1e120 (then only a final product can underflow, by 2^-1075 at most, far below the bound);
// elsewhere, and for anything not finite, it does not decide.
inline int certifiedPowerTestSign(double px, double py, double pw, double qx, double qy, double qw,
  double rx, double ry, double rw, double tx, double ty, double tw)
{
  const double dpx = px - tx, dpy = py - ty, dqx = qx - tx, dqy = qy - ty, drx = rx - tx,
               dry = ry - ty;
  const auto inRange = [](double d) { return d == 0.0 || (1e-60 <= d && d <= 1e60); };
  const auto weightInRange = [](double w) { return std::fabs(w) <= 1e120; };
  if (!inRange(std::fabs(dpx)) || !inRange(std::fabs(dpy)) || !inRange(std::fabs(dqx)) ||
    !inRange(std::fabs(dqy)) || !inRange(std::fabs(drx)) || !inRange(std::fabs(dry)) ||
    !weightInRange(pw) || !weightInRange(qw) || !weightInRange(rw) || !weightInRange(tw))
  {
    return 0; // also NaN, which fails every comparison
  }
  const double dpz = dpx * dpx + dpy * dpy - pw + tw;
  const double dqz = dqx * dqx + dqy * dqy - qw + tw;
  const double drz = drx * drx + dry * dry - rw + tw;
  const double absTw = std::fabs(tw);
  const double mp = dpx * dpx + dpy * dpy + std::fabs(pw) + absTw;
  const double mq = dqx * dqx + dqy * dqy + std::fabs(qw) + absTw;
  const double mr = drx * drx + dry * dry + std::fabs(rw) + absTw;
  const double minorP = dqx * dry - dqy * drx;
  const double minorQ = dpx * dry - dpy * drx;
  const double minorR = dpx * dqy - dpy * dqx;
  const double det = dpz * minorP - dqz * minorQ + drz * minorR;
  const double permanent = mp * (std::fabs(dqx * dry) + std::fabs(dqy * drx)) +
    mq * (std::fabs(dpx * dry) + std::fabs(dpy * drx)) +
    mr * (std::fabs(dpx * dqy) + std::fabs(dpy * dqx));
  constexpr double RelativeBound = 3e-15;
  const double bound = RelativeBound * permanent;
  return det > bound ? 1 : (det < -bound ? -1 : 0);
}

// Epick whose 2D power test of four points is filtered first by certifiedPowerTestSign. The
// three- and two-point forms (collinear configurations) stay CGAL's.
struct PowerTestKernel : public CGAL::Epick
{
  class Power_side_of_oriented_power_circle_2
  {
  public:
    using Weighted_point_2 = CGAL::Epick::Weighted_point_2;
    using result_type = CGAL::Oriented_side;

    CGAL::Oriented_side operator()(const Weighted_point_2& p, const Weighted_point_2& q,
      const Weighted_point_2& r, const Weighted_point_2& t) const
    {
      const int sign = certifiedPowerTestSign(p.x(), p.y(), p.weight(), q.x(), q.y(), q.weight(),
        r.x(), r.y(), r.weight(), t.x(), t.y(), t.weight());
      if (sign != 0)
      {
        return sign > 0 ? CGAL::ON_POSITIVE_SIDE : CGAL::ON_NEGATIVE_SIDE;
      }
      return this->Exact(p, q, r, t);
    }
    CGAL::Oriented_side operator()(
      const Weighted_point_2& p, const Weighted_point_2& q, const Weighted_point_2& t) const
    {
      return this->Exact(p, q, t);
    }
    CGAL::Oriented_side operator()(const Weighted_point_2& p, const Weighted_point_2& t) const
    {
      return this->Exact(p, t);
    }

  private:
    CGAL::Epick::Power_side_of_oriented_power_circle_2 Exact;
  };

  Power_side_of_oriented_power_circle_2 power_side_of_oriented_power_circle_2_object() const
  {
    return Power_side_of_oriented_power_circle_2();
  }
};

} // namespace otparam

// CGAL's triangulations locate a point with an inexact walk first ("structural filtering") only
// for kernels that declare it, as Epick does. Without this, the same triangles came out stored
// in another order, and the cells' integrals differed in their last bits (hand_stein_810 0.0114
// -> 0.0110): with it, every triangulation is Epick's to the bit.
namespace CGAL
{
template <>
struct Triangulation_structural_filtering_traits<otparam::PowerTestKernel>
{
  typedef Tag_true Use_structural_filtering_tag;
};
} // namespace CGAL

#endif
