#!/usr/bin/python3
"""Conformal disk map of a surface: vtkConformalDiskMap, its output (.vtp) and a picture.

    conformal_map_demo.py [OUTPUT_DIR] [--mesh FILE.obj|.off|.vtp] [--size PIXELS]

Without --mesh the surface is a built-in one (a disk-like relief with three bumps, generated
here). Writes OUTPUT_DIR/conformal_disk_map.vtp (the disk image with every array) and
OUTPUT_DIR/conformal_disk_map.png: left, the 3D surface with a checkerboard texture through the
conformal coordinates (conformal: the squares stay square); right, the disk image coloured by
log10 of the area distortion AreaDensity.

Rendering needs an X server (Debian's VTK has no EGL/OSMesa): without DISPLAY, the script runs
itself again under `xvfb-run -a`.
"""

import argparse
import math
import os
import sys

from otparam_example_utils import (density_disk_actors, ensure_display, read_surface,
                                   ring_surface, save_png, view_along_mean_normal)
from vtkmodules.vtkCommonCore import vtkDoubleArray, vtkUnsignedCharArray
from vtkmodules.vtkCommonDataModel import vtkImageData, vtkPolyData


def make_default_surface(rings=40):
    """A disk-like surface generated here: concentric rings of 6k points over the unit disk,
    lifted by three Gaussian bumps (a nose and two cheeks, roughly), so that the conformal map
    has a visibly non-uniform area distortion."""
    def height(x, y):
        bumps = ((0.0, -0.1, 0.5, 0.28), (-0.45, 0.3, 0.3, 0.25), (0.45, 0.3, 0.3, 0.25))
        return sum(a * math.exp(-((x - cx) ** 2 + (y - cy) ** 2) / (s * s))
                   for cx, cy, a, s in bumps)

    return ring_surface(rings, height)


