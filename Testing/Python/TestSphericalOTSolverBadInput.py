"""Every bad input of vtkSphericalOTSolver: a vtkErrorMacro naming the problem (and the
offending ids), RequestData failing, all outputs empty, the input untouched, and the filter
working again once the input is fixed."""

from otparam import vtkSphericalOTSolver
from otparam_test_utils import (MessageRecorder, check, check_failed_run, fibonacci_sphere_points,
                                finish, make_sphere_diracs, same, snapshot)
from vtkmodules.vtkCommonCore import vtkDoubleArray, vtkStringArray
from vtkmodules.vtkCommonDataModel import vtkPolyData

N = 30
POINTS = fibonacci_sphere_points(N)


def good_diracs():
    return make_sphere_diracs(POINTS, [1.0 + 0.1 * i for i in range(N)])


def with_mass(index, value):
    data = good_diracs()
    data.GetPointData().GetArray("Mass").SetValue(index, value)
    return data


def with_point(index, xyz):
    data = good_diracs()
    data.GetPoints().SetPoint(index, *xyz)
    return data


def without_mass():
    data = good_diracs()
    data.GetPointData().RemoveArray("Mass")
    other = vtkDoubleArray()
    other.SetName("Weight")
    other.SetNumberOfTuples(N)
    other.Fill(1.0)
    data.GetPointData().AddArray(other)
    return data


def string_mass():
    data = good_diracs()
    data.GetPointData().RemoveArray("Mass")
    mass = vtkStringArray()
    mass.SetName("Mass")
    for i in range(N):
        mass.InsertNextValue("heavy")
    data.GetPointData().AddArray(mass)
    return data


def vector_mass():
    data = good_diracs()
    data.GetPointData().RemoveArray("Mass")
    mass = vtkDoubleArray()
    mass.SetName("Mass")
    mass.SetNumberOfComponents(2)
    mass.SetNumberOfTuples(N)
    mass.Fill(1.0)
    data.GetPointData().AddArray(mass)
    return data


def duplicate():
    data = good_diracs()
    data.GetPoints().SetPoint(17, data.GetPoints().GetPoint(4))
    return data


def upper_hemisphere(closed):
    """The points with z >= 0 (closed: some of them on the equator)."""
    points = [(x, y, abs(z)) for x, y, z in POINTS]
    if closed:
        points[:3] = [(1.0, 0.0, 0.0), (0.0, 1.0, 0.0), (-0.6, -0.8, 0.0)]
    return make_sphere_diracs(points, [1.0] * N)


def three_points():
    return make_sphere_diracs([(1.0, 0.0, 0.0), (0.0, 1.0, 0.0), (0.0, 0.0, 1.0)], [1.0] * 3)


