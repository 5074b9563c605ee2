"""Loads OTParam.so into ParaView and runs its filters and its mesh reader (OpenDataFile on .off
and .obj, Save Data as .obj read back with its texture coordinates): Semi-Discrete OT Solver on Diracs read
from a .vtp, Spherical OT Solver on Diracs on the unit sphere read from a .vtp, Conformal Disk Map on a triangulated ParaView Plane, Adaptive Density Sampler on
a triangulated disk read from a .vtp (and the OT solver on its samples), Area-Preserving
Parameterization on a bumpy plane (all three ports), on a closed sphere (Domain Automatic: the
sphere path; Domain Disk: its error in the output window, empty outputs, the filter usable
again), Conformal Sphere Map on the closed sphere and the sphere chain (Adaptive Density Sampler
on its output, then the Spherical OT Solver).

Usage: pvpython|pvbatch TestPlugin.py <OTParam.so> <work dir>
In the GUI (paraview --script=...), the same arguments come from the environment variables
OTPARAM_PLUGIN and OTPARAM_TEST_DIR; with OTPARAM_SCREENSHOT=1 it also renders the power
diagram, the area-preserving texture on a shared face (compared with a baseline from
OTPARAM_BASELINE_DIR; the mesh from OTPARAM_SHARED_DATA_DIR, the circle texture from
OTPARAM_EXAMPLES_DIR) and the histograms in a bar chart. Writes <work dir>/PASSED when every
check passed.
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
for stale in (passed_marker, os.path.join(work_dir, "FAILURES")):
    if os.path.exists(stale):
        os.remove(stale)

failures = []


def check(condition, message):
    if not condition:
        failures.append(message)
        print("FAIL:", message, flush=True)
        # The GUI keeps the script's output in its own window: leave the failures in a file.
        with open(os.path.join(work_dir, "FAILURES"), "a") as f:
            f.write(message + "\n")


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

# ---- Spherical OT Solver on 200 Fibonacci Diracs on the unit sphere, written by this test,
# masses of contrast 1e2 (log-linear in z).
sphere_n = 200
sphere_points = vtkPoints()
sphere_points.SetDataTypeToDouble()
sphere_mass = vtkDoubleArray()
sphere_mass.SetName("Mass")
sphere_vertices = vtkCellArray()
golden = math.pi * (3.0 - math.sqrt(5.0))
for i in range(sphere_n):
    z = 1.0 - (2.0 * i + 1.0) / sphere_n
    r = math.sqrt(1.0 - z * z)
    sphere_vertices.InsertNextCell(1, [sphere_points.InsertNextPoint(
        r * math.cos(golden * i), r * math.sin(golden * i), z)])
    sphere_mass.InsertNextValue(10.0 ** (1.0 + z))
sphere_diracs = vtkPolyData()
sphere_diracs.SetPoints(sphere_points)
sphere_diracs.SetVerts(sphere_vertices)
sphere_diracs.GetPointData().AddArray(sphere_mass)
sphere_vtp = os.path.join(work_dir, "sphere_diracs.vtp")
writer.SetFileName(sphere_vtp)
writer.SetInputData(sphere_diracs)
check(writer.Write() == 1, f"wrote {sphere_vtp}")

check("SphericalOTSolver" in globals(), "LoadPlugin defines SphericalOTSolver")
spherical = SphericalOTSolver(Diracs=XMLPolyDataReader(FileName=[sphere_vtp]))
check(spherical.SMProxy.GetXMLLabel() == "Spherical OT Solver", "label 'Spherical OT Solver'")
hints = spherical.SMProxy.GetHints()
menu = hints.FindNestedElementByName("ShowInMenu") if hints else None
check(menu is not None and menu.GetAttribute("category") == "Optimal Transport",
      "Spherical OT Solver is in the menu category 'Optimal Transport'")
check(abs(spherical.Tolerance - 1e-10) < 1e-25 and spherical.MaximumNumberOfIterations == 200
      and abs(spherical.MaximumArcAngle - 0.05) < 1e-15,
      "Spherical OT Solver: Tolerance 1e-10, MaximumNumberOfIterations 200, MaximumArcAngle 0.05")
names = [spherical.SMProxy.GetOutputPortName(i)
         for i in range(spherical.SMProxy.GetNumberOfOutputPorts())]
check(names == ["Diracs", "Power Diagram", "Polytope", "Convex Hull"],
      f"Spherical OT Solver output port names {names}")
spherical.UpdatePipeline()
sout = servermanager.Fetch(spherical)
sfd = sout.GetFieldData()
check(sfd.GetArray("Converged") is not None and sfd.GetArray("Converged").GetValue(0) == 1
      and sfd.GetArray("RelativeError").GetValue(0) <= 1e-10,
      "Spherical OT Solver: converged, RelativeError <= 1e-10")
scell = sout.GetPointData().GetArray("CellMass")
total = math.fsum(scell.GetValue(i) for i in range(sphere_n)) if scell else 0.0
check(sout.GetNumberOfPoints() == sphere_n and sout.GetNumberOfPolys() == 2 * sphere_n - 4
      and abs(total - 4.0 * math.pi) <= 1e-12 * 4.0 * math.pi,
      f"Spherical OT Solver: {sphere_n} Diracs, 2n - 4 triangles, CellMass sums to 4 pi ({total!r})")
check(sfd.GetArray("LargestTransportDegrees") is not None, "field data LargestTransportDegrees")
sdiagram = servermanager.Fetch(spherical, idx=1)
sids = sdiagram.GetCellData().GetArray("DiracId")
check(sdiagram.GetNumberOfCells() == sphere_n and sids is not None
      and sorted(int(sids.GetValue(c)) for c in range(sphere_n)) == list(range(sphere_n)),
      "Spherical OT Solver Power Diagram: one polygon per Dirac, DiracId covers every Dirac")
check(servermanager.Fetch(spherical, idx=2).GetNumberOfCells() == sphere_n
      and servermanager.Fetch(spherical, idx=3).GetNumberOfCells() == 2 * sphere_n - 4,
      "Spherical OT Solver: Polytope has one face per Dirac, Convex Hull 2n - 4 triangles")
print(f"spherical: {int(sfd.GetArray('Iterations').GetValue(0))} Newton iterations, relative "
      f"error {sfd.GetArray('RelativeError').GetValue(0):.3e}", flush=True)
spherical.MaximumNumberOfIterations = 1
spherical.UpdatePipeline()
check(servermanager.Fetch(spherical).GetFieldData().GetArray("Converged").GetValue(0) == 0,
      "Spherical OT Solver, MaximumNumberOfIterations = 1: Converged == 0")
spherical.MaximumNumberOfIterations = 200

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

# ---- Adaptive Density Sampler on a triangulated unit disk (rings of 6k points, written by this
# test) with a smooth AreaDensity per point and per triangle; then the OT solver on its samples.
rings = 8
disk_points = vtkPoints()
disk_points.SetDataTypeToDouble()
disk_points.InsertNextPoint(0.0, 0.0, 0.0)
disk_triangles = vtkCellArray()
inner, inner_start = [0], 0.0
for k in range(1, rings + 1):
    count, start = 6 * k, (k % 2) * math.pi / (6 * k)
    outer = [disk_points.InsertNextPoint(k / rings * math.cos(start + 2 * math.pi * j / count),
                                         k / rings * math.sin(start + 2 * math.pi * j / count), 0.0)
             for j in range(count)]
    ni, i, o = len(inner), 0, 0
    while (ni > 1 and i < ni) or o < count:  # zip the two rings in order of angle
        if o < count and (ni == 1 or i == ni or start + 2 * math.pi * (o + 1) / count
                          < inner_start + 2 * math.pi * (i + 1) / ni):
            disk_triangles.InsertNextCell(3, (inner[i % ni], outer[o], outer[(o + 1) % count]))
            o += 1
        else:
            disk_triangles.InsertNextCell(3, (inner[i % ni], outer[o % count], inner[(i + 1) % ni]))
            i += 1
    inner, inner_start = outer, start
disk_domain = vtkPolyData()
disk_domain.SetPoints(disk_points)
disk_domain.SetPolys(disk_triangles)


def disk_density(x, y):
    return 1.0 + 8.0 * math.exp(-((x - 0.3) ** 2 + y * y) / 0.1)


point_density, cell_density = vtkDoubleArray(), vtkDoubleArray()
point_density.SetName("AreaDensity")
cell_density.SetName("AreaDensity")
for i in range(disk_points.GetNumberOfPoints()):
    point_density.InsertNextValue(disk_density(*disk_points.GetPoint(i)[:2]))
for t in range(disk_domain.GetNumberOfCells()):
    corners = [disk_points.GetPoint(disk_domain.GetCell(t).GetPointId(q)) for q in range(3)]
    cell_density.InsertNextValue(disk_density(sum(p[0] for p in corners) / 3,
                                              sum(p[1] for p in corners) / 3))
disk_domain.GetPointData().AddArray(point_density)
disk_domain.GetCellData().AddArray(cell_density)
disk_vtp = os.path.join(work_dir, "disk.vtp")
writer.SetFileName(disk_vtp)
writer.SetInputData(disk_domain)
check(writer.Write() == 1, f"wrote {disk_vtp}")

check("AdaptiveDensitySampler" in globals(), "LoadPlugin defines AdaptiveDensitySampler")
disk_reader = XMLPolyDataReader(FileName=[disk_vtp])
disk_reader.UpdatePipeline()  # as in the GUI: the array list needs the input's arrays
sampler = AdaptiveDensitySampler(Input=disk_reader)
check(sampler.SMProxy.GetXMLLabel() == "Adaptive Density Sampler", "label 'Adaptive Density Sampler'")
hints = sampler.SMProxy.GetHints()
menu = hints.FindNestedElementByName("ShowInMenu") if hints else None
check(menu is not None and menu.GetAttribute("category") == "Optimal Transport",
      "Adaptive Density Sampler is in the menu category 'Optimal Transport'")
check(list(sampler.Density)[-1] == "AreaDensity",
      f"the density defaults to AreaDensity ({list(sampler.Density)})")
check(sampler.NumberOfSamples == 1000 and sampler.SamplingMode == "Adaptive"
      and abs(sampler.MinimumAngle - 30.0) < 1e-12 and sampler.SizeRule == "R * sqrt(density)",
      "NumberOfSamples, SamplingMode, MinimumAngle and SizeRule defaults")
sampler.NumberOfSamples = 300
for association in ("POINTS", "CELLS"):
    sampler.Density = [association, "AreaDensity"]
    sampler.UpdatePipeline()
    samples = servermanager.Fetch(sampler)
    count = samples.GetNumberOfPoints()
    mass = samples.GetPointData().GetArray("Mass")
    total = math.fsum(mass.GetValue(i) for i in range(count)) if mass else 0.0
    check(mass is not None and abs(total - math.pi) <= 1e-9 * math.pi,
          f"{association} AreaDensity: Mass sums to pi ({total!r})")
    number = samples.GetFieldData().GetArray("NumberOfSamples")
    check(number is not None and number.GetValue(0) == count and abs(count - 300) <= 30,
          f"{association} AreaDensity: field data NumberOfSamples = {count}, within 10% of 300")
    cv = samples.GetFieldData().GetArray("MassCoefficientOfVariation")
    print(f"sampler ({association}): {count} samples, mass CV {cv.GetValue(0) if cv else -1:.3f}",
          flush=True)
sampler.Density = ["POINTS", "AreaDensity"]
sampler.SamplingMode = "Mesh Vertices"
sampler.UpdatePipeline()
check(servermanager.Fetch(sampler).GetNumberOfPoints() == disk_points.GetNumberOfPoints(),
      "SamplingMode 'Mesh Vertices': the disk's own points")
sampler.SamplingMode = "Adaptive"
chained = SemiDiscreteOTSolver(Diracs=sampler)
chained.UpdatePipeline()
converged = servermanager.Fetch(chained).GetFieldData().GetArray("Converged")
check(converged is not None and converged.GetValue(0) == 1,
      "the OT solver converges on the sampler's output")

# ---- A target support with a hole, from ParaView's own Disk source (an annulus of quads),
# triangulated, with a Calculator's uniform AreaDensity: the sampler samples it, the solver
# transports the unit disk onto it, and "Discontinuities" (port 4) holds the singularity set,
# which for an annulus is a point-like set at the centre.
annulus = Calculator(Input=Triangulate(Input=Disk(InnerRadius=0.4, OuterRadius=1.0,
                                                  RadialResolution=8,
                                                  CircumferentialResolution=96)))
annulus.ResultArrayName = "AreaDensity"
annulus.Function = "1"
annulus_samples = AdaptiveDensitySampler(Input=annulus)
annulus_samples.NumberOfSamples = 500
onto_annulus = SemiDiscreteOTSolver(Diracs=annulus_samples)
onto_annulus.UpdatePipeline()
fd = servermanager.Fetch(onto_annulus).GetFieldData()
check(fd.GetArray("Converged") is not None and fd.GetArray("Converged").GetValue(0) == 1
      and fd.GetArray("RelativeError").GetValue(0) <= 1e-10,
      "annulus: the solver converges to 1e-10 on the samples of a support with a hole")
jumps = servermanager.Fetch(onto_annulus, idx=4)
reach = max((math.hypot(*jumps.GetPoint(i)[:2]) for i in range(jumps.GetNumberOfPoints())),
            default=-1.0)
check(jumps.GetNumberOfCells() > 0 and jumps.GetCellData().GetArray("JumpLength") is not None
      and 0.0 <= reach <= 0.05,
      f"annulus: a singularity set with JumpLength, within 0.05 of the centre ({reach:.4f})")

# ---- Area-Preserving Parameterization of a bumpy plane: all three ports, the figures.
check("AreaPreservingParameterization" in globals(),
      "LoadPlugin defines AreaPreservingParameterization")
bumps = Calculator(Input=Triangulate(Input=Plane(XResolution=30, YResolution=30)))
bumps.CoordinateResults = 1
bumps.Function = "coordsX*iHat + coordsY*jHat + 0.4*exp(-20*((coordsX-0.1)^2+coordsY^2))*kHat"
param = AreaPreservingParameterization(Input=bumps)
check(param.SMProxy.GetXMLLabel() == "Area-Preserving Parameterization",
      "label 'Area-Preserving Parameterization'")
hints = param.SMProxy.GetHints()
menu = hints.FindNestedElementByName("ShowInMenu") if hints else None
check(menu is not None and menu.GetAttribute("category") == "Optimal Transport",
      "Area-Preserving Parameterization is in the menu category 'Optimal Transport'")
check(param.NumberOfSamples == 0 and param.Tolerance == 1e-10 and param.AreaCorrection == 1,
      "pass-through defaults: NumberOfSamples 0 (automatic), Tolerance 1e-10, AreaCorrection on")
param.NumberOfSamples = 1500
param.UpdatePipeline()
surface = servermanager.Fetch(param, idx=0)
flat = servermanager.Fetch(param, idx=1)
table = servermanager.Fetch(param, idx=2)
fd = surface.GetFieldData()
check(surface.GetNumberOfPoints() == 31 * 31 and flat.GetNumberOfPoints() == 31 * 31,
      "every point on ports 0 and 1")
check(fd.GetArray("Converged").GetValue(0) == 1 and fd.GetArray("FlippedTriangles").GetValue(0) == 0,
      "converged, no flipped triangle")
check(fd.GetArray("MeanAbsLogAreaRatio").GetValue(0) <= 0.03,
      f"area-preserving: mean |log area ratio| {fd.GetArray('MeanAbsLogAreaRatio').GetValue(0):.4f}")
tcoords = surface.GetPointData().GetTCoords()
check(tcoords is not None and tcoords.GetName() == "AreaPreservingCoordinates",
      "texture coordinates AreaPreservingCoordinates")
# Export for texture workflows: Save Data as .obj keeps the texture coordinates; read back by
# the OTParam Mesh Reader.
exported = os.path.join(work_dir, "mapped.obj")
SaveData(exported, proxy=param)
back = OTParamMeshReader(FileName=exported)
back.UpdatePipeline()
back_data = servermanager.Fetch(back)
back_tcoords = back_data.GetPointData().GetTCoords()
check(back_data.GetNumberOfPoints() == surface.GetNumberOfPoints() and back_tcoords is not None
      and max(abs(a - b) for i in range(surface.GetNumberOfPoints())
              for a, b in zip(tcoords.GetTuple2(i), back_tcoords.GetTuple2(i))) <= 1e-12,
      "SaveData .obj keeps the texture coordinates (read back to 1e-12)")
Delete(back)
check(table.IsA("vtkTable") and table.GetNumberOfRows() == 50
      and table.GetColumnByName("AreaPreservingLogAreaRatio") is not None,
      "port 2: the histogram table")


def checkerboard_shown_on_apply(source, label):
    """What Apply shows (the GUI's pqApplyBehavior calls ShowInPreferredView on every port):
    the surface coloured by its Checkerboard cell scalars, the domain mesh held back, the
    histograms in a bar chart. The two colours cover equal shares of an area-preserving map."""
    controller = servermanager.vtkSMParaViewPipelineControllerWithRendering()
    render_view = CreateView("RenderView")
    shown = [controller.ShowInPreferredView(source.SMProxy, port, render_view.SMProxy)
             for port in range(3)]
    check(shown[0] is not None and shown[0].GetXMLName() == "RenderView" and shown[1] is None
          and shown[2] is not None and shown[2].GetXMLName() == "XYBarChartView",
          f"{label}: Apply shows the surface, holds back the domain mesh, charts the histograms")
    display = GetDisplayProperties(source, render_view)
    check(list(display.ColorArrayName) == ["CELLS", "Checkerboard"],
          f"{label}: the surface comes up coloured by Checkerboard ({list(display.ColorArrayName)})")
    mapped_surface = servermanager.Fetch(source, idx=0)
    checker = mapped_surface.GetCellData().GetScalars()
    area = [0.0, 0.0]
    for t in range(mapped_surface.GetNumberOfCells()):
        area[int(checker.GetValue(t))] += mapped_surface.GetCell(t).ComputeArea()
    share = area[1] / sum(area)
    print(f"{label}: Checkerboard 1 covers {share:.4f} of the surface", flush=True)
    check(checker.GetName() == "Checkerboard" and abs(share - 0.5) <= 0.03,
          f"{label}: the checkerboard's two colours cover equal areas ({share:.3f} of the surface)")
    for view in (render_view, shown[2]):
        Delete(servermanager._getPyProxy(view) if view is shown[2] else view)


# In the GUI, views made here would split its layout and move the screenshots' framing; the
# GUI part below checks what Apply shows on a screenshot instead.
gui = os.environ.get("OTPARAM_SCREENSHOT") == "1"
if not gui:
    checkerboard_shown_on_apply(param, "bumpy plane")

# ---- The mesh reader: OpenDataFile picks it for .off (ParaView 5.11 has no OFF reader) and
# for .obj (its own OBJ reader crashes on face_dense_gpp_5k.obj: texture indices, no vt lines).
if os.environ.get("OTPARAM_SHARED_DATA_DIR"):
    meshes = os.path.join(os.environ["OTPARAM_SHARED_DATA_DIR"], "meshes")
    for mesh, points, triangles in (("hand_choi_53k.off", 53054, 105860),
                                    ("face_dense_gpp_5k.obj", 5101, 10000)):
        opened = OpenDataFile(os.path.join(meshes, mesh))
        check(opened is not None and opened.GetXMLName() == "OTParamMeshReader",
              f"OpenDataFile picks the OTParam Mesh Reader for {mesh}")
        named = OTParamMeshReader(FileName=os.path.join(meshes, mesh))
        for proxy in (opened, named):
            if proxy is None:
                continue
            proxy.UpdatePipeline()
            info = proxy.GetDataInformation()
            check(info.GetNumberOfPoints() == points and info.GetNumberOfCells() == triangles,
                  f"{mesh}: {info.GetNumberOfPoints()} points, {info.GetNumberOfCells()} "
                  f"triangles (expected {points}, {triangles})")
            Delete(proxy)

# ---- A real scan with holes (the shared bunny: 4 holes besides the opening at its base)
# through Area-Preserving Parameterization with default properties.
if os.environ.get("OTPARAM_SHARED_DATA_DIR"):
    bunny_reader = OpenDataFile(os.path.join(os.environ["OTPARAM_SHARED_DATA_DIR"], "meshes",
                                             "bunny_holes_35k.obj"))
    bunny = AreaPreservingParameterization(Input=bunny_reader)
    check(bunny.FillHoles == 1, "FillHoles is on by default")
    bunny.UpdatePipeline()
    mapped = servermanager.Fetch(bunny, idx=0)
    read = servermanager.Fetch(bunny_reader)
    bfd = mapped.GetFieldData()
    figure = {name: bfd.GetArray(name).GetValue(0) if bfd.GetArray(name) else None
              for name in ("FilledHoles", "Converged", "FlippedTriangles", "MeanAbsLogAreaRatio")}
    print(f"bunny_holes_35k.obj: {figure}", flush=True)
    check(mapped.GetNumberOfPoints() == read.GetNumberOfPoints()
          and mapped.GetNumberOfCells() == read.GetNumberOfCells(),
          "bunny: the output has the input's points and triangles")
    check(figure["FilledHoles"] == 4 and figure["Converged"] == 1
          and figure["FlippedTriangles"] == 0 and figure["MeanAbsLogAreaRatio"] <= 0.03,
          f"bunny: 4 holes filled, converged, no flip, area-preserving ({figure})")
    Delete(bunny)
    Delete(bunny_reader)

# ---- A closed scan with small holes (three triangles cut out of the shared spot, written as an
# OBJ file): Domain Automatic takes it to the sphere with the holes filled, and Conformal
# Sphere Map fills them too (Fill Holes on by default); both keep the input's points and cells.
if os.environ.get("OTPARAM_SHARED_DATA_DIR"):
    spot_lines = open(os.path.join(os.environ["OTPARAM_SHARED_DATA_DIR"], "meshes",
                                   "spot_closed_3k.obj")).read().splitlines()
    faces = [k for k, line in enumerate(spot_lines) if line.startswith("f ")]
    holed_path = os.path.join(work_dir, "spot_3_holes.obj")
    cut = {faces[10], faces[500], faces[2000]}
    with open(holed_path, "w") as holed_file:
        holed_file.write("\n".join(line for k, line in enumerate(spot_lines) if k not in cut) + "\n")
    holed_reader = OpenDataFile(holed_path)
    read = servermanager.Fetch(holed_reader)
    for proxy in (AreaPreservingParameterization(Input=holed_reader),
                  ConformalSphereMap(Input=holed_reader)):
        check(proxy.FillHoles == 1, "FillHoles is on by default")
        proxy.UpdatePipeline()
        mapped = servermanager.Fetch(proxy, idx=0)
        hfd = mapped.GetFieldData()
        figure = {name: hfd.GetArray(name).GetValue(0) if hfd.GetArray(name) else None
                  for name in ("FilledHoles", "Domain", "FlippedTriangles")}
        print(f"spot with 3 holes, {proxy.GetXMLLabel()}: {figure}", flush=True)
        check(mapped.GetNumberOfPoints() == read.GetNumberOfPoints()
              and mapped.GetNumberOfCells() == read.GetNumberOfCells()
              and figure["FilledHoles"] == 3 and figure["FlippedTriangles"] == 0
              and figure["Domain"] in (None, 2),
              f"spot with 3 holes, {proxy.GetXMLLabel()}: filled, on the sphere, the input's "
              f"points and cells ({figure})")
        Delete(proxy)
    Delete(holed_reader)

# ---- A closed surface: Domain Automatic (the default) maps it onto the unit sphere.
closed = Triangulate(Input=Sphere(ThetaResolution=16, PhiResolution=12))
on_sphere = AreaPreservingParameterization(Input=closed)
check(on_sphere.Domain in (0, "Automatic"),
      f"Area-Preserving Parameterization: Domain defaults to Automatic ({on_sphere.Domain!r})")
on_sphere.NumberOfSamples = 500
on_sphere.UpdatePipeline()
sphere_out = servermanager.Fetch(on_sphere, idx=0)
sphere_mesh = servermanager.Fetch(on_sphere, idx=1)
sfigure = {name: sphere_out.GetFieldData().GetArray(name).GetValue(0)
           for name in ("Domain", "Converged", "FlippedTriangles", "RelativeError")
           if sphere_out.GetFieldData().GetArray(name) is not None}
check(sfigure.get("Domain") == 2 and sfigure.get("Converged") == 1
      and sfigure.get("FlippedTriangles") == 0,
      f"closed surface, Domain Automatic: the sphere path, converged, no flip ({sfigure})")
sphere_radius_error = max((abs(math.sqrt(sum(c * c for c in sphere_mesh.GetPoint(i))) - 1.0)
                           for i in range(sphere_mesh.GetNumberOfPoints())), default=math.inf)
check(sphere_mesh.GetNumberOfPoints() == sphere_out.GetNumberOfPoints()
      and sphere_radius_error <= 1e-12,
      f"closed surface: port 1 on the unit sphere ({sphere_radius_error:.1e})")
sphere_tcoords = sphere_out.GetPointData().GetTCoords()
check(sphere_tcoords is not None and sphere_tcoords.GetName() == "SphericalTextureCoordinates"
      and sphere_out.GetPointData().GetArray("AreaPreservingCoordinates").GetNumberOfComponents()
      == 3, "closed surface: longitude/latitude texture coordinates, 3D coordinates")

if not gui:
    checkerboard_shown_on_apply(on_sphere, "closed surface")

# ---- Conformal Sphere Map on the same closed surface, and the sphere chain after it.
check("ConformalSphereMap" in globals(), "LoadPlugin defines ConformalSphereMap")
sphere_map = ConformalSphereMap(Input=closed)
check(sphere_map.SMProxy.GetXMLLabel() == "Conformal Sphere Map", "label 'Conformal Sphere Map'")
hints = sphere_map.SMProxy.GetHints()
menu = hints.FindNestedElementByName("ShowInMenu") if hints else None
check(menu is not None and menu.GetAttribute("category") == "Optimal Transport",
      "Conformal Sphere Map is in the menu category 'Optimal Transport'")
check(sphere_map.PunctureTriangleId == -1 and sphere_map.MaximumBalanceIterations == 100
      and abs(sphere_map.BalanceTolerance - 1e-10) < 1e-25,
      "Conformal Sphere Map defaults: PunctureTriangleId -1, BalanceTolerance 1e-10, "
      "MaximumBalanceIterations 100")
sphere_map.UpdatePipeline()
mapped = servermanager.Fetch(sphere_map)
mfd = mapped.GetFieldData()
check(mapped.GetNumberOfPoints() == servermanager.Fetch(closed).GetNumberOfPoints()
      and mfd.GetArray("FlippedTriangles") is not None
      and mfd.GetArray("FlippedTriangles").GetValue(0) == 0
      and mfd.GetArray("MaximumRadiusError").GetValue(0) <= 1e-12,
      "Conformal Sphere Map: every point on the unit sphere, no flipped triangle")
check(mapped.GetPointData().GetArray("AreaDensity") is not None
      and mapped.GetCellData().GetArray("AreaDensity") is not None
      and mfd.GetArray("MeanAngleDistortion") is not None
      and mfd.GetArray("MaximumAngleDistortion") is not None,
      "Conformal Sphere Map: AreaDensity per point and cell, angle distortion figures")
sphere_samples = AdaptiveDensitySampler(Input=sphere_map)
sphere_samples.Density = ["CELLS", "AreaDensity"]
sphere_samples.NumberOfSamples = 400
sphere_ot = SphericalOTSolver(Diracs=sphere_samples)
sphere_ot.UpdatePipeline()
drawn = servermanager.Fetch(sphere_samples)
drawn_mass = drawn.GetPointData().GetArray("Mass")
mass_sum = math.fsum(drawn_mass.GetValue(i) for i in range(drawn_mass.GetNumberOfTuples())) \
    if drawn_mass else 0.0
check(drawn.GetNumberOfPoints() > 300 and abs(mass_sum - 4 * math.pi) <= 1e-12,
      f"Adaptive Density Sampler on the sphere: Mass sums to 4 pi ({mass_sum!r})")
ot_fd = servermanager.Fetch(sphere_ot).GetFieldData()
check(ot_fd.GetArray("Converged") is not None and ot_fd.GetArray("Converged").GetValue(0) == 1
      and ot_fd.GetArray("RelativeError").GetValue(0) <= 1e-10,
      "Spherical OT Solver on the sphere samples: converged to 1e-10")

# ---- Bad input in a ParaView pipeline: a closed surface with Domain Disk. The filter's error
# reaches the output window (ParaView's Output Messages), the outputs stay empty, and the same
# filter works once it gets a disk-like surface.
from vtkmodules.vtkCommonCore import vtkCommand, vtkOutputWindow  # noqa: E402
messages = []
output_window = vtkOutputWindow.GetInstance()


def record_error(obj, event, text):
    messages.append(text)


record_error.CallDataType = "string0"  # Python observers get the text only when typed
observer = output_window.AddObserver(vtkCommand.ErrorEvent, record_error)
broken = AreaPreservingParameterization(Input=closed)
broken.NumberOfSamples = 500
broken.Domain = "Disk"
broken.UpdatePipeline()
check(servermanager.Fetch(broken, idx=0).GetNumberOfPoints() == 0
      and servermanager.Fetch(broken, idx=2).GetNumberOfRows() == 0,
      "closed surface, Domain Disk: the outputs stay empty")
check(any("conformal map:" in m and "closed" in m for m in messages),
      f"closed surface, Domain Disk: the filter's error reaches the output window "
      f"({messages[:1]})")
broken.Input = bumps
broken.UpdatePipeline()
check(servermanager.Fetch(broken, idx=0).GetNumberOfPoints() == 31 * 31,
      "the same filter works once given a disk-like surface")

# The Conformal Sphere Map on the (open) bumpy plane: its error names the boundary.
messages.clear()
open_map = ConformalSphereMap(Input=bumps)
open_map.UpdatePipeline()
check(servermanager.Fetch(open_map).GetNumberOfPoints() == 0,
      "Conformal Sphere Map, open surface: the output stays empty")
check(any("closed" in m and "boundary" in m for m in messages),
      f"Conformal Sphere Map, open surface: the error reaches the output window "
      f"({messages[:1]})")

# The Spherical OT Solver on the plane's points (not on the sphere): its error names them.
messages.clear()
off_sphere = SphericalOTSolver(Diracs=reader)
off_sphere.UpdatePipeline()
check(servermanager.Fetch(off_sphere).GetNumberOfPoints() == 0,
      "Spherical OT Solver, Diracs off the sphere: the outputs stay empty")
check(any("not on the unit sphere" in m for m in messages),
      f"Spherical OT Solver, Diracs off the sphere: the error reaches the output window "
      f"({messages[:1]})")
output_window.RemoveObserver(observer)

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

    def distinct_colors(path):
        image = vtkPNGReader()
        image.SetFileName(path)
        image.Update()
        pixels = vtk_to_numpy(image.GetOutput().GetPointData().GetScalars())
        return len(numpy.unique(pixels[:, :3], axis=0))

    colors = distinct_colors(png)
    check(colors >= n, f"screenshot {png} shows the colored cells ({colors} distinct colors)")

    # Area-Preserving Parameterization of a shared face in the GUI: the surface textured with
    # circles through its texture coordinates (the area-preserving ones), against a baseline;
    # and the histograms in a bar chart view.
    sys.path.insert(0, os.environ["OTPARAM_EXAMPLES_DIR"])
    from otparam_example_utils import circle_image
    from vtkmodules.vtkIOImage import vtkPNGWriter
    texture_png = os.path.join(work_dir, "circles_texture.png")
    writer = vtkPNGWriter()
    writer.SetFileName(texture_png)
    writer.SetInputData(circle_image(512))
    writer.Write()
    face_file = os.path.join(os.environ["OTPARAM_SHARED_DATA_DIR"], "meshes",
                             "face_choi_bff_17k.obj")
    face = AreaPreservingParameterization(Input=Triangulate(Input=OpenDataFile(face_file)))
    for representation in view.Representations:  # every port shown so far
        representation.Visibility = 0
    display = Show(face, view)
    display.Texture = CreateTexture(texture_png)
    display.RepeatTextures = 1
    display.ColorArrayName = [None, ""]
    def face_screenshot(face_view, name):
        face_view.CameraFocalPoint = [0.0, 0.0, 0.0]
        face_view.CameraPosition = [0.0, 0.0, 1.0]
        face_view.CameraViewUp = [0.0, 1.0, 0.0]
        face_view.ResetCamera()
        Render(face_view)
        png = os.path.join(work_dir, name)
        SaveScreenshot(png, face_view, ImageResolution=[500, 500])
        return png

    face_png = face_screenshot(view, "area_preserving_face.png")
    baseline = os.path.join(os.environ["OTPARAM_BASELINE_DIR"], "TestPluginGUI_area_preserving_face.png")

    def rgb(path):
        image = vtkPNGReader()
        image.SetFileName(path)
        image.Update()
        return vtk_to_numpy(image.GetOutput().GetPointData().GetScalars())[:, :3].astype(int)

    if not os.path.exists(baseline):
        check(False, f"no baseline {baseline}: look at {face_png} and commit it as the baseline")
    else:
        # vtkImageDifference's shift search and averaging forgive circles moved by a few
        # pixels (measured: thresholded error 0 with the area correction off); count the
        # pixels that changed colour instead: 1.5% with the correction off, 0 run to run.
        current, expected = rgb(face_png), rgb(baseline)
        changed = (numpy.abs(current - expected).max(axis=1) > 64).mean() \
            if current.shape == expected.shape else 1.0
        check(changed <= 0.005,
              f"{face_png}: {100 * changed:.2f}% of the pixels differ from {baseline} (> 0.5%)")
    # What Apply shows, without any hand-made texture: the face coloured by its checkerboard.
    # Both colours of the default map (Cool to Warm: blue for 0, red for 1) must fill it.
    apply_view = CreateView("RenderView")
    AssignViewToLayout(view=apply_view)
    apply_view.OrientationAxesVisibility = 0
    servermanager.vtkSMParaViewPipelineControllerWithRendering().ShowInPreferredView(
        face.SMProxy, 0, apply_view.SMProxy)
    apply_png = face_screenshot(apply_view, "apply_face_checkerboard.png")
    pixels = rgb(apply_png)
    red = (pixels[:, 0] > pixels[:, 2] + 60).mean()
    blue = (pixels[:, 2] > pixels[:, 0] + 60).mean()
    print(f"{apply_png}: {100 * red:.1f}% red, {100 * blue:.1f}% blue pixels", flush=True)
    check(red >= 0.05 and blue >= 0.05,
          f"{apply_png}: the face shows its checkerboard ({100 * red:.1f}% red, "
          f"{100 * blue:.1f}% blue pixels)")
    chart = CreateView("XYBarChartView")
    AssignViewToLayout(view=chart)
    bars = Show(OutputPort(face, 2), chart)
    bars.UseIndexForXAxis = 0
    bars.XArrayName = "AreaPreservingLogAreaRatioBinCenter"
    bars.SeriesVisibility = ["AreaPreservingLogAreaRatio"]
    chart_png = os.path.join(work_dir, "histograms.png")
    SaveScreenshot(chart_png, chart, ImageResolution=[600, 300])
    check(distinct_colors(chart_png) >= 3, f"{chart_png} shows the bar chart")

if failures:
    print(f"{len(failures)} check(s) failed", flush=True)
    sys.exit(1)
with open(passed_marker, "w") as f:
    f.write("ok\n")
print("all checks passed", flush=True)
