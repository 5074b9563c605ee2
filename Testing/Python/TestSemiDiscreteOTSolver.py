"""vtkSemiDiscreteOTSolver through the Python package: the unit disk with 100 equal Diracs, all
output ports, field data, progress and abort, non-convergence, a triangulated source with a
linear density, and Diracs outside the source."""

import math

import otparam
from otparam import vtkSemiDiscreteOTSolver
from otparam_test_utils import (MessageRecorder, check, field_value, finish, make_diracs,
                                random_disk_points, same, snapshot, square_domain)
from vtkmodules.vtkCommonCore import vtkCommand

N = 100

# ---- The package: exports the class, documents its ports and arrays for help().
check("vtkSemiDiscreteOTSolver" in otparam.__all__, "otparam.__all__ lists the solver")
doc = vtkSemiDiscreteOTSolver.__doc__ or ""
for word in ("Power Diagram", "Brenier Potential", "Legendre Dual", "Discontinuities",
             "CellMass", "Centroid", "GradientNormHistory", "JumpLength", "Tolerance"):
    check(word in doc, f"class documentation mentions {word}")

# ---- 100 random Diracs (fixed seed) of mass pi/100 in the default source, the unit disk.
points = random_disk_points(N, seed=20240611)
diracs = make_diracs(points, [math.pi / N] * N)
before = snapshot(diracs)

solver = vtkSemiDiscreteOTSolver()
check(solver.GetTolerance() == 1e-10, "default Tolerance is 1e-10")
check(solver.GetMaximumNumberOfIterations() == 200, "default MaximumNumberOfIterations is 200")
check(solver.GetNumberOfOutputPorts() == 5, "5 output ports")
errors = MessageRecorder(solver)
progress = []
solver.AddObserver(vtkCommand.ProgressEvent, lambda caller, event: progress.append(caller.GetProgress()))
solver.SetInputData(0, diracs)
solver.Update()

check(not errors.messages, f"no error on valid input: {errors.text()}")
check(same(snapshot(diracs), before), "the input is not modified")

out = solver.GetOutput(0)
iterations = int(field_value(out, "Iterations"))
relative_error = field_value(out, "RelativeError")
print(f"unit disk, {N} Diracs: {iterations} iterations, relative error {relative_error:.3e}, "
      f"{field_value(out, 'SecondsTotal'):.3f} s")
check(field_value(out, "Converged") == 1, "Converged == 1")
check(relative_error is not None and relative_error <= 1e-10, f"RelativeError {relative_error} <= 1e-10")
check(out.GetFieldData().GetArray("Iterations").IsA("vtkIntArray"), "Iterations is an int array")
check(out.GetFieldData().GetArray("Converged").IsA("vtkIntArray"), "Converged is an int array")
for name in ("GradientNormHistory", "StepLengthHistory"):
    history = out.GetFieldData().GetArray(name)
    check(history is not None and history.GetNumberOfTuples() == iterations,
          f"{name} has one value per iteration ({iterations})")
steps = out.GetFieldData().GetArray("StepLengthHistory")
check(all(0.0 < steps.GetValue(k) <= 1.0 for k in range(steps.GetNumberOfTuples())),
      "step lengths are in (0, 1]")
for name in ("SecondsTriangulation", "SecondsIntegration", "SecondsAssembly", "SecondsSolve",
             "SecondsOutput", "SecondsTotal"):
    value = field_value(out, name)
    check(value is not None and value >= 0.0, f"field data {name} >= 0")
check(abs(field_value(out, "SourceMass") - math.pi) <= 1e-12 * math.pi, "SourceMass is pi")
check(len(progress) >= iterations and max(progress) == 1.0,
      f"progress reported per iteration ({len(progress)} events, last {progress[-1:]})")
check(all(b >= a for a, b in zip(progress, progress[1:])), "progress never goes back")

# Port 0: the Diracs, weighted Delaunay triangles, point arrays.
check(out.GetNumberOfPoints() == N, "port 0 has one point per Dirac")
check(out.GetNumberOfPolys() > N, f"port 0 has the Delaunay triangles ({out.GetNumberOfPolys()})")
pd = out.GetPointData()
for name, components in (("Mass", 1), ("Height", 1), ("CellMass", 1), ("Centroid", 3)):
    array = pd.GetArray(name)
    check(array is not None and array.IsA("vtkDoubleArray") and array.GetNumberOfComponents() == components
          and array.GetNumberOfTuples() == N, f"port 0 double point array {name} ({components} comp.)")
mass = [pd.GetArray("Mass").GetValue(i) for i in range(N)]
cell_mass = [pd.GetArray("CellMass").GetValue(i) for i in range(N)]
total = math.fsum(cell_mass)
check(abs(total - math.pi) <= 1e-12 * math.pi, f"sum of CellMass {total!r} == pi to 1e-12")
check(abs(math.fsum(mass) - math.pi) <= 1e-12 * math.pi, "Mass is rescaled to total pi")
check(max(abs(c - m) / m for c, m in zip(cell_mass, mass)) <= 1e-10, "every cell has its mass")
for i in range(N):
    x, y, z = out.GetPoint(i)
    cx, cy, cz = pd.GetArray("Centroid").GetTuple3(i)
    if not check(z == 0.0 and cz == 0.0 and cx * cx + cy * cy < 1.0, f"Dirac {i}: z = 0, centroid in the disk"):
        break

