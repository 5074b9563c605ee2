#!/usr/bin/python3
"""Area-preserving parameterization of a surface onto the unit disk with vtkAreaPreservingParam:
every output (.vtp, .csv) and the paper's figure set (PNG).

    area_preserving_demo.py [OUTPUT_DIR] [--mesh FILE] [--samples N] [--size PIXELS]

Without --mesh the surface is a built-in one generated here: a hand-like height field (a palm
and five tall, narrow fingers) whose conformal image shrinks the finger tips by a factor of
~1e5 in area. --mesh takes any surface VTK reads (.vtp, .vtk, .ply, .stl, .obj) or an .off;
a closed one goes to the unit sphere (the outputs of Examples/sphere_demo.py).
Progress is printed as the stages run. Written to OUTPUT_DIR (default ./otparam-output):
- area_preserving_surface.vtp: the surface with texture coordinates AreaPreservingCoordinates,
  ConformalCoordinates, per-triangle LogAreaRatio and AngleDistortion, every figure as field
  data; area_preserving_disk.vtp: the flattened disk; distortion_histograms.csv;
- conformal_image.vtp, samples.vtp, power_diagram.vtp, brenier_potential.vtp,
  legendre_dual.vtp: the stages' own outputs (from the three filters run on their own with
  the same settings, since vtkAreaPreservingParam keeps them internal);
- PNGs: conformal_density_samples.png (the conformal image coloured by log10 of the area
  distortion, with the samples), power_diagram.png, brenier_legendre.png (the Brenier potential
  and its Legendre dual in 3D), circle_texture.png (the surface textured with circles through
  the conformal coordinates, which keep them circles, and through the area-preserving ones,
  which make them ellipses of equal area), distortion_histograms.png (angle and area
  distortion of both maps: the paper's Fig. 5), flat_map_curvature.png (the surface's mean
  curvature, a point array of the input, on the surface and on the area-preserving disk, which
  carries the input's arrays).

Rendering needs an X server (Debian's VTK has no EGL/OSMesa): without DISPLAY, the script runs
itself again under `xvfb-run -a`.
"""

import argparse
import csv
import math
import os
import sys
import time

from otparam_example_utils import (circle_image, density_disk_actors, ensure_display,
                                   read_surface, ring_surface, save_png,
                                   view_along_mean_normal)

STAGE_OUTPUTS = ["conformal_image", "samples", "power_diagram", "brenier_potential",
                 "legendre_dual"]


def make_hand_like_surface(rings=70):
    """A height field over the unit disk sampled on concentric rings of 6k points: a low palm
    and five fingers, elongated Gaussian ridges one unit tall and 0.075 wide. Lifted, the ring
    triangles on the fingers' flanks turn obtuse (the conformal map then needs its intrinsic
    Delaunay fallback) and the finger tips are where the conformal map shrinks area most."""
    fingers = [(-100, 0.20, 0.8), (-40, 0.30, 1.0), (-5, 0.32, 1.1), (30, 0.30, 1.0),
               (62, 0.24, 0.8)]  # direction (degrees), length, height

    def height(x, y):
        z = 0.25 * math.exp(-((x + 0.15) ** 2 + y ** 2) / 0.25)
        for degrees, length, tall in fingers:
            a = math.radians(degrees)
            cx, cy = 0.5 * math.cos(a), 0.5 * math.sin(a)
            along = (x - cx) * math.cos(a) + (y - cy) * math.sin(a)
            across = -(x - cx) * math.sin(a) + (y - cy) * math.cos(a)
            z += tall * math.exp(-(along / length) ** 2 - (across / 0.075) ** 2)
        return z

    return ring_surface(rings, height)


def print_progress(algorithm):
    """Prints the running stage and its progress in steps of 10%."""
    from vtkmodules.vtkCommonCore import vtkCommand
    last = [None]

    def report(caller, _event):
        text = caller.GetProgressText() or ""
        step = (text, int(caller.GetProgress() * 10))
        if step != last[0]:
            last[0] = step
            print(f"  {caller.GetProgress():4.0%}  {text}", flush=True)

    algorithm.AddObserver(vtkCommand.ProgressEvent, report)


