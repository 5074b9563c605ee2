"""vtkSphericalOTSolver through the Python package: Fibonacci and random Diracs on the unit
sphere with masses of contrast 1e2, every output port checked against the transport's
definition (cell areas by Girard's theorem, the polytope Q(h) and the hull of y_i / h_i), field
data, progress and abort, and non-convergence."""

import math

import otparam
from otparam import vtkSphericalOTSolver
from otparam_test_utils import (MessageRecorder, check, fibonacci_sphere_points, field_value,
                                finish, make_sphere_diracs, random_sphere_points, same, snapshot)
from vtkmodules.vtkCommonCore import vtkCommand, vtkIdList

FOUR_PI = 4.0 * math.pi


def dot(a, b):
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]


def cross(a, b):
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


def sub(a, b):
    return (a[0] - b[0], a[1] - b[1], a[2] - b[2])


def spherical_polygon_area(polygon):
    """Signed area of a convex spherical polygon (fan of Eriksson triangles)."""
    area = 0.0
    a = polygon[0]
    for b, c in zip(polygon[1:-1], polygon[2:]):
        triple = dot(a, cross(sub(b, a), sub(c, a)))
        area += 2.0 * math.atan2(triple, 1.0 + dot(a, b) + dot(b, c) + dot(c, a))
    return area


def cells(data):
    """Point ids of every polygon."""
    ids = vtkIdList()
    result = []
    polys = data.GetPolys()
    for c in range(polys.GetNumberOfCells()):
        polys.GetCellAtId(c, ids)
        result.append([ids.GetId(k) for k in range(ids.GetNumberOfIds())])
    return result


# ---- The package: exports the class, documents its ports and arrays for help().
check("vtkSphericalOTSolver" in otparam.__all__, "otparam.__all__ lists the spherical solver")
doc = vtkSphericalOTSolver.__doc__ or ""
for word in ("Power Diagram", "Polytope", "Convex Hull", "CellMass", "Centroid", "Height",
             "LargestTransportDegrees", "DiracId", "hemisphere", "Tolerance"):
    check(word in doc, f"class documentation mentions {word}")


