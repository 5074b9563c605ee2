// Samples of a density on a planar domain whose masses are as equal as possible: the paper's
// self-adaptive sampling (Algorithm 2: Delaunay refinement graded by the density), and the
// conventional baselines (uniform samples, the mesh's own vertices).
#ifndef OTPARAM_SAMPLING_PLANARSAMPLER_H
#define OTPARAM_SAMPLING_PLANARSAMPLER_H

#include "Sampling/PlanarDensityField.h"
#include "Sampling/Sampler.h"

#include <functional>

namespace otparam
{

SamplerResult sampleDensity(const DensityField& density, const SamplerOptions& options);

} // namespace otparam

#endif
