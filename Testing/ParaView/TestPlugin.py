"""Loads OTParam.so into ParaView and runs its filters: Semi-Discrete OT Solver on Diracs read
from a .vtp, Conformal Disk Map on a triangulated ParaView Plane.

Usage: pvpython|pvbatch TestPlugin.py <OTParam.so> <work dir>
In the GUI (paraview --script=...), the same arguments come from the environment variables
OTPARAM_PLUGIN and OTPARAM_TEST_DIR; with OTPARAM_SCREENSHOT=1 it also renders the power
diagram. Writes <work dir>/PASSED when every check passed.
"""

import math
import os
import random
import sys

from paraview import servermanager
from paraview.simple import *  # noqa: F401,F403  (LoadPlugin adds the OTParam functions here)
from vtkmodules.vtkCommonCore import vtkDoubleArray, vtkPoints
from vtkmodules.vtkCommonDataModel import vtkCellArray, vtkPolyData
from vtkmodules.vtkIOXML import vtkXMLPolyDataWriter

if len(sys.argv) >= 3:
    plugin, work_dir = sys.argv[1], sys.argv[2]
else:
    plugin, work_dir = os.environ["OTPARAM_PLUGIN"], os.environ["OTPARAM_TEST_DIR"]
os.makedirs(work_dir, exist_ok=True)
passed_marker = os.path.join(work_dir, "PASSED")
if os.path.exists(passed_marker):
    os.remove(passed_marker)

failures = []


def check(condition, message):
    if not condition:
        failures.append(message)
        print("FAIL:", message, flush=True)


# ---- Diracs with Mass, written by this test (50 random points in the disk, fixed seed).
n = 50
rng = random.Random(11)
points = vtkPoints()
points.SetDataTypeToDouble()
mass = vtkDoubleArray()
mass.SetName("Mass")
vertices = vtkCellArray()
while points.GetNumberOfPoints() < n:
    x, y = rng.uniform(-0.9, 0.9), rng.uniform(-0.9, 0.9)
    if x * x + y * y < 0.81:
        vertices.InsertNextCell(1, [points.InsertNextPoint(x, y, 0.0)])
        mass.InsertNextValue(1.0 + x)
diracs = vtkPolyData()
diracs.SetPoints(points)
diracs.SetVerts(vertices)
diracs.GetPointData().AddArray(mass)
vtp = os.path.join(work_dir, "diracs.vtp")
writer = vtkXMLPolyDataWriter()
writer.SetFileName(vtp)
# Inline (not appended) data: Debian 12's expat security update breaks reading appended data.
writer.SetDataModeToBinary()
writer.SetInputData(diracs)
check(writer.Write() == 1, f"wrote {vtp}")

# ---- The plugin: loads, defines the filter under its label, in the right menu category.
LoadPlugin(plugin, ns=globals())
check("SemiDiscreteOTSolver" in globals(), "LoadPlugin defines SemiDiscreteOTSolver")

reader = XMLPolyDataReader(FileName=[vtp])
solver = SemiDiscreteOTSolver(Diracs=reader)
check(abs(solver.Tolerance - 1e-10) < 1e-25, "Tolerance property defaults to 1e-10")
check(solver.MaximumNumberOfIterations == 200, "MaximumNumberOfIterations defaults to 200")
hints = solver.SMProxy.GetHints()
menu = hints.FindNestedElementByName("ShowInMenu") if hints else None
check(menu is not None and menu.GetAttribute("category") == "Optimal Transport",
      "the filter is in the menu category 'Optimal Transport'")
check(solver.SMProxy.GetXMLLabel() == "Semi-Discrete OT Solver", "label 'Semi-Discrete OT Solver'")
names = [solver.SMProxy.GetOutputPortName(i) for i in range(solver.SMProxy.GetNumberOfOutputPorts())]
check(names == ["Diracs", "Power Diagram", "Brenier Potential", "Legendre Dual", "Discontinuities"],
      f"output port names {names}")

