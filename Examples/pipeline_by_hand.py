#!/usr/bin/python3
"""The method as a VTK pipeline built by hand, then the same in one filter: a plain python3
script (no ParaView) for users who want the stages' outputs.

    pipeline_by_hand.py [SURFACE]     (default: the main job's built-in hand-like surface)

vtkConformalDiskMap -> vtkAdaptiveDensitySampler (on the exact per-triangle AreaDensity) ->
vtkSemiDiscreteOTSolver, connected with SetInputConnection like any VTK pipeline; then
vtkAreaPreservingParam, which runs the same three internally and composes them. Prints what
each stage reached and checks that the composite agrees with the hand-built stages.
"""

import sys

from area_preserving_demo import make_hand_like_surface
from otparam import (vtkAdaptiveDensitySampler, vtkAreaPreservingParam, vtkConformalDiskMap,
                     vtkSemiDiscreteOTSolver)
from otparam_example_utils import read_surface
from vtkmodules.vtkCommonDataModel import vtkDataObject


def field(data, name):
    return data.GetFieldData().GetArray(name).GetValue(0)


surface = read_surface(sys.argv[1]) if len(sys.argv) > 1 else make_hand_like_surface()

# By hand: three filters, one pipeline.
conformal = vtkConformalDiskMap()
conformal.SetInputData(surface)
sampler = vtkAdaptiveDensitySampler()
sampler.SetInputConnection(conformal.GetOutputPort())
sampler.SetInputArrayToProcess(0, 0, 0, vtkDataObject.FIELD_ASSOCIATION_CELLS, "AreaDensity")
sampler.SetNumberOfSamples(5000)
transport = vtkSemiDiscreteOTSolver()
transport.SetInputConnection(sampler.GetOutputPort())
transport.Update()  # pulls the whole pipeline

disk = conformal.GetOutput()
samples = sampler.GetOutput()
diracs = transport.GetOutput(0)
print(f"conformal map: mean angle error {field(disk, 'MeanAngleDistortion'):.3f} deg, "
      f"mean |log area ratio| {field(disk, 'MeanAbsLogAreaRatio'):.3f}")
print(f"sampler: {samples.GetNumberOfPoints()} samples, mass CV "
      f"{field(samples, 'MassCoefficientOfVariation'):.3f}")
print(f"transport: converged {field(diracs, 'Converged'):.0f} in "
      f"{field(diracs, 'Iterations'):.0f} Newton iterations, relative error "
      f"{field(diracs, 'RelativeError'):.1e}")

# In one filter: the same stages plus the composition.
param = vtkAreaPreservingParam()
param.SetInputData(surface)
param.SetNumberOfSamples(5000)
param.Update()
out = param.GetOutput()
print(f"vtkAreaPreservingParam: mean |log area ratio| {field(out, 'MeanAbsLogAreaRatio'):.4f} "
      f"(conformal {field(out, 'ConformalMeanAbsLogAreaRatio'):.3f}), flipped triangles "
      f"{field(out, 'FlippedTriangles'):.0f}, {field(out, 'SecondsTotal'):.2f} s")

agree = (abs(field(out, "ConformalMeanAbsLogAreaRatio") - field(disk, "MeanAbsLogAreaRatio"))
         < 1e-12 and field(out, "NumberOfSamples") == samples.GetNumberOfPoints()
         and field(out, "Converged") == field(diracs, "Converged") == 1
         and field(out, "FlippedTriangles") == 0)
print("the composite ran the same stages" if agree else "the composite DISAGREES")
sys.exit(0 if agree else 1)
