#!/usr/bin/python3
"""Area-preserving parameterization of a closed surface onto the unit sphere with
vtkAreaPreservingParam (Domain Automatic picks the sphere for a closed genus-0 surface): the
outputs (.vtp) and a picture.

    sphere_demo.py [OUTPUT_DIR] [--mesh FILE] [--samples N] [--size PIXELS]

Without --mesh the surface is a built-in one generated here: a closed surface of revolution
with two waists and a long, thin nose (its conformal sphere map shrinks the nose's area by a
factor of ~1e3). --mesh takes any closed surface VTK reads (.vtp, .vtk, .ply, .stl, .obj) or
an .off. Written to OUTPUT_DIR (default ./otparam-sphere-output):
- sphere_surface.vtp: the surface with AreaPreservingCoordinates and ConformalCoordinates
  (points on the unit sphere), texture coordinates SphericalTextureCoordinates (longitude and
  latitude in [0, 1]), per-triangle LogAreaRatio and AngleDistortion, every figure as field
  data; sphere_mesh.vtp: the area-preserving sphere mesh;
- sphere_circles.png: the surface painted with 150 equal circles of the sphere pulled back
  through the conformal map (left: they stay round, their sizes follow the area distortion)
  and through the area-preserving map (right: blobs of equal area).

Rendering needs an X server: without DISPLAY the script runs itself again under xvfb-run.
"""

import argparse
import math
import os
import sys
import time

from otparam_example_utils import ensure_display, read_surface, save_png


def make_nosed_surface(rings=120, sectors=160):
    """A closed surface of revolution about z: two waists and a thin nose along +z."""
    import numpy as np
    from vtkmodules.util.numpy_support import numpy_to_vtk, numpy_to_vtkIdTypeArray
    from vtkmodules.vtkCommonCore import vtkPoints
    from vtkmodules.vtkCommonDataModel import vtkCellArray, vtkPolyData

    def profile(t):  # t in [0, pi] from the tip of the nose to the south pole
        z = math.cos(t)
        body = math.sin(t) * (0.7 + 0.3 * math.cos(2.0 * math.pi * z))
        nose = 0.12 * math.sin(t) if z > 0.6 else body
        return (min(body, nose) if z > 0.6 else body), z + (1.2 * (z - 0.6) if z > 0.6 else 0.0)

    points = [(0.0, 0.0, profile(0.0)[1])]
    for r in range(1, rings + 1):
        radius, z = profile(math.pi * r / (rings + 1))
        for s in range(sectors):
            phi = 2.0 * math.pi * (s + 0.5 * (r % 2)) / sectors
            points.append((radius * math.cos(phi), radius * math.sin(phi), z))
    points.append((0.0, 0.0, profile(math.pi)[1]))
    south = len(points) - 1
    at = lambda r, s: 1 + (r - 1) * sectors + s % sectors  # noqa: E731
    triangles = []
    for s in range(sectors):
        triangles.append((0, at(1, s), at(1, s + 1)))
        triangles.append((south, at(rings, s + 1), at(rings, s)))
    for r in range(1, rings):
        for s in range(sectors):
            a, b, c, d = at(r, s), at(r, s + 1), at(r + 1, s), at(r + 1, s + 1)
            triangles += [(a, d, b), (a, c, d)] if r % 2 else [(a, c, b), (b, c, d)]
    data = vtkPolyData()
    vtk_points = vtkPoints()
    vtk_points.SetData(numpy_to_vtk(np.array(points, float), deep=True))
    data.SetPoints(vtk_points)
    cells = np.hstack([np.full((len(triangles), 1), 3), np.array(triangles)]).ravel()
    polys = vtkCellArray()
    polys.SetCells(len(triangles), numpy_to_vtkIdTypeArray(cells.astype(np.int64), deep=True))
    data.SetPolys(polys)
    return data


def circle_scalars(sphere_points, circles=150, radius=0.11):
    """Per point: angle to the nearest of `circles` evenly spread centres over `radius`
    (< 1 inside a circle)."""
    import numpy as np
    k = np.arange(circles) + 0.5
    z = 1.0 - 2.0 * k / circles
    phi = math.pi * (3.0 - math.sqrt(5.0)) * k
    centres = np.stack([np.sqrt(1 - z * z) * np.cos(phi), np.sqrt(1 - z * z) * np.sin(phi), z], 1)
    nearest = np.clip((sphere_points @ centres.T).max(axis=1), -1.0, 1.0)
    return np.arccos(nearest) / radius


