"""Transport of the uniform unit disk onto targets with complicated supports (method.md): the
sampler samples only the support, the solver converges, and its port 4 ("Discontinuities")
holds the singularity set of the map, checked against the known answers:
- two half-disks facing away from each other, gap 0.2: by symmetry each takes one half of the
  source disk, so the singularity set is the vertical diameter (length 2, x = 0);
- a uniform annulus 0.4 < r < 1: the map is radial, r -> sqrt(0.16 + 0.84 r^2), continuous
  except at the centre, so the singularity set shrinks to a point and the cell centroids
  follow the radial map;
- a thick letter C: a non-convex support, one curve of jumps from the centre towards the
  opening. The target shapes are generated here (Examples/otparam_example_utils.py)."""

import math
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "Examples"))

from complicated_supports import transport_onto  # noqa: E402
from otparam_example_utils import annulus, letter_c, two_half_disks  # noqa: E402
from otparam_test_utils import check, finish  # noqa: E402


def run(shape, samples):
    sampler, solver = transport_onto(shape, samples)
    return sampler.GetOutput(), solver


def jumps(solver):
    """The discontinuity segments: ((a, b), jump length, Dirac ids)."""
    out = solver.GetOutput(4)
    lengths = out.GetCellData().GetArray("JumpLength")
    ids = out.GetCellData().GetArray("DiracIds")
    segments = []
    for c in range(out.GetNumberOfCells()):
        cell = out.GetCell(c)
        a, b = out.GetPoint(cell.GetPointId(0)), out.GetPoint(cell.GetPointId(1))
        segments.append(((a, b), lengths.GetValue(c), ids.GetTuple2(c)))
    return segments


def common_checks(name, samples, solver, in_support):
    diracs = solver.GetOutput(0)
    fd = diracs.GetFieldData()
    check(fd.GetArray("Converged").GetValue(0) == 1
          and fd.GetArray("RelativeError").GetValue(0) <= 1e-10,
          f"{name}: converged to 1e-10 ({fd.GetArray('RelativeError').GetValue(0):.2e})")
    mass = diracs.GetPointData().GetArray("Mass")
    cell_mass = diracs.GetPointData().GetArray("CellMass")
    n = diracs.GetNumberOfPoints()
    check(abs(math.fsum(mass.GetValue(i) for i in range(n)) - math.pi) <= 1e-12 * math.pi
          and abs(math.fsum(cell_mass.GetValue(i) for i in range(n)) - math.pi) <= 1e-9,
          f"{name}: masses and cell masses sum to pi")
    check(all(in_support(*samples.GetPoint(i)[:2]) for i in range(samples.GetNumberOfPoints())),
          f"{name}: every sample in the support")
    out = solver.GetOutput(4)
    check(out.GetCellData().GetArray("JumpLength") is not None and out.GetNumberOfCells() > 0,
          f"{name}: a singularity set with JumpLength")
    for (a, b), length, (i, j) in jumps(solver):
        yi, yj = diracs.GetPoint(int(i)), diracs.GetPoint(int(j))
        if not check(abs(length - math.dist(yi[:2], yj[:2])) <= 1e-12,
                     f"{name}: JumpLength is |y_i - y_j|"):
            break
        if not check(math.hypot(*a[:2]) <= 1 + 1e-9 and math.hypot(*b[:2]) <= 1 + 1e-9,
                     f"{name}: the singularity set lies in the source disk"):
            break


# The shapes' curved sides are polygons: samples on an edge lie inside the circle by at most
# the edge's sagitta (r (1 - cos(pi / sectors)) <= 2e-4 here).
SAGITTA = 1e-3

# Two half-disks: the diameter x = 0, closer with more samples.
GAP, RADIUS = 0.2, 0.8


def in_halves(x, y, eps=1e-9):
    return (abs(x) >= GAP / 2 - eps and math.hypot(abs(x) - GAP / 2, y) <= RADIUS + eps)


