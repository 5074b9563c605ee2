"""Every bad input of vtkSemiDiscreteOTSolver: a vtkErrorMacro naming the problem (and the
offending ids), RequestData failing, all outputs empty, the input untouched, and the filter
working again once the input is fixed."""

import math

from otparam import vtkSemiDiscreteOTSolver
from otparam_test_utils import (check_failed_run, MessageRecorder, check, finish, make_diracs, make_domain,
                                random_disk_points, same, snapshot, square_domain)
from vtkmodules.vtkCommonCore import vtkDoubleArray, vtkStringArray
from vtkmodules.vtkCommonDataModel import vtkPolyData

N = 20
POINTS = random_disk_points(N, seed=7)


def good_diracs():
    return make_diracs(POINTS, [1.0 + 0.1 * i for i in range(N)])


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
    data.GetPoints().SetPoint(11, data.GetPoints().GetPoint(4))
    return data


def lifted_square():
    domain = square_domain(1.0)
    domain.GetPoints().SetPoint(2, 1.0, 1.0, 0.25)
    return domain


def l_shape():
    # An L made of 3 unit squares (6 triangles): triangulated, planar, not convex.
    points = [(0, 0, 0), (1, 0, 0), (2, 0, 0), (0, 1, 0), (1, 1, 0), (2, 1, 0), (0, 2, 0), (1, 2, 0)]
    triangles = [(0, 1, 4), (0, 4, 3), (1, 2, 5), (1, 5, 4), (3, 4, 7), (3, 7, 6)]
    return make_domain(points, triangles)


def quad_domain():
    points = [(-1, -1, 0), (1, -1, 0), (1, 1, 0), (-1, 1, 0)]
    return make_domain(points, [(0, 1, 2, 3)])


def density(values):
    return square_domain(1.0, density=values)


# name, Diracs, source domain (or None), settings, words the message must contain (lower case;
# a tuple means any of them).
CASES = [
    ("no points", vtkPolyData(), None, {}, ["no points"]),
    ("Mass missing", without_mass(), None, {}, ["mass"]),
    ("Mass not numeric", string_mass(), None, {}, ["mass", "not numeric"]),
    ("Mass with 2 components", vector_mass(), None, {}, ["mass", "component"]),
    ("Mass NaN", with_mass(7, float("nan")), None, {}, ["mass", "nan", "7"]),
    ("Mass zero", with_mass(3, 0.0), None, {}, ["mass", ("positive", "zero"), "3"]),
    ("Mass negative", with_mass(5, -2.0), None, {}, ["mass", ("positive", "negative"), "5"]),
    ("Mass infinite", with_mass(6, float("inf")), None, {}, ["mass", ("finite", "infinite"), "6"]),
    ("NaN coordinate", with_point(4, (float("nan"), 0.1, 0.0)), None, {}, ["nan", "coordinate", "4"]),
    ("infinite coordinate", with_point(9, (0.1, float("inf"), 0.0)), None, {}, ["infinite", "9"]),
    ("NaN z coordinate", with_point(12, (0.1, 0.2, float("nan"))), None, {}, ["nan", "12"]),
    ("duplicate points", duplicate(), None, {}, [("duplicate", "share their position"), "4", "11"]),
    ("non-planar source", good_diracs(), lifted_square(), {}, ["planar", "z", "2"]),
    ("non-convex source", good_diracs(), l_shape(), {}, ["convex"]),
    ("non-triangle source", good_diracs(), quad_domain(), {}, ["triang", "0"]),
    ("Density zero", good_diracs(), density([1.0, 0.0, 1.0, 1.0]), {}, ["density", "1"]),
    ("Density negative", good_diracs(), density([1.0, 1.0, -1.0, 1.0]), {}, ["density", "2"]),
    ("Density NaN", good_diracs(), density([float("nan"), 1.0, 1.0, 1.0]), {}, ["density", "0"]),
    ("Tolerance zero", good_diracs(), None, {"Tolerance": 0.0}, ["tolerance"]),
    ("Tolerance negative", good_diracs(), None, {"Tolerance": -1e-8}, ["tolerance", "positive"]),
    ("Tolerance NaN", good_diracs(), None, {"Tolerance": float("nan")}, ["tolerance"]),
    ("MaximumNumberOfIterations 0", good_diracs(), None, {"MaximumNumberOfIterations": 0},
     ["maximumnumberofiterations", "at least 1"]),
    ("MaximumNumberOfIterations negative", good_diracs(), None, {"MaximumNumberOfIterations": -5},
     ["maximumnumberofiterations"]),
]

for name, diracs, domain, settings, words in CASES:
    before_diracs = snapshot(diracs)
    before_domain = snapshot(domain) if domain is not None else None
    solver = vtkSemiDiscreteOTSolver()
    for prop, value in settings.items():
        getattr(solver, "Set" + prop)(value)
    solver.SetInputData(0, diracs)
    if domain is not None:
        solver.SetSourceDomainData(domain)
    errors = MessageRecorder(solver)
    pipeline_errors = MessageRecorder(solver.GetExecutive())
    solver.Update()

    check_failed_run(name, errors, pipeline_errors, words)
    for port in range(solver.GetNumberOfOutputPorts()):
        output = solver.GetOutput(port)
        check(output.GetNumberOfPoints() == 0 and output.GetNumberOfCells() == 0
              and output.GetPointData().GetNumberOfArrays() == 0
              and output.GetFieldData().GetNumberOfArrays() == 0,
              f"{name}: output port {port} is empty")
    check(same(snapshot(diracs), before_diracs), f"{name}: the Diracs input is not modified")
    if domain is not None:
        check(same(snapshot(domain), before_domain), f"{name}: the source domain is not modified")

# A failed run does not poison the filter: fix the input and it works.
solver = vtkSemiDiscreteOTSolver()
solver.SetInputData(0, with_mass(2, -1.0))
MessageRecorder(solver)
MessageRecorder(solver.GetExecutive())
solver.Update()
check(solver.GetOutput(0).GetNumberOfPoints() == 0, "bad Mass: empty output")
solver.SetInputData(0, good_diracs())
solver.Update()
converged = solver.GetOutput(0).GetFieldData().GetArray("Converged")
check(converged is not None and converged.GetValue(0) == 1, "fixed input: converges")

finish()
