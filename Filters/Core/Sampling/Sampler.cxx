#include "Sampling/Sampler.h"

#include <cmath>
#include <numeric>
#include <sstream>

namespace otparam
{

//------------------------------------------------------------------------------
std::string checkSamplerOptions(const SamplerOptions& options)
{
  std::ostringstream msg;
  const int mode = static_cast<int>(options.mode);
  const int rule = static_cast<int>(options.sizeRule);
  if (mode < 0 || mode > 2)
  {
    msg << "SamplingMode must be 0 (Adaptive), 1 (Uniform) or 2 (MeshVertices); got " << mode
        << ".";
  }
  else if (rule < 0 || rule > 1)
  {
    msg << "SizeRule must be 0 (R * sqrt(density)) or 1 (R * density); got " << rule << ".";
  }
  else if (options.numberOfSamples < 3)
  {
    msg << "NumberOfSamples must be at least 3; got " << options.numberOfSamples << ".";
  }
  else if (options.numberOfSamples > options.maximumNumberOfSamples)
  {
    msg << "NumberOfSamples = " << options.numberOfSamples
        << " is above MaximumNumberOfSamples = " << options.maximumNumberOfSamples
        << "; raise MaximumNumberOfSamples or ask for fewer.";
  }
  // Chew's refinement is guaranteed to end up to 30 degrees. Above, the fuzzer found inputs
  // where it runs for minutes (31 degrees: > 10 s, 33: 48 s, 35: > 400 s on small disks).
  else if (!(options.minimumAngleDegrees > 0.0) || !(options.minimumAngleDegrees <= 30.0))
  {
    msg << "MinimumAngle must be in (0, 30] degrees (above 30 Delaunay refinement may run for "
           "minutes or not end); got "
        << options.minimumAngleDegrees << ".";
  }
  return msg.str();
}

//------------------------------------------------------------------------------
double massCoefficientOfVariation(const std::vector<double>& mass)
{
  if (mass.empty())
  {
    return 0.0;
  }
  const double n = static_cast<double>(mass.size());
  const double mean = std::accumulate(mass.begin(), mass.end(), 0.0) / n;
  double variance = 0.0;
  for (double m : mass)
  {
    variance += (m - mean) * (m - mean);
  }
  return std::sqrt(variance / n) / mean;
}

//------------------------------------------------------------------------------
std::string sampleCountWarning(long long reached, long long target, bool capped)
{
  if (capped || std::abs(static_cast<double>(reached) / static_cast<double>(target) - 1.0) <= 0.1)
  {
    return {};
  }
  std::ostringstream text;
  text << "NumberOfSamples = " << target << " not met: reached " << reached
       << " samples for a target of " << target
       << ": the density varies too fast for so few samples at this minimum angle (the "
          "graded refinement needs that many).";
  return text.str();
}

//------------------------------------------------------------------------------
bool refineToTargetCount(const SamplerOptions& options, double gradedArea, double tolerance,
  const std::function<double(double epsilon, double runTarget)>& refine, SamplerResultBase& result)
{
  const double target = static_cast<double>(options.numberOfSamples);
  double runTarget = target >= 4000.0 ? target / 4.0 : target;
  double epsilon = std::sqrt(gradedArea / runTarget);
  for (int run = 0; run < 5; ++run)
  {
    ++result.refinementRuns;
    const double count = refine(epsilon, runTarget);
    if (count < 0.0)
    {
      result.status.aborted = true;
      return false;
    }
    result.epsilon = epsilon;
    if (result.capped)
    {
      break;
    }
    epsilon *= std::sqrt(count / target);
    if (runTarget == target && std::abs(count / target - 1.0) <= tolerance)
    {
      break;
    }
    runTarget = target;
  }
  return true;
}

} // namespace otparam
