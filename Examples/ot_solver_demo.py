#!/usr/bin/python3
"""Semi-discrete optimal transport from the uniform unit disk to 2000 Diracs whose masses follow
a Gaussian mixture of contrast 1e4 (largest mass / smallest mass), with vtkSemiDiscreteOTSolver.

Prints the Newton iterations as they run, writes every output of the filter as .vtp and renders
the power diagram (cells colored by DiracId) over the weighted Delaunay triangulation as a PNG.

    PYTHONPATH=<build>/lib/python3/dist-packages /usr/bin/python3 Examples/ot_solver_demo.py [outdir]

Rendering needs an X server (Debian's VTK has no EGL/OSMesa): without DISPLAY, the script runs
itself again under `xvfb-run -a`.
"""

import argparse
import math
import os
import random
import sys
import time

from otparam_example_utils import ensure_display, save_png


def parse_args():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("output", nargs="?", default="otparam-output",
                        help="output directory (default: ./otparam-output)")
    parser.add_argument("-n", "--diracs", type=int, default=2000, help="number of Diracs")
    parser.add_argument("--contrast", type=float, default=1e4,
                        help="largest / smallest Dirac mass (default 1e4)")
    parser.add_argument("--seed", type=int, default=2024, help="random seed")
    parser.add_argument("--tolerance", type=float, default=1e-10, help="relative mass error")
    parser.add_argument("--size", type=int, default=1200, help="picture size in pixels")
    parser.add_argument("--no-picture", action="store_true", help="skip the PNG")
    return parser.parse_args()


def make_diracs(n, contrast, seed):
    """n uniform random points in the disk of radius 0.98, masses from a Gaussian mixture
    rescaled so that max / min = contrast."""
    from vtkmodules.vtkCommonCore import vtkDoubleArray, vtkPoints
    from vtkmodules.vtkCommonDataModel import vtkPolyData

    rng = random.Random(seed)
    bumps = [((0.45, 0.2), 0.12, 1.0), ((-0.35, 0.4), 0.2, 0.6), ((-0.1, -0.5), 0.08, 0.8)]
    xy, density = [], []
    while len(xy) < n:
        x, y = rng.uniform(-0.98, 0.98), rng.uniform(-0.98, 0.98)
        if x * x + y * y >= 0.98 * 0.98:
            continue
        xy.append((x, y))
        density.append(sum(w * math.exp(-((x - cx) ** 2 + (y - cy) ** 2) / (2 * s * s))
                           for (cx, cy), s, w in bumps))
    low, high = min(density), max(density)
    # Affine map of the mixture onto [1, contrast]: exactly the requested contrast.
    masses = [1.0 + (contrast - 1.0) * (d - low) / (high - low) for d in density]

    points = vtkPoints()
    points.SetDataTypeToDouble()
    mass = vtkDoubleArray()
    mass.SetName("Mass")
    for (x, y), m in zip(xy, masses):
        points.InsertNextPoint(x, y, 0.0)
        mass.InsertNextValue(m)
    diracs = vtkPolyData()
    diracs.SetPoints(points)
    diracs.GetPointData().AddArray(mass)
    return diracs


def write_outputs(solver, directory):
    from vtkmodules.vtkIOXML import vtkXMLPolyDataWriter

    names = ["diracs", "power_diagram", "brenier_potential", "legendre_dual", "discontinuities"]
    files = []
    for port, name in enumerate(names):
        path = os.path.join(directory, name + ".vtp")
        writer = vtkXMLPolyDataWriter()
        writer.SetFileName(path)
        writer.SetInputData(solver.GetOutput(port))
        # Inline data: Debian 12's patched expat cannot read VTK's appended-data section.
        writer.SetDataModeToBinary()
        if writer.Write() != 1:
            sys.exit(f"could not write {path}")
        files.append(path)
    return files