previous_offset = None
# At 500 samples the jumps zigzag around the diameter: their length exceeds 2 by 0.023-0.031
# depending on the sampler's relaxation; the distance to x = 0 is the sharper figure.
for samples, length_tolerance, tolerance in [(500, 0.04, 0.03), (4000, 0.006, 0.006)]:
    name = f"two half-disks, {samples} samples"
    target, solver = run(two_half_disks(GAP, RADIUS), samples)
    common_checks(name, target, solver, in_halves)
    segments = jumps(solver)
    length = math.fsum(math.dist(a[:2], b[:2]) for (a, b), _, _ in segments)
    offset = max(max(abs(a[0]), abs(b[0])) for (a, b), _, _ in segments)
    print(f"{name}: jump length {length:.4f}, largest |x| {offset:.4f}", flush=True)
    check(abs(length - 2.0) <= length_tolerance,
          f"{name}: total length {length:.4f} = 2 +- {length_tolerance}")
    check(offset <= tolerance, f"{name}: every point within {tolerance} of x = 0 ({offset:.4f})")
    check(all(length_ >= GAP for _, length_, _ in segments),
          f"{name}: every jump crosses the gap (>= {GAP})")
    if previous_offset is not None:
        check(offset < previous_offset, f"{name}: closer to the diameter than with fewer samples")
    previous_offset = offset

# Annulus: a point-like singularity at the centre; centroids on the radial map.
R_IN, R_OUT = 0.4, 1.0
for samples in (1000, 4000):
    name = f"annulus, {samples} samples"
    target, solver = run(annulus(R_IN, R_OUT, rings=8, sectors=96), samples)
    common_checks(name, target, solver, lambda x, y: R_IN - SAGITTA <= math.hypot(x, y) <= R_OUT + 1e-9)
    reach = max(max(math.hypot(*a[:2]), math.hypot(*b[:2])) for (a, b), _, _ in jumps(solver))
    check(reach <= 0.05, f"{name}: the singularity set stays within 0.05 of the centre ({reach:.4f})")
    diracs = solver.GetOutput(0)
    centroid = diracs.GetPointData().GetArray("Centroid")
    worst = 0.0
    for i in range(diracs.GetNumberOfPoints()):
        cx, cy, _ = centroid.GetTuple3(i)
        r = math.hypot(cx, cy)
        if r < 0.1:
            continue  # cells at the centre straddle the singularity
        s = math.sqrt(R_IN ** 2 + (R_OUT ** 2 - R_IN ** 2) * r * r)
        y = diracs.GetPoint(i)
        worst = max(worst, math.dist((s * cx / r, s * cy / r), y[:2]))
    bound = 4.0 / math.sqrt(samples)  # a few cell diameters
    check(worst <= bound, f"{name}: centroids on the radial map within {bound:.3f} ({worst:.4f})")

# Letter C: converges, and its jumps form one curve from the centre to the opening (x > 0).
name = "letter C, 3000 samples"
target, solver = run(letter_c(), 3000)
common_checks(name, target, solver,
              lambda x, y: 0.45 - SAGITTA <= math.hypot(x, y) <= 0.9 + 1e-9
              and abs(math.atan2(y, x)) >= math.pi / 4 - 1e-9)
segments = jumps(solver)
check(all(min(a[0], b[0]) >= -0.1 for (a, b), _, _ in segments),
      f"{name}: the jumps lie towards the opening (x >= -0.1)")

# The support is the input's triangles: without triangles it is unknown and port 4 is empty;
# a malformed triangle (a point id out of range) is left out rather than read.
import otparam  # noqa: E402
from vtkmodules.vtkCommonDataModel import vtkPolyData  # noqa: E402

samples, _ = run(annulus(R_IN, R_OUT), 500)
points_only = vtkPolyData()
points_only.SetPoints(samples.GetPoints())
points_only.GetPointData().AddArray(samples.GetPointData().GetArray("Mass"))
malformed = vtkPolyData()
malformed.DeepCopy(samples)
malformed.GetPolys().InsertNextCell(3, (0, 1, samples.GetNumberOfPoints() + 5))
expected = None
for name, data in [("points only", points_only), ("with triangles", samples),
                   ("a malformed triangle", malformed)]:
    solver = otparam.vtkSemiDiscreteOTSolver()
    solver.SetInputData(data)
    solver.Update()
    count = solver.GetOutput(4).GetNumberOfCells()
    check(solver.GetOutput(0).GetFieldData().GetArray("Converged").GetValue(0) == 1,
          f"annulus, {name}: converged")
    if name == "points only":
        check(count == 0, f"annulus, {name}: no support, no singularity set ({count})")
    elif expected is None:
        expected = count
        check(count > 0, f"annulus, {name}: a singularity set")
    else:
        check(count == expected, f"annulus, {name}: the same singularity set ({count} vs {expected})")

finish()
