#!/usr/bin/python3
"""Optimal transport from the uniform unit disk onto targets with complicated supports, and the
singularity set of the (discontinuous) transport map: the paper's Fig. 13 analogue.

For each target (two half-disks facing away from each other, an annulus, a thick letter C;
generated here, uniform density), the Adaptive Density Sampler samples the support, the
Semi-Discrete OT Solver transports the unit disk onto the samples, and its "Discontinuities"
output (port 4) holds the power edges across which the map jumps. Each figure shows the source
disk with every power cell coloured by where its mass goes (hue: the target point's angle,
paleness: its distance from the centre) and the singularity curves in black (left), beside the
target support with its samples in the same colours (right).

    PYTHONPATH=<build>/lib/python3/dist-packages /usr/bin/python3 Examples/complicated_supports.py [outdir]

Writes supports_<shape>.png and the sampler's and solver's outputs as .vtp. Rendering needs an
X server (Debian's VTK has no EGL/OSMesa): without DISPLAY, the script runs itself again under
`xvfb-run -a`.
"""

import argparse
import colorsys
import math
import os
import sys

from otparam_example_utils import annulus, ensure_display, letter_c, save_png, two_half_disks

SHAPES = {
    "two_half_disks": lambda: two_half_disks(gap=0.2, radius=0.8),
    "annulus": lambda: annulus(0.4, 1.0),
    "letter_c": letter_c,
}


def parse_args():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("output", nargs="?", default="otparam-supports",
                        help="output directory (default: ./otparam-supports)")
    parser.add_argument("-n", "--samples", type=int, default=3000, help="samples per target")
    parser.add_argument("--size", type=int, default=700, help="height of a figure in pixels")
    parser.add_argument("--no-picture", action="store_true", help="skip the PNGs")
    return parser.parse_args()


def transport_onto(shape, samples):
    """Samples the shape's support (uniform density) and transports the unit disk onto the
    samples. Returns (sampler, solver), both updated."""
    import otparam
    from vtkmodules.vtkCommonCore import vtkDoubleArray

    density = vtkDoubleArray()
    density.SetName("AreaDensity")
    density.SetNumberOfTuples(shape.GetNumberOfPoints())
    density.Fill(1.0)
    shape.GetPointData().AddArray(density)
    sampler = otparam.vtkAdaptiveDensitySampler()
    sampler.SetInputData(shape)
    sampler.SetNumberOfSamples(samples)
    solver = otparam.vtkSemiDiscreteOTSolver()
    solver.SetInputConnection(sampler.GetOutputPort())
    solver.Update()
    return sampler, solver


def target_colour(x, y):
    """Hue from the angle, paler towards the centre: neighbours in the target get similar
    colours, so a jump of the map shows as a jump of colour."""
    r, g, b = colorsys.hsv_to_rgb((math.atan2(y, x) / (2 * math.pi)) % 1.0,
                                  0.25 + 0.75 * min(1.0, math.hypot(x, y)), 0.95)
    return int(255 * r), int(255 * g), int(255 * b)


def coloured_by_target(data, diracs, use_cells):
    """A shallow copy of data with an RGB array: each cell's (DiracId) or point's Dirac colour."""
    from vtkmodules.vtkCommonCore import vtkUnsignedCharArray
    from vtkmodules.vtkCommonDataModel import vtkPolyData

    copy = vtkPolyData()
    copy.ShallowCopy(data)
    colours = vtkUnsignedCharArray()
    colours.SetName("TargetColour")
    colours.SetNumberOfComponents(3)
    if use_cells:
        ids = data.GetCellData().GetArray("DiracId")
        for c in range(data.GetNumberOfCells()):
            colours.InsertNextTuple3(*target_colour(*diracs.GetPoint(int(ids.GetValue(c)))[:2]))
        copy.GetCellData().SetScalars(colours)
    else:
        for i in range(data.GetNumberOfPoints()):
            colours.InsertNextTuple3(*target_colour(*data.GetPoint(i)[:2]))
        copy.GetPointData().SetScalars(colours)
    return copy