# Port 1: the power diagram, one polygon per cell, with DiracId.
diagram = solver.GetOutput(1)
ids = diagram.GetCellData().GetArray("DiracId")
check(ids is not None, "port 1 has cell array DiracId")
check(diagram.GetNumberOfPolys() == N, f"port 1 has one polygon per Dirac ({diagram.GetNumberOfPolys()})")
if ids is not None:
    check(sorted(int(ids.GetValue(c)) for c in range(ids.GetNumberOfTuples())) == list(range(N)),
          "port 1 DiracId covers every Dirac once")
bounds = diagram.GetBounds()
check(max(abs(b) for b in bounds[:4]) <= 1.0 + 1e-12 and bounds[4] == bounds[5] == 0.0,
      f"port 1 lies in the unit disk, z = 0 ({bounds})")

# Port 2: the Brenier potential u(x) = max_i <x, y_i> - h_i over the disk.
brenier = solver.GetOutput(2)
check(brenier.GetNumberOfPolys() >= N and brenier.GetCellData().GetArray("DiracId") is not None,
      "port 2: triangles with DiracId")
heights = [pd.GetArray("Height").GetValue(i) for i in range(N)]
worst = 0.0
for k in range(0, brenier.GetNumberOfPoints(), 7):
    x, y, z = brenier.GetPoint(k)
    u = max(x * p[0] + y * p[1] - h for p, h in zip(points, heights))
    worst = max(worst, abs(u - z))
check(worst <= 1e-9, f"port 2 heights are max_i <x, y_i> - h_i (error {worst:.2e})")

# Port 3: the Legendre dual through (y_i, h_i).
dual = solver.GetOutput(3)
check(dual.GetNumberOfPoints() == N and dual.GetNumberOfPolys() == out.GetNumberOfPolys(),
      "port 3: one point per Dirac with the Delaunay triangles")
check(all(abs(dual.GetPoint(i)[2] - heights[i]) == 0.0 for i in range(N)), "port 3: z = Height")

# Port 4: discontinuities: empty for now, JumpLength declared.
jumps = solver.GetOutput(4)
check(jumps.GetNumberOfCells() == 0 and jumps.GetCellData().GetArray("JumpLength") is not None,
      "port 4: empty, with cell array JumpLength")

# ---- Abort from a progress observer: empty outputs, and a later run works again.
aborting = vtkSemiDiscreteOTSolver()
aborting.SetInputData(0, diracs)
warnings = MessageRecorder(aborting, vtkCommand.WarningEvent)
aborting.AddObserver(vtkCommand.ProgressEvent, lambda caller, event: caller.SetAbortExecute(1))
aborting.Update()
check(aborting.GetOutput(0).GetNumberOfPoints() == 0, "aborted run leaves port 0 empty")
check("abort" in warnings.text().lower(), f"aborted run warns: {warnings.text()!r}")
aborting.RemoveAllObservers()
aborting.SetAbortExecute(0)
aborting.Modified()
aborting.Update()
check(field_value(aborting.GetOutput(0), "Converged") == 1, "a run after an abort converges")

# ---- Not converged within MaximumNumberOfIterations = 1: Converged = 0 and a warning.
uneven = make_diracs(points, [1.0 + 50.0 * x * x for x, _ in points])
limited = vtkSemiDiscreteOTSolver()
limited.SetInputData(0, uneven)
limited.SetMaximumNumberOfIterations(1)
warnings = MessageRecorder(limited, vtkCommand.WarningEvent)
limited.Update()
lout = limited.GetOutput(0)
check(field_value(lout, "Converged") == 0, "Converged == 0 after 1 iteration")
check(field_value(lout, "Iterations") <= 1, "at most 1 iteration")
check(field_value(lout, "RelativeError") > 1e-10, "RelativeError above Tolerance")
check("not converged" in warnings.text().lower() and "relative error" in warnings.text().lower(),
      f"warning says how far it got: {warnings.text()!r}")
check(lout.GetNumberOfPoints() == N and limited.GetOutput(1).GetNumberOfPolys() > 0,
      "the unconverged iterate is still output")

# ---- Triangulated source: the square [-1, 1]^2 with the linear density 2 + x.
square = square_domain(1.0, density=[1.0, 3.0, 3.0, 1.0])
square_points = [(1.9 * (x / 0.95) / 2.0, 1.9 * (y / 0.95) / 2.0) for x, y in points]
linear = vtkSemiDiscreteOTSolver()
linear.SetInputData(0, make_diracs(square_points, [1.0] * N))
linear.SetSourceDomainData(square)
errors = MessageRecorder(linear)
linear.Update()
sout = linear.GetOutput(0)
smass = sum(sout.GetPointData().GetArray("CellMass").GetValue(i) for i in range(N))
check(not errors.messages, f"triangulated source: no error ({errors.text()})")
check(field_value(sout, "Converged") == 1, "triangulated source converges")
check(abs(field_value(sout, "SourceMass") - 8.0) <= 1e-12 * 8.0, "square with density 2 + x has mass 8")
check(abs(smass - 8.0) <= 1e-10 * 8.0, f"cell masses sum to 8 ({smass})")

# ---- Diracs outside the source domain are valid input.
outside = vtkSemiDiscreteOTSolver()
outside.SetInputData(0, make_diracs([(3.0 + x, 2.0 * y) for x, y in points[:30]], [1.0] * 30))
errors = MessageRecorder(outside)
outside.Update()
oout = outside.GetOutput(0)
check(not errors.messages and field_value(oout, "Converged") == 1,
      f"Diracs outside the disk: converged ({errors.text()})")
check(outside.GetOutput(1).GetNumberOfPolys() == 30, "Diracs outside the disk: every cell non-empty")

finish()
