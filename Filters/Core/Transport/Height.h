// The heights of semi-discrete transport (the dual variables), shared by every power diagram.
#ifndef OTPARAM_TRANSPORT_HEIGHT_H
#define OTPARAM_TRANSPORT_HEIGHT_H

namespace otparam
{

// Quad precision where the compiler has it as a type of its own (GCC and Clang on x86-64:
// software, ~113 bits); elsewhere the widest floating type (long double: quad on AArch64,
// 64 bits of mantissa on x86).
#if defined(__SIZEOF_FLOAT128__)
using Quad = __float128;
#else
using Quad = long double;
#endif

// Heights carry more precision than the coordinates. A cell edge between Diracs at distance
// delta moves by (error of h_i - h_j) / delta, and a small cell's mass by its perimeter times
// that. Doubles would pin the tiny cells of Diracs 1e-4 apart to ~1e-9 relative error; long
// doubles still fell short: at 1e5 Diracs of contrast 1e6, a cell of mass 5.2e-10 by the circle
// needed a Newton correction of 4.4e-21 to its height 1.17, below the long double spacing there
// (1.1e-19), and the solve stopped at 1.9e-10. So a height is an unevaluated sum of two long
// doubles (~128 bits), updated with error-free sums; what the diagram reads are differences of
// neighbours' heights, which keep their full precision when rounded to long double.
class Height
{
public:
  Height() = default;
  Height(long double value)
    : High(value)
  {
  }
  long double value() const { return High + Low; }

  friend Height operator+(const Height& h, long double step)
  {
    // Knuth's two-sum, then a renormalization (Dekker's fast two-sum).
    const long double sum = h.High + step;
    const long double stepPart = sum - h.High;
    const long double error = (h.High - (sum - stepPart)) + (step - stepPart);
    const long double low = h.Low + error;
    Height out;
    out.High = sum + low;
    out.Low = low - (out.High - sum);
    return out;
  }
  friend Height operator-(const Height& h, long double step) { return h + (-step); }
  Height& operator+=(long double step) { return *this = *this + step; }
  Height& operator-=(long double step) { return *this = *this + (-step); }
  friend long double operator-(const Height& a, const Height& b)
  {
    return (a.High - b.High) + (a.Low - b.Low);
  }
  // a - b in Quad: for the few computations whose conditioning a long double difference does
  // not survive.
  Quad preciseDifference(const Height& b) const
  {
    return (Quad(High) - Quad(b.High)) + (Quad(Low) - Quad(b.Low));
  }
  friend bool operator<(const Height& a, const Height& b) { return a - b < 0.0L; }
  friend bool operator>(const Height& a, const Height& b) { return b < a; }

private:
  long double High = 0.0L, Low = 0.0L;
};

} // namespace otparam

#endif
