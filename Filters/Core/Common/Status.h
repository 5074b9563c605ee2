// How a stage of the core ends: the one error convention of the stage functions that the
// adapters, the pipeline and the command line call.
#ifndef OTPARAM_COMMON_STATUS_H
#define OTPARAM_COMMON_STATUS_H

#include <cmath>
#include <iomanip>
#include <sstream>
#include <string>
#include <vector>

namespace otparam
{

struct Status
{
  // Empty when the stage succeeded; else a sentence about the user's data or parameters that
  // names the problem and where (ids, property names), ready to be shown as it is.
  std::string error;
  // What a user should know about a successful run (points left out, a cap that was hit).
  std::vector<std::string> warnings;
  // The progress callback asked to stop; the stage's results are incomplete.
  bool aborted = false;

  bool ok() const { return this->error.empty() && !this->aborted; }
};

// The value checks of options, worded as the filters' messages ("Tolerance must be positive
// and finite; got 0."): "" when the value is fine.
inline std::string checkPositiveFinite(const char* name, double value)
{
  if (value > 0.0 && std::isfinite(value))
  {
    return {};
  }
  std::ostringstream msg;
  msg << name << " must be positive and finite; got " << value << ".";
  return msg.str();
}

inline std::string checkAtLeast(const char* name, long long value, long long minimum)
{
  if (value >= minimum)
  {
    return {};
  }
  std::ostringstream msg;
  msg << name << " must be at least " << minimum << "; got " << value << ".";
  return msg.str();
}

// A fraction as a percentage for messages: "0.053%", "1.8%", "100%" (two significant digits,
// never in exponent form).
inline std::string percentOf(double fraction)
{
  std::ostringstream text;
  const double percent = 100.0 * fraction;
  if (percent >= 10.0)
  {
    text << std::fixed << std::setprecision(0) << percent << "%";
  }
  else
  {
    text << std::setprecision(2) << percent << "%";
  }
  return text.str();
}

} // namespace otparam

#endif