def run_case(label, points, masses):
    """Solves, checks every output, returns the solver."""
    n = len(points)
    diracs = make_sphere_diracs(points, masses)
    before = snapshot(diracs)
    solver = vtkSphericalOTSolver()
    errors = MessageRecorder(solver)
    warnings = MessageRecorder(solver, vtkCommand.WarningEvent)
    progress = []
    solver.AddObserver(vtkCommand.ProgressEvent,
                       lambda caller, event: progress.append(caller.GetProgress()))
    solver.SetInputData(0, diracs)
    solver.Update()
    check(not errors.messages and not warnings.messages,
          f"{label}: no error or warning ({errors.text()}{warnings.text()})")
    check(same(snapshot(diracs), before), f"{label}: the input is not modified")

    out = solver.GetOutput(0)
    fd = out.GetFieldData()
    iterations = int(field_value(out, "Iterations"))
    relative_error = field_value(out, "RelativeError")
    print(f"{label}: {n} Diracs, {iterations} iterations, relative error {relative_error:.3e}, "
          f"largest transport {field_value(out, 'LargestTransportDegrees'):.1f} degrees, "
          f"{field_value(out, 'SecondsTotal'):.3f} s", flush=True)
    check(field_value(out, "Converged") == 1, f"{label}: Converged == 1")
    check(relative_error <= 1e-10, f"{label}: RelativeError {relative_error} <= 1e-10")
    check(fd.GetArray("Iterations").IsA("vtkIntArray") and fd.GetArray("Converged").IsA("vtkIntArray"),
          f"{label}: Iterations and Converged are int arrays")
    for name in ("GradientNormHistory", "StepLengthHistory"):
        history = fd.GetArray(name)
        check(history is not None and history.GetNumberOfTuples() == iterations,
              f"{label}: {name} has one value per iteration ({iterations})")
    for name in ("SecondsTriangulation", "SecondsIntegration", "SecondsAssembly", "SecondsSolve",
                 "SecondsOutput", "SecondsTotal"):
        value = field_value(out, name)
        check(value is not None and value >= 0.0, f"{label}: field data {name} >= 0")
    check(isinstance(field_value(out, "StopReason"), str), f"{label}: StopReason is a string")
    check(abs(field_value(out, "SourceMass") - FOUR_PI) <= 1e-15 * FOUR_PI,
          f"{label}: SourceMass is 4 pi")
    largest = field_value(out, "LargestTransportDegrees")
    check(0.0 < largest < 90.0, f"{label}: 0 < LargestTransportDegrees {largest} < 90")
    check(len(progress) >= iterations and max(progress) == 1.0
          and all(b >= a for a, b in zip(progress, progress[1:])),
          f"{label}: progress per iteration, never going back ({len(progress)} events)")

    # Port 0: the Diracs on the sphere with the 2n - 4 triangles of the dual hull.
    check(out.GetNumberOfPoints() == n, f"{label}: port 0 has one point per Dirac")
    check(out.GetNumberOfPolys() == 2 * n - 4,
          f"{label}: port 0 has 2n - 4 = {2 * n - 4} hull triangles ({out.GetNumberOfPolys()})")
    pd = out.GetPointData()
    for name, components in (("Mass", 1), ("Height", 1), ("CellMass", 1), ("Centroid", 3)):
        array = pd.GetArray(name)
        check(array is not None and array.IsA("vtkDoubleArray")
              and array.GetNumberOfComponents() == components and array.GetNumberOfTuples() == n,
              f"{label}: port 0 double point array {name} ({components} comp.)")
    mass = [pd.GetArray("Mass").GetValue(i) for i in range(n)]
    cell_mass = [pd.GetArray("CellMass").GetValue(i) for i in range(n)]
    heights = [pd.GetArray("Height").GetValue(i) for i in range(n)]
    scale = FOUR_PI / math.fsum(masses)
    check(max(abs(m - scale * given) / m for m, given in zip(mass, masses)) <= 1e-14,
          f"{label}: Mass is the input's, rescaled to 4 pi")
    check(abs(math.fsum(mass) - FOUR_PI) <= 1e-12 * FOUR_PI, f"{label}: Mass sums to 4 pi")
    total = math.fsum(cell_mass)
    check(abs(total - FOUR_PI) <= 1e-12 * FOUR_PI, f"{label}: CellMass sums to 4 pi ({total!r})")
    worst = max(abs(c - m) / m for c, m in zip(cell_mass, mass))
    check(worst <= 1e-10, f"{label}: CellMass matches Mass to 1e-10 relative ({worst:.2e})")
    check(abs(math.fsum(heights)) <= 1e-12 * n * max(map(abs, heights)),
          f"{label}: Height has mean 0 (the gauge)")
    ys = [out.GetPoint(i) for i in range(n)]
    check(max(abs(math.sqrt(dot(y, y)) - 1.0) for y in ys) <= 1e-15 * 4,
          f"{label}: port 0 points on the unit sphere")
    centroid = pd.GetArray("Centroid")
    off = max(abs(math.sqrt(dot(centroid.GetTuple3(i), centroid.GetTuple3(i))) - 1.0)
              for i in range(n))
    check(off <= 1e-12, f"{label}: centroids on the unit sphere ({off:.1e})")
    reach = max(math.degrees(math.acos(max(-1.0, min(1.0, dot(centroid.GetTuple3(i), ys[i])))))
                for i in range(n))
    check(reach < largest, f"{label}: every centroid within LargestTransportDegrees of its Dirac")
    outward = min(dot(cross(sub(ys[b], ys[a]), sub(ys[c], ys[a])), ys[a]) for a, b, c in cells(out))
    check(outward > 0.0, f"{label}: hull triangles counter-clockwise seen from outside")

    # Port 1: the power diagram on the sphere, one polygon per Dirac.
    diagram = solver.GetOutput(1)
    ids = diagram.GetCellData().GetArray("DiracId")
    check(ids is not None and ids.IsA("vtkIntArray"), f"{label}: port 1 has int cell array DiracId")
    check(diagram.GetNumberOfPolys() == n, f"{label}: port 1 has one polygon per Dirac")
    if ids is not None:
        check(sorted(int(ids.GetValue(c)) for c in range(ids.GetNumberOfTuples())) == list(range(n)),
              f"{label}: port 1 DiracId covers every Dirac once")
        off = max(abs(math.sqrt(dot(p, p)) - 1.0)
                  for p in (diagram.GetPoint(k) for k in range(diagram.GetNumberOfPoints())))
        check(off <= 1e-15 * 4, f"{label}: port 1 points on the unit sphere ({off:.1e})")
        # The arcs are sampled on their great circles: Girard's areas of the polygons are the
        # cell masses (the geometry is rebuilt from Height rounded to double).
        area_error = 0.0
        for c, polygon in enumerate(cells(diagram)):
            dirac = int(ids.GetValue(c))
            area = spherical_polygon_area([diagram.GetPoint(k) for k in polygon])
            area_error = max(area_error, abs(area - mass[dirac]) / mass[dirac])
        check(area_error <= 2e-10, f"{label}: port 1 polygon areas are the masses ({area_error:.1e})")
        for name in ("Mass", "CellMass"):
            check(diagram.GetCellData().GetArray(name) is not None, f"{label}: port 1 cell array {name}")

    # Port 2: the polytope Q(h) = {x : <x, y_i> <= h_i}, h_i = e^Height_i: one face per Dirac,
    # one vertex per hull triangle, every vertex on the planes of its faces and inside Q(h).
    polytope = solver.GetOutput(2)
    faces = cells(polytope)
    face_dirac = polytope.GetCellData().GetArray("DiracId")
    check(len(faces) == n and polytope.GetNumberOfPoints() == 2 * n - 4 and face_dirac is not None,
          f"{label}: port 2 has n faces with DiracId and 2n - 4 vertices")
    if face_dirac is not None and len(faces) == n:
        h = [math.exp(psi) for psi in heights]
        on_plane = max(abs(dot(polytope.GetPoint(k), ys[int(face_dirac.GetValue(f))])
                           / h[int(face_dirac.GetValue(f))] - 1.0)
                       for f, face in enumerate(faces) for k in face)
        inside = max(dot(polytope.GetPoint(k), y) / hi
                     for k in range(polytope.GetNumberOfPoints()) for y, hi in zip(ys, h))
        check(on_plane <= 1e-12, f"{label}: polytope faces lie on their planes ({on_plane:.1e})")
        check(inside <= 1.0 + 1e-12, f"{label}: polytope vertices inside Q(h) ({inside - 1.0:.1e})")

    # Port 3: the convex hull of y_i / h_i with the dual triangles.
    hull = solver.GetOutput(3)
    check(hull.GetNumberOfPoints() == n and hull.GetNumberOfPolys() == 2 * n - 4
          and hull.GetPointData().GetArray("DiracId") is not None,
          f"{label}: port 3 has n points, the 2n - 4 triangles and DiracId")
    if hull.GetNumberOfPoints() == n:
        gap = max(max(abs(c - yc * math.exp(-psi)) for c, yc in zip(hull.GetPoint(i), ys[i]))
                  for i, psi in enumerate(heights))
        check(gap <= 1e-14, f"{label}: port 3 points are y_i / h_i ({gap:.1e})")
    return solver