def run_stages(surface, samples, sampling_mode):
    """The three stages on their own (for their outputs and pictures), with the settings
    vtkAreaPreservingParam uses."""
    from otparam import vtkAdaptiveDensitySampler, vtkConformalDiskMap, vtkSemiDiscreteOTSolver
    from vtkmodules.vtkCommonDataModel import vtkDataObject

    conformal = vtkConformalDiskMap()
    conformal.SetInputData(surface)
    sampler = vtkAdaptiveDensitySampler()
    sampler.SetInputConnection(conformal.GetOutputPort())
    sampler.SetInputArrayToProcess(0, 0, 0, vtkDataObject.FIELD_ASSOCIATION_CELLS, "AreaDensity")
    sampler.SetNumberOfSamples(samples)
    sampler.SetSamplingMode(sampling_mode)
    transport = vtkSemiDiscreteOTSolver()
    transport.SetInputConnection(sampler.GetOutputPort())
    transport.Update()
    return conformal, sampler, transport


def write_vtp(data, path):
    from vtkmodules.vtkIOXML import vtkXMLPolyDataWriter
    writer = vtkXMLPolyDataWriter()
    writer.SetFileName(path)
    writer.SetInputData(data)
    # Inline data: Debian 12's patched expat cannot read VTK's appended-data section.
    writer.SetDataModeToBinary()
    if writer.Write() != 1:
        sys.exit(f"could not write {path}")
    print("wrote", path)


def write_histograms(table, path):
    with open(path, "w", newline="") as f:
        out = csv.writer(f)
        names = [table.GetColumnName(c) for c in range(table.GetNumberOfColumns())]
        out.writerow(names)
        for r in range(table.GetNumberOfRows()):
            out.writerow([table.GetColumn(c).GetValue(r) for c in range(len(names))])
    print("wrote", path)


def new_window(width, height):
    import vtkmodules.vtkRenderingFreeType  # noqa: F401  (text: scalar bars, chart titles)
    import vtkmodules.vtkRenderingOpenGL2  # noqa: F401  (the OpenGL backend)
    from vtkmodules.vtkRenderingCore import vtkRenderWindow
    window = vtkRenderWindow()
    window.SetMultiSamples(0)
    window.SetSize(width, height)
    return window


def render_to_png(window, path):
    """Renders off screen; writes the PNG unless path is None (regression tests compare the
    window instead). Returns the window."""
    window.SetOffScreenRendering(1)
    window.Render()
    if path is not None:
        save_png(window, path)
        print("wrote", path)
    return window


def top_view(renderer, scale=1.1):
    camera = renderer.GetActiveCamera()
    camera.SetPosition(0.0, 0.0, 5.0)
    camera.SetFocalPoint(0.0, 0.0, 0.0)
    camera.SetViewUp(0.0, 1.0, 0.0)
    camera.SetParallelProjection(1)
    camera.SetParallelScale(scale)
    renderer.ResetCameraClippingRange()


def render_density_and_samples(conformal_image, samples, path, size):
    """The conformal image coloured per triangle by log10 AreaDensity, samples as dots."""
    from vtkmodules.vtkFiltersGeneral import vtkVertexGlyphFilter
    from vtkmodules.vtkRenderingCore import vtkActor, vtkPolyDataMapper, vtkRenderer

    disk, bar = density_disk_actors(conformal_image)
    dots = vtkVertexGlyphFilter()
    dots.SetInputData(samples)
    dots_mapper = vtkPolyDataMapper()
    dots_mapper.SetInputConnection(dots.GetOutputPort())
    dots_mapper.ScalarVisibilityOff()
    dots_actor = vtkActor()
    dots_actor.SetMapper(dots_mapper)
    dots_actor.GetProperty().SetColor(0.0, 0.0, 0.0)
    dots_actor.GetProperty().SetPointSize(1.5)
    renderer = vtkRenderer()
    renderer.SetBackground(1.0, 1.0, 1.0)
    renderer.AddActor(disk)
    renderer.AddActor(dots_actor)
    renderer.AddActor2D(bar)
    # A window wider than high: the disk on the left with a margin, the colour bar beside it.
    window = new_window(int(1.3 * size), size)
    window.AddRenderer(renderer)
    top_view(renderer)
    shift = 1.3 * 1.1 - 1.1  # the visible half-width minus the disk's half-width and margin
    renderer.GetActiveCamera().SetPosition(shift, 0.0, 5.0)
    renderer.GetActiveCamera().SetFocalPoint(shift, 0.0, 0.0)
    bar.SetPosition(0.82, 0.1)
    bar.SetHeight(0.75)
    return render_to_png(window, path)