def render_png(solver, path, size):
    import vtkmodules.vtkRenderingOpenGL2  # noqa: F401  (registers the OpenGL render window)
    from vtkmodules.vtkCommonCore import vtkLookupTable
    from vtkmodules.vtkRenderingCore import vtkActor, vtkPolyDataMapper, vtkRenderer, vtkRenderWindow

    diagram = solver.GetOutput(1)
    triangulation = solver.GetOutput(0)
    n = triangulation.GetNumberOfPoints()

    # One random color per Dirac: neighbouring cells rarely share a color, unlike a smooth map.
    rng = random.Random(1)
    lut = vtkLookupTable()
    lut.SetNumberOfTableValues(n)
    lut.SetTableRange(0, n - 1)
    for i in range(n):
        hue, saturation, value = rng.random(), 0.35 + 0.4 * rng.random(), 0.75 + 0.25 * rng.random()
        lut.SetTableValue(i, *hsv_to_rgb(hue, saturation, value), 1.0)
    lut.Build()

    cells_mapper = vtkPolyDataMapper()
    cells_mapper.SetInputData(diagram)
    cells_mapper.SetScalarModeToUseCellFieldData()
    cells_mapper.SelectColorArray("DiracId")
    cells_mapper.SetLookupTable(lut)
    cells_mapper.UseLookupTableScalarRangeOn()
    cells_mapper.SetResolveCoincidentTopologyToPolygonOffset()
    cells = vtkActor()
    cells.SetMapper(cells_mapper)

    edges_mapper = vtkPolyDataMapper()
    edges_mapper.SetInputData(triangulation)
    edges_mapper.ScalarVisibilityOff()
    edges = vtkActor()
    edges.SetMapper(edges_mapper)
    edges.GetProperty().SetRepresentationToWireframe()
    edges.GetProperty().SetColor(0.1, 0.1, 0.1)
    edges.GetProperty().SetLineWidth(1.0)
    edges.GetProperty().SetOpacity(0.35)

    renderer = vtkRenderer()
    renderer.SetBackground(1.0, 1.0, 1.0)
    renderer.AddActor(cells)
    renderer.AddActor(edges)
    renderer.ResetCamera()
    renderer.GetActiveCamera().Zoom(1.35)

    window = vtkRenderWindow()
    window.SetOffScreenRendering(1)
    window.SetMultiSamples(0)
    window.SetSize(size, size)
    window.AddRenderer(renderer)
    window.Render()
    if path is not None:  # None: for a regression test, which compares the window
        save_png(window, path)
    return window


def hsv_to_rgb(h, s, v):
    import colorsys
    return colorsys.hsv_to_rgb(h, s, v)


def main():
    args = parse_args()
    ensure_display(args)

    from otparam import vtkSemiDiscreteOTSolver
    from vtkmodules.vtkCommonCore import vtkCommand

    os.makedirs(args.output, exist_ok=True)
    diracs = make_diracs(args.diracs, args.contrast, args.seed)
    print(f"{args.diracs} Diracs in the unit disk, Gaussian-mixture masses of contrast "
          f"{args.contrast:g}; uniform unit disk source", flush=True)

    solver = vtkSemiDiscreteOTSolver()
    solver.SetInputData(0, diracs)
    solver.SetTolerance(args.tolerance)

    last = [None]

    def report(caller, _event):
        # The filter sets its text once per Newton iteration; other progress events repeat it.
        text = caller.GetProgressText()
        if text and text != last[0]:
            last[0] = text
            print(f"  {text}  (progress {caller.GetProgress():.0%})", flush=True)

    solver.AddObserver(vtkCommand.ProgressEvent, report)
    start = time.perf_counter()
    solver.Update()
    seconds = time.perf_counter() - start

    out = solver.GetOutput(0)
    fd = out.GetFieldData()
    if fd.GetArray("Converged") is None:
        sys.exit("the solver failed (see the error above)")
    converged = fd.GetArray("Converged").GetValue(0) == 1
    cell_mass = out.GetPointData().GetArray("CellMass")
    print(f"{'converged' if converged else 'NOT converged'} in "
          f"{fd.GetArray('Iterations').GetValue(0)} Newton iterations, relative mass error "
          f"{fd.GetArray('RelativeError').GetValue(0):.2e}, {seconds:.2f} s; total cell mass "
          f"{math.fsum(cell_mass.GetValue(i) for i in range(cell_mass.GetNumberOfTuples())):.15f}"
          f" (pi = {math.pi:.15f})")
    stages = ["Triangulation", "Integration", "Assembly", "Solve", "Output"]
    print("seconds per stage: " + ", ".join(
        f"{s.lower()} {fd.GetArray('Seconds' + s).GetValue(0):.3f}" for s in stages))

    for path in write_outputs(solver, args.output):
        print("wrote", path)
    if not args.no_picture:
        png = os.path.join(args.output, "power_diagram.png")
        render_png(solver, png, args.size)
        print("wrote", png)
    return 0 if converged else 1


if __name__ == "__main__":
    sys.exit(main())