# ---- 500 Fibonacci Diracs, masses of contrast 1e2 (from 1 at the south pole to 100 at the
# north pole, log-linear in z).
fibonacci = fibonacci_sphere_points(500)
run_case("Fibonacci, contrast 1e2", fibonacci, [10.0 ** (1.0 + p[2]) for p in fibonacci])

# ---- 400 random Diracs (fixed seed), masses of contrast 1e2 in a smooth random-looking pattern.
random_points = random_sphere_points(400, seed=20261124)
random_masses = [10.0 ** (1.0 + math.sin(3.0 * p[0] + 2.0 * p[1] * p[2] + 5.0 * p[2] * p[0]))
                 for p in random_points]
check(max(random_masses) / min(random_masses) > 50.0, "random case: mass contrast near 1e2")
run_case("random, contrast 1e2", random_points, random_masses)

# ---- Equal masses on the Fibonacci lattice: the spherical Voronoi diagram is nearly the
# answer (heights close to equal).
solver = run_case("Fibonacci, equal masses", fibonacci, [1.0] * len(fibonacci))
heights = solver.GetOutput(0).GetPointData().GetArray("Height").GetRange()
check(heights[1] - heights[0] < 0.05, f"equal masses: heights nearly equal ({heights})")

# ---- Abort from a progress observer: empty outputs, and a later run works again.
diracs = make_sphere_diracs(fibonacci, [10.0 ** (1.0 + p[2]) for p in fibonacci])
aborting = vtkSphericalOTSolver()
aborting.SetInputData(0, diracs)
warnings = MessageRecorder(aborting, vtkCommand.WarningEvent)
aborting.AddObserver(vtkCommand.ProgressEvent, lambda caller, event: caller.SetAbortExecute(1))
aborting.Update()
check(all(aborting.GetOutput(p).GetNumberOfPoints() == 0 for p in range(4)),
      "aborted run leaves every port empty")