def render_circles(surface, path, size, circles=150, radius=0.11):
    """The surface painted with equal circles of the sphere through ConformalCoordinates
    (left) and AreaPreservingCoordinates (right); writes the PNG unless path is None. (Per-point
    colours: the circles must span several triangles of the mesh.)"""
    import numpy as np
    import vtkmodules.vtkRenderingOpenGL2  # noqa: F401
    from vtkmodules.util.numpy_support import numpy_to_vtk, vtk_to_numpy
    from vtkmodules.vtkCommonCore import vtkLookupTable
    from vtkmodules.vtkCommonDataModel import vtkPolyData
    from vtkmodules.vtkFiltersCore import vtkPolyDataNormals
    from vtkmodules.vtkRenderingCore import (vtkActor, vtkPolyDataMapper, vtkRenderer,
                                             vtkRenderWindow)

    window = vtkRenderWindow()
    window.SetMultiSamples(0)
    window.SetSize(size, size // 2)
    window.SetOffScreenRendering(1)
    table = vtkLookupTable()
    table.SetNumberOfTableValues(2)
    table.SetTableValue(0, 0.85, 0.25, 0.2, 1.0)
    table.SetTableValue(1, 0.95, 0.93, 0.85, 1.0)
    table.SetRange(0.0, 2.0)
    table.Build()
    for k, name in enumerate(("ConformalCoordinates", "AreaPreservingCoordinates")):
        points = vtk_to_numpy(surface.GetPointData().GetArray(name))
        copy = vtkPolyData()
        copy.SetPoints(surface.GetPoints())
        copy.SetPolys(surface.GetPolys())
        scalars = numpy_to_vtk(
            np.nan_to_num(circle_scalars(points, circles, radius), nan=2.0), deep=True)
        copy.GetPointData().SetScalars(scalars)
        normals = vtkPolyDataNormals()
        normals.SetInputData(copy)
        normals.SplittingOff()
        mapper = vtkPolyDataMapper()
        mapper.SetInputConnection(normals.GetOutputPort())
        mapper.SetLookupTable(table)
        mapper.SetScalarRange(0.0, 2.0)
        mapper.InterpolateScalarsBeforeMappingOn()
        actor = vtkActor()
        actor.SetMapper(mapper)
        renderer = vtkRenderer()
        renderer.SetViewport(0.5 * k, 0.0, 0.5 * k + 0.5, 1.0)
        renderer.SetBackground(1.0, 1.0, 1.0)
        renderer.AddActor(actor)
        renderer.ResetCamera()
        camera = renderer.GetActiveCamera()
        camera.Azimuth(-90.0)  # a side view: x toward the viewer for a brain hemisphere
        camera.Elevation(10.0)
        camera.OrthogonalizeViewUp()
        renderer.ResetCamera()
        camera.Zoom(1.35)
        window.AddRenderer(renderer)
    window.Render()
    if path is not None:  # regression tests compare the window instead
        save_png(window, path)
        print("wrote", path)
    return window


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("output", nargs="?", default="otparam-sphere-output")
    parser.add_argument("--mesh", help="closed surface file; default: the built-in nosed surface")
    parser.add_argument("--samples", type=int, default=5000, help="NumberOfSamples (5000)")
    parser.add_argument("--size", type=int, default=1200, help="picture width in pixels")
    parser.add_argument("--no-picture", action="store_true", help="skip the PNG")
    args = parser.parse_args()
    ensure_display(args)

    from otparam import vtkAreaPreservingParam

    os.makedirs(args.output, exist_ok=True)
    surface = read_surface(args.mesh) if args.mesh else make_nosed_surface()
    print(f"{args.mesh or 'built-in nosed surface'}: {surface.GetNumberOfPoints()} points, "
          f"{surface.GetNumberOfCells()} triangles", flush=True)
    param = vtkAreaPreservingParam()
    param.SetInputData(surface)
    param.SetNumberOfSamples(args.samples)
    start = time.perf_counter()
    param.Update()
    out = param.GetOutput()
    if out.GetNumberOfPoints() == 0:
        sys.exit("the parameterization failed (see the error above)")
    if out.GetFieldData().GetArray("Domain").GetValue(0) != 2:
        sys.exit("the surface is not closed: use area_preserving_demo.py for the disk")
    print(f"done in {time.perf_counter() - start:.2f} s", flush=True)
    return write_sphere_outputs(param, args.output, None if args.no_picture else args.size)


def write_sphere_outputs(param, output, size):
    """Prints the figures of a finished sphere run, writes its two meshes and (size not None)
    the circle picture; returns the exit status (0 when converged without flips)."""
    from vtkmodules.vtkIOXML import vtkXMLPolyDataWriter
    out = param.GetOutput()
    fd = out.GetFieldData()
    value = lambda name: fd.GetArray(name).GetValue(0)  # noqa: E731
    print(f"sphere: transport converged {value('Converged')} (relative error"
          f" {value('RelativeError'):.1e}), flipped {value('FlippedTriangles')}, mean |log area"
          f" ratio| {value('ConformalMeanAbsLogAreaRatio'):.3f} (conformal) ->"
          f" {value('MeanAbsLogAreaRatio'):.4f}, mean angle distortion"
          f" {value('ConformalMeanAngleDistortion'):.2f} -> {value('MeanAngleDistortion'):.2f}"
          f" degrees", flush=True)
    for data, name in ((out, "sphere_surface.vtp"), (param.GetOutput(1), "sphere_mesh.vtp")):
        writer = vtkXMLPolyDataWriter()
        writer.SetFileName(os.path.join(output, name))
        writer.SetInputData(data)
        writer.SetDataModeToBinary()  # Debian 12's expat cannot read appended data
        writer.Write()
        print("wrote", os.path.join(output, name))
    if size is not None:
        render_circles(out, os.path.join(output, "sphere_circles.png"), size)
    return 0 if value("Converged") == 1 and value("FlippedTriangles") == 0 else 1


if __name__ == "__main__":
    sys.exit(main())