solver.UpdatePipeline()
out = servermanager.Fetch(solver)
fd = out.GetFieldData()
converged = fd.GetArray("Converged")
check(converged is not None and converged.GetValue(0) == 1, "Converged == 1 by value")
error = fd.GetArray("RelativeError")
check(error is not None and error.GetValue(0) <= 1e-10, "RelativeError <= 1e-10")
check(out.GetNumberOfPoints() == n, f"{n} Diracs out")
cell_mass = out.GetPointData().GetArray("CellMass")
total = math.fsum(cell_mass.GetValue(i) for i in range(n)) if cell_mass else 0.0
check(abs(total - math.pi) <= 1e-12 * math.pi, f"cell masses sum to pi ({total!r})")
diagram = servermanager.Fetch(solver, idx=1)
check(diagram.GetNumberOfCells() == n and diagram.GetCellData().GetArray("DiracId") is not None,
      "Power Diagram port: one polygon per Dirac with DiracId")
print(f"pipeline: {int(fd.GetArray('Iterations').GetValue(0))} Newton iterations, relative error "
      f"{error.GetValue(0) if error else float('nan'):.3e}", flush=True)

# A different setting reaches the server: one iteration cannot converge on uneven masses.
solver.MaximumNumberOfIterations = 1
solver.UpdatePipeline()
limited = servermanager.Fetch(solver)
check(limited.GetFieldData().GetArray("Converged").GetValue(0) == 0,
      "MaximumNumberOfIterations = 1: Converged == 0")
solver.MaximumNumberOfIterations = 200

# ---- Conformal Disk Map on ParaView's own Plane source, triangulated (a square is a disk).
check("ConformalDiskMap" in globals(), "LoadPlugin defines ConformalDiskMap")
plane = Triangulate(Input=Plane(XResolution=12, YResolution=12))
conformal = ConformalDiskMap(Input=plane)
check(conformal.SMProxy.GetXMLLabel() == "Conformal Disk Map", "label 'Conformal Disk Map'")
hints = conformal.SMProxy.GetHints()
menu = hints.FindNestedElementByName("ShowInMenu") if hints else None
check(menu is not None and menu.GetAttribute("category") == "Optimal Transport",
      "Conformal Disk Map is in the menu category 'Optimal Transport'")
check(conformal.CenterPointId == -1 and conformal.AlignPointId == -1,
      "CenterPointId and AlignPointId default to -1")
conformal.UpdatePipeline()
disk = servermanager.Fetch(conformal)
fd = disk.GetFieldData()
check(disk.GetNumberOfPoints() == 13 * 13, "every plane point in the disk image")
check(fd.GetArray("FlippedTriangles") is not None and fd.GetArray("FlippedTriangles").GetValue(0) == 0,
      "no flipped triangle")
check(fd.GetArray("MaximumBoundaryRadiusError").GetValue(0) <= 1e-12, "boundary on the circle")
check(disk.GetPointData().GetArray("AreaDensity") is not None
      and disk.GetCellData().GetArray("AreaDensity") is not None, "AreaDensity per point and cell")
check(disk.GetPointData().GetTCoords() is not None, "texture coordinates")
conformal.CenterPointId = 20  # an interior point of the 13 x 13 grid
conformal.UpdatePipeline()
moved = servermanager.Fetch(conformal)
x, y, _ = moved.GetPoint(20)
check(math.hypot(x, y) < 1e-14, f"CenterPointId = 20 goes to the origin ({x}, {y})")

if os.environ.get("OTPARAM_SCREENSHOT") == "1":
    # The GUI only renders views that sit in a layout: use (or create) the active one.
    view = GetActiveViewOrCreate("RenderView")
    view.OrientationAxesVisibility = 0
    display = Show(OutputPort(solver, 1), view)
    ColorBy(display, ("CELLS", "DiracId"))
    display.RescaleTransferFunctionToDataRange(True)
    Show(OutputPort(solver, 0), view).SetRepresentationType("Wireframe")
    view.ResetCamera()
    Render(view)
    png = os.path.join(work_dir, "power_diagram.png")
    SaveScreenshot(png, view, ImageResolution=[600, 600])
    from vtkmodules.vtkIOImage import vtkPNGReader
    from vtkmodules.util.numpy_support import vtk_to_numpy
    import numpy
    image = vtkPNGReader()
    image.SetFileName(png)
    image.Update()
    pixels = vtk_to_numpy(image.GetOutput().GetPointData().GetScalars())
    colors = len(numpy.unique(pixels[:, :3], axis=0))
    check(colors >= n, f"screenshot {png} shows the colored cells ({colors} distinct colors)")

if failures:
    print(f"{len(failures)} check(s) failed", flush=True)
    sys.exit(1)
with open(passed_marker, "w") as f:
    f.write("ok\n")
print("all checks passed", flush=True)