check("abort" in warnings.text().lower(), f"aborted run warns: {warnings.text()!r}")
aborting.RemoveAllObservers()
aborting.SetAbortExecute(0)
aborting.Modified()
aborting.Update()
check(field_value(aborting.GetOutput(0), "Converged") == 1, "a run after an abort converges")

# ---- Not converged within MaximumNumberOfIterations = 1: Converged = 0, a warning, and the
# last iterate is still output.
limited = vtkSphericalOTSolver()
limited.SetInputData(0, diracs)
limited.SetMaximumNumberOfIterations(1)
warnings = MessageRecorder(limited, vtkCommand.WarningEvent)
limited.Update()
lout = limited.GetOutput(0)
check(field_value(lout, "Converged") == 0, "Converged == 0 after 1 iteration")
check(field_value(lout, "Iterations") <= 1, "at most 1 iteration")
check(field_value(lout, "RelativeError") > 1e-10, "RelativeError above Tolerance")
text = warnings.text().lower()
check("not converged" in text and "relative error" in text and "maximumnumberofiterations" in text,
      f"warning says how far it got: {warnings.text()!r}")
check(lout.GetNumberOfPoints() == len(fibonacci) and limited.GetOutput(1).GetNumberOfPolys() > 0,
      "the unconverged iterate is still output")

# ---- MaximumArcAngle samples the arcs: a smaller angle, more points on port 1, same cells.
coarse = vtkSphericalOTSolver()
coarse.SetInputData(0, make_sphere_diracs(fibonacci_sphere_points(60), [1.0] * 60))
coarse.SetMaximumArcAngle(1.0)
coarse.Update()
fine = vtkSphericalOTSolver()
fine.SetInputData(0, make_sphere_diracs(fibonacci_sphere_points(60), [1.0] * 60))
fine.SetMaximumArcAngle(0.01)
fine.Update()
check(fine.GetOutput(1).GetNumberOfPoints() > 3 * coarse.GetOutput(1).GetNumberOfPoints()
      and fine.GetOutput(1).GetNumberOfPolys() == coarse.GetOutput(1).GetNumberOfPolys() == 60,
      "MaximumArcAngle 0.01 samples the arcs more finely than 1.0")

finish()