def render_support_figure(sampler, solver, path, size):
    """Source disk with the coloured power cells and the singularity set (left), target support
    with its samples (right). Writes the PNG unless path is None; returns the window."""
    import vtkmodules.vtkRenderingOpenGL2  # noqa: F401  (the OpenGL backend)
    from vtkmodules.vtkFiltersSources import vtkRegularPolygonSource
    from vtkmodules.vtkRenderingCore import (vtkActor, vtkPolyDataMapper, vtkRenderer,
                                             vtkRenderWindow)
    from vtkmodules.vtkFiltersGeneral import vtkVertexGlyphFilter

    diracs = solver.GetOutput(0)

    def actor(data, colour=None, direct=False, width=1.0, wireframe=False, point_size=0.0):
        mapper = vtkPolyDataMapper()
        mapper.SetInputData(data)
        if direct:
            mapper.SetColorModeToDirectScalars()
        else:
            mapper.ScalarVisibilityOff()
        result = vtkActor()
        result.SetMapper(mapper)
        if colour:
            result.GetProperty().SetColor(*colour)
        if wireframe:
            result.GetProperty().SetRepresentationToWireframe()
        result.GetProperty().SetLineWidth(width)
        if point_size:
            result.GetProperty().SetPointSize(point_size)
        return result

    def view(renderer, viewport):
        renderer.SetViewport(*viewport)
        renderer.SetBackground(1.0, 1.0, 1.0)
        camera = renderer.GetActiveCamera()
        camera.SetPosition(0.0, 0.0, 5.0)
        camera.SetFocalPoint(0.0, 0.0, 0.0)
        camera.SetViewUp(0.0, 1.0, 0.0)
        camera.SetParallelProjection(1)
        camera.SetParallelScale(1.08)
        renderer.ResetCameraClippingRange()

    circle = vtkRegularPolygonSource()
    circle.SetNumberOfSides(256)
    circle.SetRadius(1.0)
    circle.GeneratePolygonOff()
    circle.Update()

    source = vtkRenderer()
    cells = actor(coloured_by_target(solver.GetOutput(1), diracs, True), direct=True)
    cells.GetMapper().SetResolveCoincidentTopologyToPolygonOffset()
    source.AddActor(cells)
    source.AddActor(actor(circle.GetOutput(), (0.2, 0.2, 0.2), width=1.5))
    jumps = actor(solver.GetOutput(4), (0.0, 0.0, 0.0), width=max(2.0, size / 250))
    jumps.SetPosition(0.0, 0.0, 0.01)
    source.AddActor(jumps)
    view(source, (0.0, 0.0, 0.5, 1.0))

    target = vtkRenderer()
    support = actor(sampler.GetOutput(), (0.86, 0.86, 0.86))
    support.GetMapper().SetResolveCoincidentTopologyToPolygonOffset()
    target.AddActor(support)
    points = vtkVertexGlyphFilter()
    points.SetInputData(coloured_by_target(sampler.GetOutput(), diracs, False))
    points.Update()
    target.AddActor(actor(points.GetOutput(), direct=True, point_size=max(2.0, size / 180)))
    target.AddActor(actor(circle.GetOutput(), (0.6, 0.6, 0.6), width=1.0))
    view(target, (0.5, 0.0, 1.0, 1.0))

    window = vtkRenderWindow()
    window.SetOffScreenRendering(1)
    window.SetMultiSamples(0)
    window.SetSize(2 * size, size)
    window.AddRenderer(source)
    window.AddRenderer(target)
    window.Render()
    if path is not None:
        save_png(window, path)
        print("wrote", path)
    return window


def summary(name, sampler, solver):
    fd = solver.GetOutput(0).GetFieldData()
    jumps = solver.GetOutput(4)
    length = 0.0
    for c in range(jumps.GetNumberOfCells()):
        cell = jumps.GetCell(c)
        length += math.dist(jumps.GetPoint(cell.GetPointId(0))[:2],
                            jumps.GetPoint(cell.GetPointId(1))[:2])
    cv = sampler.GetOutput().GetFieldData().GetArray("MassCoefficientOfVariation").GetValue(0)
    return (f"{name}: {sampler.GetOutput().GetNumberOfPoints()} samples (mass CV {cv:.3f}), "
            f"{'converged' if fd.GetArray('Converged').GetValue(0) else 'NOT converged'} in "
            f"{fd.GetArray('Iterations').GetValue(0)} Newton iterations to "
            f"{fd.GetArray('RelativeError').GetValue(0):.1e}; singularity set: "
            f"{jumps.GetNumberOfCells()} power edges, total length {length:.3f}")


def main():
    args = parse_args()
    ensure_display(args)
    from vtkmodules.vtkIOXML import vtkXMLPolyDataWriter

    os.makedirs(args.output, exist_ok=True)
    first = True
    for name, make in SHAPES.items():
        sampler, solver = transport_onto(make(), args.samples)
        if solver.GetOutput(0).GetFieldData().GetArray("Converged") is None:
            sys.exit(f"{name}: the transport failed (see the error above)")
        print(summary(name, sampler, solver), flush=True)
        outputs = [(sampler.GetOutput(), "samples"), (solver.GetOutput(1), "power_diagram"),
                   (solver.GetOutput(4), "singularities")]
        for data, kind in outputs:
            writer = vtkXMLPolyDataWriter()
            writer.SetFileName(os.path.join(args.output, f"{name}_{kind}.vtp"))
            writer.SetInputData(data)
            writer.Write()
        if not args.no_picture:
            if first:
                # Under Xvfb, Debian's VTK 9.2 renders the first picture of a process black.
                render_support_figure(sampler, solver, None, 100)
                first = False
            render_support_figure(sampler, solver,
                                  os.path.join(args.output, f"supports_{name}.png"), args.size)


if __name__ == "__main__":
    main()