def checkerboard(size=512, checks=16):
    """An RGB checkerboard image for texturing (two blues, so it reads on any shading)."""
    image = vtkImageData()
    image.SetDimensions(size, size, 1)
    colors = vtkUnsignedCharArray()
    colors.SetNumberOfComponents(3)
    colors.SetNumberOfTuples(size * size)
    cell = size // checks
    for j in range(size):
        for i in range(size):
            dark = ((i // cell) + (j // cell)) % 2
            colors.SetTuple3(j * size + i, *((30, 60, 140) if dark else (235, 235, 245)))
    image.GetPointData().SetScalars(colors)
    return image


def render(surface, disk, size=1200, elevation=-50.0):
    """The picture: textured 3D surface (left) and the disk coloured by log10 AreaDensity
    (right). Returns the vtkRenderWindow (rendered, deterministic: fixed size and cameras, no
    multisampling)."""
    from vtkmodules.vtkFiltersCore import vtkPolyDataNormals
    from vtkmodules.vtkRenderingCore import (vtkActor, vtkPolyDataMapper, vtkRenderer,
                                             vtkRenderWindow, vtkTexture)
    import vtkmodules.vtkRenderingOpenGL2  # noqa: F401  (the OpenGL backend)

    # Left: the surface with checkerboard texture coordinates (u, v) mapped to [0, 1]^2.
    textured = vtkPolyData()
    textured.ShallowCopy(surface)
    tcoords = vtkDoubleArray()
    tcoords.SetName("Checkerboard")
    tcoords.SetNumberOfComponents(2)
    uv = disk.GetPointData().GetTCoords()
    for i in range(uv.GetNumberOfTuples()):
        u, v = uv.GetTuple2(i)
        tcoords.InsertNextTuple2(0.5 * (u + 1.0), 0.5 * (v + 1.0))
    textured.GetPointData().SetTCoords(tcoords)
    normals = vtkPolyDataNormals()
    normals.SetInputData(textured)
    normals.SplittingOff()
    texture = vtkTexture()
    texture.SetInputData(checkerboard())
    texture.InterpolateOff()
    surface_mapper = vtkPolyDataMapper()
    surface_mapper.SetInputConnection(normals.GetOutputPort())
    surface_mapper.ScalarVisibilityOff()
    surface_actor = vtkActor()
    surface_actor.SetMapper(surface_mapper)
    surface_actor.SetTexture(texture)
    left = vtkRenderer()
    left.SetViewport(0.0, 0.0, 0.5, 1.0)
    left.SetBackground(1.0, 1.0, 1.0)
    left.AddActor(surface_actor)

    # Right: the disk coloured per triangle by log10 of the exact area ratio.
    disk_actor, bar = density_disk_actors(disk)
    right = vtkRenderer()
    right.SetViewport(0.5, 0.0, 1.0, 1.0)
    right.SetBackground(1.0, 1.0, 1.0)
    right.AddActor(disk_actor)
    right.AddActor2D(bar)

    window = vtkRenderWindow()
    window.SetMultiSamples(0)
    window.SetSize(size, size // 2)
    window.AddRenderer(left)
    window.AddRenderer(right)
    window.SetOffScreenRendering(1)

    # Cameras from the data alone: the surface seen along its mean normal, the disk from +z.
    normals.Update()
    camera = view_along_mean_normal(left, normals.GetOutput(), elevation)  # oblique: relief shows
    camera.Zoom(1.25)
    right.GetActiveCamera().SetPosition(0.15, 0.0, 5.0)
    right.GetActiveCamera().SetFocalPoint(0.15, 0.0, 0.0)
    right.GetActiveCamera().SetViewUp(0.0, 1.0, 0.0)
    right.ResetCameraClippingRange()
    right.GetActiveCamera().SetParallelProjection(1)
    right.GetActiveCamera().SetParallelScale(1.15)
    window.Render()
    return window


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("output", nargs="?", default="otparam-output", help="output directory")
    parser.add_argument("--mesh", help="surface file (.obj, .off, .vtp); default: built-in")
    parser.add_argument("--size", type=int, default=1200, help="picture width in pixels")
    parser.add_argument("--elevation", type=float,
                        help="camera elevation from the mean normal, degrees (default: -50 for "
                             "the built-in surface, 0 for --mesh)")
    parser.add_argument("--no-picture", action="store_true", help="skip the PNG")
    args = parser.parse_args()
    ensure_display(args)

    from otparam import vtkConformalDiskMap
    from vtkmodules.vtkIOXML import vtkXMLPolyDataWriter

    surface = read_surface(args.mesh) if args.mesh else make_default_surface()
    mapper = vtkConformalDiskMap()
    mapper.SetInputData(surface)
    mapper.Update()
    disk = mapper.GetOutput()
    if disk.GetNumberOfPoints() == 0:
        sys.exit("the conformal map failed (see the error above)")
    field = disk.GetFieldData()
    figures = {name: field.GetArray(name).GetTuple1(0) for name in (
        "MeanAngleDistortion", "MaximumAngleDistortion", "MeanQuasiConformalDilatation",
        "FlippedTriangles", "MaximumBoundaryRadiusError", "MaximumAbsLogAreaRatio",
        "Iterations", "SecondsTotal")}
    print(f"conformal disk map of {surface.GetNumberOfPoints()} points, "
          f"{surface.GetNumberOfPolys()} triangles:")
    for name, value in figures.items():
        print(f"  {name:32s} {value:.6g}")

    os.makedirs(args.output, exist_ok=True)
    writer = vtkXMLPolyDataWriter()
    writer.SetDataModeToBinary()  # Debian's ParaView VTK cannot read appended-mode files back
    writer.SetFileName(os.path.join(args.output, "conformal_disk_map.vtp"))
    writer.SetInputData(disk)
    writer.Write()
    if not args.no_picture:
        path = os.path.join(args.output, "conformal_disk_map.png")
        elevation = args.elevation if args.elevation is not None else (0.0 if args.mesh else -50.0)
        save_png(render(surface, disk, args.size, elevation), path)
        print(f"wrote {path}")


if __name__ == "__main__":
    main()
