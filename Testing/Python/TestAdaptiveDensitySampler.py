"""vtkAdaptiveDensitySampler in the paper's pipeline: ConformalDiskMap -> AdaptiveDensitySampler
-> SemiDiscreteOTSolver on the shared brain, with the per-triangle AreaDensity; its field data
agrees with its output; the Uniform and MeshVertices baselines; a point-array density; the
sample count follows NumberOfSamples; progress and abort."""

import math

import numpy as np
from otparam import vtkAdaptiveDensitySampler, vtkConformalDiskMap, vtkSemiDiscreteOTSolver
from otparam_test_utils import (MessageRecorder, check_abort, check, field_value, finish, read_mesh, same,
                                shared_mesh, snapshot)
from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.vtkCommonCore import vtkCommand
from vtkmodules.vtkCommonDataModel import vtkDataObject

CELLS = vtkDataObject.FIELD_ASSOCIATION_CELLS
POINTS = vtkDataObject.FIELD_ASSOCIATION_POINTS

conformal = vtkConformalDiskMap()
conformal.SetInputData(read_mesh(shared_mesh("brain_cortex_cut_48k.off")))
conformal.Update()
disk = conformal.GetOutput()
before = snapshot(disk) if disk.GetNumberOfPoints() < 3000 else None


def sample(mode, count, association=CELLS, name="AreaDensity"):
    sampler = vtkAdaptiveDensitySampler()
    sampler.SetInputData(disk)
    sampler.SetInputArrayToProcess(0, 0, 0, association, name)
    sampler.SetSamplingMode(mode)
    sampler.SetNumberOfSamples(count)
    errors = MessageRecorder(sampler)
    sampler.Update()
    out = sampler.GetOutput()
    check(not errors.messages, f"mode {mode}: no error ({errors.text()})")
    return sampler, out


def solve(samples):
    solver = vtkSemiDiscreteOTSolver()
    solver.SetInputData(0, samples)
    solver.SetMaximumNumberOfIterations(100)
    MessageRecorder(solver, vtkCommand.WarningEvent)  # Uniform may not converge: quietly
    solver.Update()
    out = solver.GetOutput(0)
    return int(field_value(out, "Iterations")), field_value(out, "RelativeError"), \
        int(field_value(out, "Converged"))


def masses_and_triangles(out):
    mass = vtk_to_numpy(out.GetPointData().GetArray("Mass"))
    triangles = vtk_to_numpy(out.GetPolys().GetConnectivityArray()).reshape(-1, 3)
    return mass, triangles


print(f"{'mode':14s} {'samples':>7s} {'mass CV':>8s} {'angle':>6s} {'OT its':>6s} "
      f"{'rel. error':>10s} converged")
results = {}
for mode, label in ((0, "Adaptive"), (1, "Uniform"), (2, "MeshVertices")):
    sampler, out = sample(mode, 5000)
    mass, triangles = masses_and_triangles(out)
    n = out.GetNumberOfPoints()
    cv = field_value(out, "MassCoefficientOfVariation")
    its, error, converged = solve(out)
    results[label] = (n, cv, converged, error, field_value(out, "Relaxed"))
    print(f"{label:14s} {n:7d} {cv:8.3f} {field_value(out, 'MinimumAngle'):6.1f} {its:6d} "
          f"{error:10.2e} {converged}", flush=True)
    check(abs(mass.sum() - math.pi) < 1e-12, f"{label}: masses sum to pi ({mass.sum()!r})")
    check(np.all(mass > 0), f"{label}: every mass positive")
    check(abs(cv - mass.std() / mass.mean()) < 1e-12, f"{label}: MassCoefficientOfVariation = std/mean")
    check(field_value(out, "NumberOfSamples") == n, f"{label}: NumberOfSamples = point count")
    points = vtk_to_numpy(out.GetPoints().GetData())
    check(np.all(points[:, 2] == 0.0) and np.all(np.hypot(points[:, 0], points[:, 1]) <= 1 + 1e-15),
          f"{label}: samples in the unit disk, z = 0")
    a, b, c = (points[triangles[:, k], :2] for k in range(3))

    def angle(p, q, r):
        u, w = q - p, r - p
        return np.degrees(np.arctan2(np.abs(u[:, 0] * w[:, 1] - u[:, 1] * w[:, 0]), (u * w).sum(1)))
    smallest = min(angle(a, b, c).min(), angle(b, c, a).min(), angle(c, a, b).min())
    check(abs(smallest - field_value(out, "MinimumAngle")) < 1e-9, f"{label}: MinimumAngle = smallest angle")
    if label != "MeshVertices":
        check(abs(n / 5000 - 1) <= 0.1, f"{label}: {n} samples within 10% of 5000")

check(results["Adaptive"][2] == 1 and results["Adaptive"][3] <= 1e-10,
      "the OT solver converges from the adaptive samples")
check(results["Uniform"][1] >= 5 * results["Adaptive"][1],
      "uniform samples' masses spread at least 5x more (the brain's density spans 1e5)")
check(results["Adaptive"][1] <= 0.4, "adaptive masses' spread <= 0.4 on the brain")
# At 5000 samples the brain's conformal density varies faster than the samples follow: the
# relaxation would spread the masses more, so Adaptive mode keeps the unrelaxed samples;
# Uniform mode (a sampling of the area) always relaxes.
check(results["Adaptive"][4] == 0 and results["Uniform"][4] == 1,
      f"Relaxed: Adaptive {results['Adaptive'][4]}, Uniform {results['Uniform'][4]}")
check(before is None or same(snapshot(disk), before), "the sampler leaves its input untouched")
check(disk.GetPoints().GetNumberOfPoints() == conformal.GetOutput().GetNumberOfPoints(),
      "the sampler leaves its input's points in place")

# The point array (piecewise-linear density) works too.
_, out = sample(0, 1000, POINTS)
check(out.GetNumberOfPoints() > 0 and abs(vtk_to_numpy(out.GetPointData().GetArray("Mass")).sum() - math.pi) < 1e-12,
      "point AreaDensity: masses sum to pi")

# Progress and abort.
sampler = vtkAdaptiveDensitySampler()
sampler.SetInputData(disk)
sampler.SetInputArrayToProcess(0, 0, 0, CELLS, "AreaDensity")
sampler.SetNumberOfSamples(20000)
progress = []
sampler.AddObserver(vtkCommand.ProgressEvent, lambda obj, _e: progress.append(obj.GetProgress()))
sampler.Update()
check(len(progress) >= 3 and progress[-1] == 1.0, f"progress reported ({len(progress)} events)")


aborting = vtkAdaptiveDensitySampler()
aborting.SetInputData(disk)
aborting.SetInputArrayToProcess(0, 0, 0, CELLS, "AreaDensity")
aborting.SetNumberOfSamples(20000)
check_abort(aborting)

finish()