def render_brenier_legendre(transport, path, size):
    """The Brenier potential u_h (left) and the Legendre dual u_h* (right) as 3D surfaces."""
    from vtkmodules.vtkFiltersCore import vtkElevationFilter
    from vtkmodules.vtkRenderingCore import vtkActor, vtkPolyDataMapper, vtkRenderer

    window = new_window(size, size // 2)
    for port, left in ((2, 0.0), (3, 0.5)):
        data = transport.GetOutput(port)
        bounds = data.GetBounds()
        elevation = vtkElevationFilter()
        elevation.SetInputData(data)
        elevation.SetLowPoint(0.0, 0.0, bounds[4])
        elevation.SetHighPoint(0.0, 0.0, bounds[5])
        mapper = vtkPolyDataMapper()
        mapper.SetInputConnection(elevation.GetOutputPort())
        actor = vtkActor()
        actor.SetMapper(mapper)
        actor.GetProperty().EdgeVisibilityOn()
        actor.GetProperty().SetEdgeColor(0.15, 0.15, 0.15)
        actor.GetProperty().SetLineWidth(0.5)
        renderer = vtkRenderer()
        renderer.SetViewport(left, 0.0, left + 0.5, 1.0)
        renderer.SetBackground(1.0, 1.0, 1.0)
        renderer.AddActor(actor)
        renderer.ResetCamera()
        camera = renderer.GetActiveCamera()
        camera.Elevation(-60.0)
        camera.OrthogonalizeViewUp()
        camera.Azimuth(30.0)
        renderer.ResetCamera()
        camera.Zoom(1.3)
        window.AddRenderer(renderer)
    return render_to_png(window, path)


def smooth_mapper(data):
    """A mapper of `data` with smooth point normals, and the data with them (for the camera)."""
    from vtkmodules.vtkFiltersCore import vtkPolyDataNormals
    from vtkmodules.vtkRenderingCore import vtkPolyDataMapper
    normals = vtkPolyDataNormals()
    normals.SetInputData(data)
    normals.SplittingOff()
    normals.Update()
    mapper = vtkPolyDataMapper()
    mapper.SetInputConnection(normals.GetOutputPort())
    return mapper, normals.GetOutput()


def half_renderer(window, left, mapper):
    """A renderer of one actor on the half of `window` from `left` (0 or 0.5)."""
    from vtkmodules.vtkRenderingCore import vtkActor, vtkRenderer
    actor = vtkActor()
    actor.SetMapper(mapper)
    renderer = vtkRenderer()
    renderer.SetViewport(left, 0.0, left + 0.5, 1.0)
    renderer.SetBackground(1.0, 1.0, 1.0)
    renderer.AddActor(actor)
    window.AddRenderer(renderer)
    return renderer, actor


def render_circle_texture(surface, path, size):
    """The surface textured with circles through ConformalCoordinates (left) and through
    AreaPreservingCoordinates (right), seen along its mean normal."""
    from vtkmodules.vtkCommonCore import vtkDoubleArray
    from vtkmodules.vtkCommonDataModel import vtkPolyData
    from vtkmodules.vtkRenderingCore import vtkTexture

    texture = vtkTexture()
    texture.SetInputData(circle_image())
    texture.InterpolateOn()
    window = new_window(size, size // 2)
    for name, left in (("ConformalCoordinates", 0.0), ("AreaPreservingCoordinates", 0.5)):
        uv = surface.GetPointData().GetArray(name)
        tcoords = vtkDoubleArray()
        tcoords.SetName("Texture")
        tcoords.SetNumberOfComponents(2)
        for i in range(uv.GetNumberOfTuples()):
            u, v = uv.GetTuple2(i)
            tcoords.InsertNextTuple2(0.5 * (u + 1.0), 0.5 * (v + 1.0))
        textured = vtkPolyData()
        textured.SetPoints(surface.GetPoints())
        textured.SetPolys(surface.GetPolys())
        textured.GetPointData().SetTCoords(tcoords)
        mapper, with_normals = smooth_mapper(textured)
        mapper.ScalarVisibilityOff()
        renderer, actor = half_renderer(window, left, mapper)
        actor.SetTexture(texture)
        view_along_mean_normal(renderer, with_normals, -35.0).Zoom(1.3)
    return render_to_png(window, path)


def render_histograms(table, path, size):
    """The four distortion histograms (the paper's Fig. 5) as bar charts, 2 x 2."""
    from vtkmodules.vtkChartsCore import vtkAxis, vtkChart, vtkChartMatrix, vtkChartXY
    from vtkmodules.vtkCommonDataModel import vtkTable, vtkVector2f, vtkVector2i
    from vtkmodules.vtkViewsContext2D import vtkContextView
    import vtkmodules.vtkRenderingContextOpenGL2  # noqa: F401  (the 2D context backend)

    view = vtkContextView()
    view.GetRenderer().SetBackground(1.0, 1.0, 1.0)
    window = view.GetRenderWindow()
    window.SetOffScreenRendering(1)
    window.SetMultiSamples(0)
    window.SetSize(size, size * 3 // 4)
    matrix = vtkChartMatrix()
    matrix.SetSize(vtkVector2i(2, 2))
    matrix.SetGutter(vtkVector2f(70.0, 70.0))
    matrix.SetBorders(70, 40, 20, 30)  # room for the left column's axis title
    view.GetScene().AddItem(matrix)
    panels = [("ConformalAngleDistortion", "conformal: mean |log angle ratio|", (0, 1)),
              ("AreaPreservingAngleDistortion", "area-preserving: mean |log angle ratio|", (1, 1)),
              ("ConformalLogAreaRatio", "conformal: log area ratio", (0, 0)),
              ("AreaPreservingLogAreaRatio", "area-preserving: log area ratio", (1, 0))]
    keep = []
    for name, title, (i, j) in panels:
        part = vtkTable()
        part.AddColumn(table.GetColumnByName(name + "BinCenter"))
        part.AddColumn(table.GetColumnByName(name))
        keep.append(part)
        chart = vtkChartXY()
        matrix.SetChart(vtkVector2i(i, j), chart)
        chart.SetTitle(title)
        bars = chart.AddPlot(vtkChart.BAR)
        bars.SetInputData(part, 0, 1)
        bars.SetColor(40, 70, 150, 255)
        chart.GetAxis(vtkAxis.LEFT).SetTitle("triangles")
        chart.GetAxis(vtkAxis.BOTTOM).SetTitle("")
    return render_to_png(window, path)


def with_mean_curvature(surface):
    """The surface with its mean curvature as point array MeanCurvature (VTK's discrete
    estimate), standing for any per-point data a user brings (a thickness, a label)."""
    from vtkmodules.vtkFiltersGeneral import vtkCurvatures
    curvatures = vtkCurvatures()
    curvatures.SetInputData(surface)
    curvatures.SetCurvatureTypeToMean()
    curvatures.Update()
    out = curvatures.GetOutput()
    out.GetPointData().GetArray("Mean_Curvature").SetName("MeanCurvature")
    return out


def render_flat_map_scalars(param, name, path, size):
    """The input's point array `name` on the surface (left) and on the area-preserving disk
    (right, output port 1, which carries the input's arrays), with one colour scale: the 5th to
    95th percentile."""
    import numpy
    from vtkmodules.util.numpy_support import vtk_to_numpy

    surface, disk = param.GetOutput(), param.GetOutput(1)
    values = vtk_to_numpy(disk.GetPointData().GetArray(name))
    low, high = numpy.percentile(values, [5.0, 95.0])
    window = new_window(size, size // 2)
    for data, left in ((surface, 0.0), (disk, 0.5)):
        mapper, with_normals = smooth_mapper(data)
        mapper.SetScalarModeToUsePointFieldData()
        mapper.SelectColorArray(name)
        mapper.SetScalarRange(low, high)
        mapper.ScalarVisibilityOn()
        renderer, _ = half_renderer(window, left, mapper)
        if data is disk:
            top_view(renderer)
        else:
            view_along_mean_normal(renderer, with_normals, -35.0).Zoom(1.05)
    return render_to_png(window, path)


def write_figures(param, conformal, sampler, transport, directory, size):
    """Every PNG of the figure set (see the module doc)."""
    from ot_solver_demo import render_png as render_power_diagram
    # Under Xvfb, Debian's VTK 9.2 renders the first picture of this figure black (not a
    # simple sphere, not the same figure again; cause not found): one render to waste, unsaved.
    render_density_and_samples(conformal.GetOutput(), sampler.GetOutput(), None, 200)
    render_density_and_samples(conformal.GetOutput(), sampler.GetOutput(),
                               os.path.join(directory, "conformal_density_samples.png"), size)
    power = os.path.join(directory, "power_diagram.png")
    render_power_diagram(transport, power, size)
    print("wrote", power)
    render_brenier_legendre(transport, os.path.join(directory, "brenier_legendre.png"), size)
    render_circle_texture(param.GetOutput(), os.path.join(directory, "circle_texture.png"), size)
    render_histograms(param.GetOutputDataObject(2),
                      os.path.join(directory, "distortion_histograms.png"), size)
    render_flat_map_scalars(param, "MeanCurvature",
                            os.path.join(directory, "flat_map_curvature.png"), size)


def summary(out):
    fd = out.GetFieldData()

    def value(name):
        array = fd.GetArray(name)
        return array.GetValue(0) if array is not None else float("nan")

    return (f"transport {'converged' if value('Converged') == 1 else 'NOT converged'} in "
            f"{value('Iterations'):.0f} Newton iterations (relative error "
            f"{value('RelativeError'):.1e}) on {value('NumberOfSamples'):.0f} samples; "
            f"flipped triangles {value('FlippedTriangles'):.0f}; mean |log area ratio| "
            f"{value('MeanAbsLogAreaRatio'):.4f} (largest {value('MaximumAbsLogAreaRatio'):.3f}; "
            f"conformal map: {value('ConformalMeanAbsLogAreaRatio'):.3f}, largest "
            f"{value('ConformalMaximumAbsLogAreaRatio'):.2f}); seconds: conformal "
            f"{value('SecondsConformalMap'):.2f}, sampling {value('SecondsSampling'):.2f}, "
            f"transport {value('SecondsTransport'):.2f}, composition "
            f"{value('SecondsComposition'):.2f}, total {value('SecondsTotal'):.2f}")


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("output", nargs="?", default="otparam-output", help="output directory")
    parser.add_argument("--mesh", help="surface file; default: the built-in hand-like surface")
    parser.add_argument("--samples", type=int, default=5000, help="NumberOfSamples (5000)")
    parser.add_argument("--size", type=int, default=1200, help="picture width in pixels")
    parser.add_argument("--no-picture", action="store_true", help="skip the PNGs")
    args = parser.parse_args()
    ensure_display(args)

    from otparam import vtkAreaPreservingParam

    os.makedirs(args.output, exist_ok=True)
    if args.mesh:
        surface = read_surface(args.mesh)
        print(f"{args.mesh}: {surface.GetNumberOfPoints()} points, "
              f"{surface.GetNumberOfCells()} triangles", flush=True)
    else:
        surface = make_hand_like_surface()
        print(f"built-in hand-like surface: {surface.GetNumberOfPoints()} points, "
              f"{surface.GetNumberOfCells()} triangles", flush=True)

    surface = with_mean_curvature(surface)
    param = vtkAreaPreservingParam()
    param.SetInputData(surface)
    param.SetNumberOfSamples(args.samples)
    print_progress(param)
    start = time.perf_counter()
    param.Update()
    out = param.GetOutput()
    if out.GetNumberOfPoints() == 0:
        sys.exit("the parameterization failed (see the error above)")
    if out.GetFieldData().GetArray("Domain").GetValue(0) == 2:
        # A closed surface went to the sphere (Domain Automatic).
        from sphere_demo import write_sphere_outputs
        print(f"closed surface: mapped onto the unit sphere in {time.perf_counter() - start:.2f} s",
              flush=True)
        return write_sphere_outputs(param, args.output, None if args.no_picture else args.size)
    print(f"done in {time.perf_counter() - start:.2f} s: {summary(out)}", flush=True)
    write_vtp(out, os.path.join(args.output, "area_preserving_surface.vtp"))
    write_vtp(param.GetOutput(1), os.path.join(args.output, "area_preserving_disk.vtp"))
    write_histograms(param.GetOutputDataObject(2),
                     os.path.join(args.output, "distortion_histograms.csv"))

    print("the stages on their own, for their outputs and pictures", flush=True)
    conformal, sampler, transport = run_stages(surface, args.samples, 0)
    for data, name in zip((conformal.GetOutput(), sampler.GetOutput(), transport.GetOutput(1),
                           transport.GetOutput(2), transport.GetOutput(3)), STAGE_OUTPUTS):
        write_vtp(data, os.path.join(args.output, name + ".vtp"))
    if not args.no_picture:
        write_figures(param, conformal, sampler, transport, args.output, args.size)
    fd = out.GetFieldData()
    ok = fd.GetArray("Converged").GetValue(0) == 1 and fd.GetArray("FlippedTriangles").GetValue(0) == 0
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
