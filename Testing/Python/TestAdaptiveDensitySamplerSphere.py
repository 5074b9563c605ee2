"""vtkAdaptiveDensitySampler with the unit sphere as its domain (sphere.md step 2): the chain
ConformalSphereMap -> AdaptiveDensitySampler -> SphericalOTSolver on the shared spot cow. The
samples lie on the unit sphere with the triangles of their spherical Delaunay triangulation
(convex hull, counter-clockwise seen from outside), Mass sums to 4 pi, the adaptive masses
spread by at most 0.15 (std / mean), far less than uniform samples', and the spherical solver
converges to 1e-10 from them; the per-point density (averaged over triangles) and MeshVertices
work too; the field data agrees with the output. Bad input on the sphere domain: one clear
error each, the output empty, the input untouched."""

import math

import numpy as np
from otparam import vtkAdaptiveDensitySampler, vtkConformalSphereMap, vtkSphericalOTSolver
from otparam_test_utils import (MessageRecorder, check, check_abort, check_failed_run,
                                field_value, finish, read_mesh, same, shared_mesh, snapshot)
from vtkmodules.util.numpy_support import numpy_to_vtk, vtk_to_numpy
from vtkmodules.vtkCommonCore import vtkCommand, vtkDoubleArray, vtkPoints
from vtkmodules.vtkCommonDataModel import vtkCellArray, vtkDataObject, vtkPolyData
from vtkmodules.vtkFiltersSources import vtkSphereSource

CELLS = vtkDataObject.FIELD_ASSOCIATION_CELLS
POINTS = vtkDataObject.FIELD_ASSOCIATION_POINTS
TARGET = 3000

conformal = vtkConformalSphereMap()
conformal.SetInputData(read_mesh(shared_mesh("spot_closed_3k.obj")))
conformal.Update()
sphere = conformal.GetOutput()
check(sphere.GetNumberOfPoints() == 2930, "spot maps onto the sphere")
before = snapshot(sphere)


def sample(data, mode=0, count=TARGET, association=CELLS, name="AreaDensity"):
    sampler = vtkAdaptiveDensitySampler()
    sampler.SetInputData(data)
    sampler.SetInputArrayToProcess(0, 0, 0, association, name)
    sampler.SetSamplingMode(mode)
    sampler.SetNumberOfSamples(count)
    errors = MessageRecorder(sampler)
    sampler.Update()
    check(not errors.messages, f"mode {mode}: no error ({errors.text()})")
    return sampler.GetOutput()


def spherical_triangle_areas(a, b, c):
    num = np.abs(np.einsum("ij,ij->i", a, np.cross(b, c)))
    den = 1 + np.einsum("ij,ij->i", a, b) + np.einsum("ij,ij->i", b, c) \
        + np.einsum("ij,ij->i", c, a)
    return 2 * np.arctan2(num, den)


def check_samples(label, out, mesh_vertices=False):
    points = vtk_to_numpy(out.GetPoints().GetData())
    triangles = vtk_to_numpy(out.GetPolys().GetConnectivityArray()).reshape(-1, 3)
    mass = vtk_to_numpy(out.GetPointData().GetArray("Mass"))
    n = len(points)
    check(abs(math.fsum(mass) - 4 * math.pi) <= 1e-12,
          f"{label}: Mass sums to 4 pi ({math.fsum(mass)!r})")
    check(np.all(mass > 0), f"{label}: every mass positive")
    radius = np.abs(np.linalg.norm(points, axis=1) - 1).max()
    check(radius <= 1e-12, f"{label}: samples on the unit sphere ({radius:.1e})")
    a, b, c = (points[triangles[:, k]] for k in range(3))
    check(np.all(np.einsum("ij,ij->i", a, np.cross(b, c)) > 0),
          f"{label}: triangles counter-clockwise seen from outside")
    area = math.fsum(spherical_triangle_areas(a, b, c))
    check(abs(area - 4 * math.pi) <= 1e-9, f"{label}: the triangles cover the sphere once ({area})")
    if not mesh_vertices:
        check(len(triangles) == 2 * n - 4, f"{label}: 2n - 4 triangles (the convex hull)")
    cv = field_value(out, "MassCoefficientOfVariation")
    check(abs(cv - mass.std() / mass.mean()) < 1e-12, f"{label}: MassCoefficientOfVariation")
    check(field_value(out, "NumberOfSamples") == n, f"{label}: NumberOfSamples = point count")
    check(abs(field_value(out, "SourceMass") - 4 * math.pi) < 1e-15, f"{label}: SourceMass 4 pi")
    check(field_value(out, "MassSumRelativeError") <= 1e-9,
          f"{label}: the cells' integrals sum to the density's integral "
          f"({field_value(out, 'MassSumRelativeError'):.1e})")
    for name in ("MinimumAngle", "Epsilon", "RefinementRuns", "Capped", "DensityIntegral",
                 "SecondsRefinement", "SecondsMasses", "SecondsTotal"):
        check(field_value(out, name) is not None, f"{label}: field data {name}")
    return n, cv


