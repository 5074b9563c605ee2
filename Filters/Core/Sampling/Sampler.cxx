#include "Sampling/Sampler.h"

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
  else if (!(options.minimumAngleDegrees > 0.0) || !(options.minimumAngleDegrees <= 35.0))
  {
    msg << "MinimumAngle must be in (0, 35] degrees (Delaunay refinement does not terminate "
           "for larger bounds); got "
        << options.minimumAngleDegrees << ".";
  }
  return msg.str();
}

} // namespace otparam