# name, Diracs, settings, words the message must contain (lower case; a tuple means any of them).
CASES = [
    ("no points", vtkPolyData(), {}, ["no points"]),
    ("Mass missing", without_mass(), {}, ["mass"]),
    ("Mass not numeric", string_mass(), {}, ["mass", "not numeric"]),
    ("Mass with 2 components", vector_mass(), {}, ["mass", "component"]),
    ("Mass NaN", with_mass(7, float("nan")), {}, ["mass", "nan", "7"]),
    ("Mass zero", with_mass(3, 0.0), {}, ["mass", ("positive", "zero"), "3"]),
    ("Mass negative", with_mass(5, -2.0), {}, ["mass", ("positive", "negative"), "5"]),
    ("Mass infinite", with_mass(6, float("inf")), {}, ["mass", ("finite", "infinite"), "6"]),
    ("NaN coordinate", with_point(4, (float("nan"), 0.1, 0.0)), {}, ["nan", "coordinate", "4"]),
    ("infinite coordinate", with_point(9, (0.1, float("inf"), 0.0)), {}, ["infinite", "9"]),
    ("point off the sphere", with_point(12, (0.0, 0.0, 1.01)), {}, ["unit sphere", "12"]),
    ("point inside the sphere", with_point(13, (0.0, 0.5, 0.0)), {}, ["unit sphere", "13"]),
    ("point at the origin", with_point(14, (0.0, 0.0, 0.0)), {}, ["unit sphere", "14"]),
    ("duplicate points", duplicate(), {}, [("duplicate", "share their position"), "4", "17"]),
    ("open hemisphere", upper_hemisphere(False), {}, ["hemisphere"]),
    ("closed hemisphere", upper_hemisphere(True), {}, ["hemisphere"]),
    ("3 points", three_points(), {}, ["3", "at least 4"]),
    ("Tolerance zero", good_diracs(), {"Tolerance": 0.0}, ["tolerance"]),
    ("Tolerance negative", good_diracs(), {"Tolerance": -1e-8}, ["tolerance", "positive"]),
    ("Tolerance NaN", good_diracs(), {"Tolerance": float("nan")}, ["tolerance"]),
    ("Tolerance infinite", good_diracs(), {"Tolerance": float("inf")}, ["tolerance", "finite"]),
    ("MaximumNumberOfIterations 0", good_diracs(), {"MaximumNumberOfIterations": 0},
     ["maximumnumberofiterations", "at least 1"]),
    ("MaximumNumberOfIterations negative", good_diracs(), {"MaximumNumberOfIterations": -5},
     ["maximumnumberofiterations"]),
    ("MaximumArcAngle zero", good_diracs(), {"MaximumArcAngle": 0.0}, ["maximumarcangle"]),
    ("MaximumArcAngle 2", good_diracs(), {"MaximumArcAngle": 2.0}, ["maximumarcangle", "(0, 1]"]),
]

for name, diracs, settings, words in CASES:
    before = snapshot(diracs)
    solver = vtkSphericalOTSolver()
    for prop, value in settings.items():
        getattr(solver, "Set" + prop)(value)
    solver.SetInputData(0, diracs)
    errors = MessageRecorder(solver)
    pipeline_errors = MessageRecorder(solver.GetExecutive())
    solver.Update()

    check_failed_run(name, errors, pipeline_errors, words)
    for port in range(solver.GetNumberOfOutputPorts()):
        output = solver.GetOutput(port)
        check(output.GetNumberOfPoints() == 0 and output.GetNumberOfCells() == 0
              and output.GetPointData().GetNumberOfArrays() == 0
              and output.GetCellData().GetNumberOfArrays() == 0
              and output.GetFieldData().GetNumberOfArrays() == 0,
              f"{name}: output port {port} is empty")
    check(same(snapshot(diracs), before), f"{name}: the Diracs input is not modified")

# Points on the sphere up to rounding (1e-9 off) are accepted and normalized on output.
nearly = with_point(2, tuple((1.0 + 1e-9) * c for c in POINTS[2]))
solver = vtkSphericalOTSolver()
solver.SetInputData(0, nearly)
errors = MessageRecorder(solver)
solver.Update()
x, y, z = solver.GetOutput(0).GetPoint(2)
check(not errors.messages and abs((x * x + y * y + z * z) ** 0.5 - 1.0) <= 1e-15,
      f"a point 1e-9 off the sphere is accepted and normalized ({errors.text()})")

# A failed run does not poison the filter: fix the input and it works.
solver = vtkSphericalOTSolver()
solver.SetInputData(0, with_mass(2, -1.0))
MessageRecorder(solver)
MessageRecorder(solver.GetExecutive())
solver.Update()
check(solver.GetOutput(0).GetNumberOfPoints() == 0, "bad Mass: empty output")
solver.SetInputData(0, good_diracs())
solver.Update()
out = solver.GetOutput(0)
converged = out.GetFieldData().GetArray("Converged")
check(converged is not None and converged.GetValue(0) == 1, "fixed input: converges")
check(out.GetNumberOfPolys() == 2 * N - 4, "fixed input: the 2n - 4 hull triangles")

finish()