def solve(samples):
    solver = vtkSphericalOTSolver()
    solver.SetInputData(samples)
    solver.Update()
    out = solver.GetOutput(0)
    return (int(field_value(out, "Iterations")), field_value(out, "RelativeError"),
            int(field_value(out, "Converged")))


# ---- The chain, with the exact per-triangle density.
print(f"{'mode':22s} {'samples':>7s} {'mass CV':>8s} {'angle':>6s} {'OT its':>6s} "
      f"{'rel. error':>10s} converged")
results = {}
for mode, label, association in ((0, "Adaptive", CELLS), (0, "Adaptive (point array)", POINTS),
                                 (1, "Uniform", CELLS), (2, "MeshVertices", CELLS)):
    out = sample(sphere, mode, TARGET, association)
    n, cv = check_samples(label, out, mode == 2)
    its, error, converged = solve(out)
    results[label] = (n, cv, converged, error)
    print(f"{label:22s} {n:7d} {cv:8.3f} {field_value(out, 'MinimumAngle'):6.1f} {its:6d} "
          f"{error:10.2e} {converged}", flush=True)
    if mode != 2:
        check(abs(n / TARGET - 1) <= 0.1, f"{label}: {n} samples within 10% of {TARGET}")
    else:
        check(n == sphere.GetNumberOfPoints(), "MeshVertices: the mesh's own points")

adaptive = results["Adaptive"]
check(adaptive[2] == 1 and adaptive[3] <= 1e-10,
      f"the spherical solver converges to 1e-10 from the adaptive samples ({adaptive[3]:.1e})")
check(adaptive[1] <= 0.15, f"adaptive masses' spread {adaptive[1]:.3f} <= 0.15 on spot")
check(results["Uniform"][1] >= 5 * adaptive[1],
      "uniform samples' masses spread at least 5x more (spot's density spans 1e3)")
check(same(snapshot(sphere), before), "the sampler leaves its input untouched")

# ---- Bad input on the sphere domain.
T = vtk_to_numpy(sphere.GetPolys().GetConnectivityArray()).reshape(-1, 3).copy()
X = vtk_to_numpy(sphere.GetPoints().GetData()).copy()
G = vtk_to_numpy(sphere.GetCellData().GetArray("AreaDensity")).copy()


def sphere_mesh(points=X, triangles=T, density=G):
    data = vtkPolyData()
    data.SetPoints(vtkPoints())
    data.GetPoints().SetData(numpy_to_vtk(np.ascontiguousarray(points, float), deep=True))
    cells = vtkCellArray()
    for t in triangles:
        cells.InsertNextCell(3, [int(v) for v in t])
    data.SetPolys(cells)
    array = vtkDoubleArray()
    array.SetName("AreaDensity")
    for g in density:
        array.InsertNextValue(g)
    data.GetCellData().AddArray(array)
    return data


moved = X.copy()
moved[17] *= 1.0 + 1e-7
off = X.copy()
off[17] *= 1.5
zero = G.copy()
zero[40] = 0.0
nan = G.copy()
nan[41] = float("nan")
source = vtkSphereSource()  # float points: on the unit sphere only to 1e-7
source.SetRadius(1.0)
source.SetThetaResolution(16)
source.SetPhiResolution(12)
source.Update()
float_sphere = vtkPolyData()
float_sphere.DeepCopy(source.GetOutput())
float_sphere.GetPointData().Initialize()
ones = vtkDoubleArray()
ones.SetName("AreaDensity")
for _ in range(float_sphere.GetNumberOfCells()):
    ones.InsertNextValue(1.0)
float_sphere.GetCellData().AddArray(ones)

CASES = [
    ("open mesh on the sphere", sphere_mesh(triangles=T[1:], density=G[1:]), {},
     ["not closed"]),
    ("point 1e-7 off the sphere", sphere_mesh(points=moved), {}, ["point 17", "unit sphere"]),
    ("float points (1e-7 off the sphere)", float_sphere, {}, ["unit sphere"]),
    ("point far off the sphere", sphere_mesh(points=off), {}, ["not planar", "sphere domain",
                                                               "point 17"]),
    ("triangles clockwise", sphere_mesh(triangles=T[:, ::-1]), {}, ["clockwise"]),
    ("density 0 on a triangle", sphere_mesh(density=zero), {}, ["triangle 40", "positive"]),
    ("density NaN", sphere_mesh(density=nan), {}, ["nan", "41"]),
    ("density missing", sphere_mesh(), {"array": (POINTS, "Density")}, ["missing", "density"]),
    ("NumberOfSamples 2", sphere_mesh(), {"NumberOfSamples": 2}, ["numberofsamples"]),
]
for name, data, settings, words in CASES:
    snap = snapshot(data)
    sampler = vtkAdaptiveDensitySampler()
    sampler.SetInputData(data)
    association, array = settings.pop("array", (CELLS, "AreaDensity"))
    sampler.SetInputArrayToProcess(0, 0, 0, association, array)
    for prop, value in settings.items():
        getattr(sampler, "Set" + prop)(value)
    errors = MessageRecorder(sampler)
    warnings = MessageRecorder(sampler, vtkCommand.WarningEvent)
    pipeline_errors = MessageRecorder(sampler.GetExecutive())
    sampler.Update()
    check_failed_run(name, errors, pipeline_errors, words)
    check(not warnings.messages, f"{name}: no warning besides the error ({warnings.text()})")
    output = sampler.GetOutput()
    check(output.GetNumberOfPoints() == 0 and output.GetNumberOfCells() == 0
          and output.GetPointData().GetNumberOfArrays() == 0
          and output.GetFieldData().GetNumberOfArrays() == 0, f"{name}: output is empty")
    check(same(snapshot(data), snap), f"{name}: the input is not modified")

# The unmodified mesh samples (the cases above isolate one problem each).
check_samples("rebuilt sphere mesh", sample(sphere_mesh(), 0, 500))

# A planar domain whose points all lie on the unit circle (on the unit sphere too) stays planar:
# the unit disk, masses summing to pi, samples in z = 0.
hexagon = [(math.cos(k * math.pi / 3), math.sin(k * math.pi / 3), 0.0) for k in range(6)]
flat = sphere_mesh(points=np.array(hexagon), triangles=[(0, 1, 2), (0, 2, 3), (0, 3, 4), (0, 4, 5)],
                   density=[1.0] * 4)
flat_out = sample(flat, 0, 200)
flat_points = vtk_to_numpy(flat_out.GetPoints().GetData())
check(abs(field_value(flat_out, "SourceMass") - math.pi) < 1e-15
      and np.all(flat_points[:, 2] == 0.0) and flat_out.GetNumberOfPoints() > 100,
      "a hexagon inscribed in the unit circle is sampled as the planar unit disk")

# Progress and abort on the sphere.
aborting = vtkAdaptiveDensitySampler()
aborting.SetInputData(sphere)
aborting.SetNumberOfSamples(20000)
progress = []
aborting.AddObserver(vtkCommand.ProgressEvent, lambda obj, _e: progress.append(obj.GetProgress()))
check_abort(aborting, after=0.1)
check(len(progress) >= 2, f"progress reported on the sphere ({len(progress)} events)")
finish()
