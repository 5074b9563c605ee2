"""Regression images of the sphere family (sphere.md):
- _texture: the shared spot cow (closed, genus 0) through vtkAreaPreservingParam with Domain
  Automatic (which picks the sphere), textured with a longitude/latitude checkerboard through
  its SphericalTextureCoordinates: the cow (left, seen from its side) and its area-preserving
  sphere image (right, port 1) carry the same texture, so each checker cell on the cow is the
  preimage of that cell on the sphere;
- _circles: the same cow painted with 40 equal circles of the sphere pulled back through the
  conformal map (left: round) and the area-preserving map (right: blobs of equal area);
- _power_diagram: vtkSphericalOTSolver's spherical power diagram (port 1, cells coloured by
  DiracId) of 300 Fibonacci Diracs with masses from 1 (south) to 10 (north pole), over the
  dual convex-hull triangulation (port 0): cells grow towards the north.

    TestSphereImage.py BASELINE_DIR TEMP_DIR

A missing baseline makes the test write the rendered image into TEMP_DIR and fail: look at it
before committing it as the baseline. Needs an X display (CMake runs it under xvfb-run)."""

import math
import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "..", "Examples"))

import numpy as np  # noqa: E402
from area_preserving_demo import new_window, render_to_png  # noqa: E402
from ot_solver_demo import render_png as render_power_diagram  # noqa: E402
from sphere_demo import render_circles  # noqa: E402
from otparam import vtkAreaPreservingParam, vtkSphericalOTSolver  # noqa: E402
from otparam_test_utils import (check, check_image, field_value, fibonacci_sphere_points,  # noqa: E402,E501
                                finish, image_test_arguments, make_sphere_diracs, read_mesh,
                                shared_mesh)
from vtkmodules.util.numpy_support import numpy_to_vtk, numpy_to_vtkIdTypeArray, vtk_to_numpy  # noqa: E402,E501
from vtkmodules.vtkCommonCore import vtkPoints, vtkUnsignedCharArray  # noqa: E402
from vtkmodules.vtkCommonDataModel import vtkCellArray, vtkImageData, vtkPolyData  # noqa: E402

baseline_dir, _ = image_test_arguments()


def checker_image(width=720, height=360, columns=24, rows=12):
    """A longitude/latitude checkerboard: columns x rows cells, light and dark, the hue running
    once around with the longitude (so the seam and the orientation show)."""
    import colorsys
    u = (np.arange(width) + 0.5) / width
    v = (np.arange(height) + 0.5) / height
    U, V = np.meshgrid(u, v)
    dark = ((np.floor(U * columns) + np.floor(V * rows)) % 2).astype(bool)
    rgb = np.array([colorsys.hsv_to_rgb(h, 0.55, 0.95) for h in u])[None, :, :] \
        * np.ones((height, 1, 1))
    rgb[dark] *= 0.45
    colors = numpy_to_vtk(np.ascontiguousarray((255 * rgb).reshape(-1, 3).astype(np.uint8)),
                          deep=True, array_type=vtkUnsignedCharArray().GetDataType())
    image = vtkImageData()
    image.SetDimensions(width, height, 1)
    image.GetPointData().SetScalars(colors)
    return image


def per_corner_textured(mesh, triangles, tcoords):
    """Every triangle of `mesh` with its own three points (carrying the mesh's smooth point
    normals), so that a triangle across the longitude seam (u jumping from near 1 to near 0)
    gets u + 1 on its small side instead of the whole texture squeezed into it (the texture
    repeats)."""
    from vtkmodules.vtkFiltersCore import vtkPolyDataNormals
    normals = vtkPolyDataNormals()
    normals.SetInputData(mesh)
    normals.SplittingOff()
    normals.ConsistencyOff()
    normals.Update()
    points = vtk_to_numpy(mesh.GetPoints().GetData())
    point_normals = vtk_to_numpy(normals.GetOutput().GetPointData().GetNormals())
    uv = tcoords[triangles].copy()
    seam = uv[:, :, 0].max(axis=1) - uv[:, :, 0].min(axis=1) > 0.5
    low = seam[:, None] & (uv[:, :, 0] < 0.5)
    uv[:, :, 0][low] += 1.0
    data = vtkPolyData()
    vtk_points = vtkPoints()
    vtk_points.SetData(numpy_to_vtk(np.ascontiguousarray(points[triangles.ravel()], float),
                                    deep=True))
    data.SetPoints(vtk_points)
    n = len(triangles)
    cells = np.hstack([np.full((n, 1), 3), np.arange(3 * n).reshape(n, 3)]).ravel()
    polys = vtkCellArray()
    polys.SetCells(n, numpy_to_vtkIdTypeArray(np.ascontiguousarray(cells, np.int64), deep=True))
    data.SetPolys(polys)
    data.GetPointData().SetNormals(numpy_to_vtk(
        np.ascontiguousarray(point_normals[triangles.ravel()], float), deep=True))
    data.GetPointData().SetTCoords(numpy_to_vtk(np.ascontiguousarray(uv.reshape(-1, 2)),
                                                deep=True))
    return data


def render_texture(surface, sphere, size):
    from vtkmodules.vtkRenderingCore import vtkActor, vtkPolyDataMapper, vtkRenderer, vtkTexture
    texture = vtkTexture()
    texture.SetInputData(checker_image())
    texture.InterpolateOn()
    texture.RepeatOn()
    window = new_window(size, size // 2)
    tcoords = vtk_to_numpy(surface.GetPointData().GetTCoords())
    triangles = vtk_to_numpy(surface.GetPolys().GetConnectivityArray()).reshape(-1, 3)
    # The cow (y up, head towards +z) from its left side; the sphere from its equator, north up.
    for data, left, view, up in ((surface, 0.0, (1.0, 0.35, 0.45), (0.0, 1.0, 0.0)),
                                 (sphere, 0.5, (0.6, -1.0, 0.35), (0.0, 0.0, 1.0))):
        textured = per_corner_textured(data, triangles, tcoords)
        mapper = vtkPolyDataMapper()
        mapper.SetInputData(textured)
        mapper.ScalarVisibilityOff()
        actor = vtkActor()
        actor.SetMapper(mapper)
        actor.SetTexture(texture)
        actor.GetProperty().SetAmbient(0.3)
        actor.GetProperty().SetDiffuse(0.7)
        renderer = vtkRenderer()
        renderer.SetViewport(left, 0.0, left + 0.5, 1.0)
        renderer.SetBackground(1.0, 1.0, 1.0)
        renderer.AddActor(actor)
        renderer.ResetCamera()
        camera = renderer.GetActiveCamera()
        focal = camera.GetFocalPoint()
        distance = camera.GetDistance()
        norm = math.sqrt(sum(c * c for c in view))
        camera.SetPosition(*(focal[k] + distance * view[k] / norm for k in range(3)))
        camera.SetViewUp(*up)
        camera.OrthogonalizeViewUp()
        renderer.ResetCamera()
        camera.Zoom(1.25)
        window.AddRenderer(renderer)
    return render_to_png(window, None)


# ---- (a) spot through the sphere, textured.
spot = read_mesh(shared_mesh("spot_closed_3k.obj"))
param = vtkAreaPreservingParam()
param.SetInputData(spot)
param.Update()
out, sphere = param.GetOutput(0), param.GetOutput(1)
check(field_value(out, "Domain") == 2, "spot: Automatic picked the sphere")
check(field_value(out, "Converged") == 1 and field_value(out, "FlippedTriangles") == 0,
      "spot: transport converged, no flipped triangle")
tc = out.GetPointData().GetTCoords()
check(tc is not None and tc.GetName() == "SphericalTextureCoordinates",
      "spot: texture coordinates SphericalTextureCoordinates")

# ---- (b) the spherical power diagram of 300 Diracs, masses 1 (south) to 10 (north).
points = fibonacci_sphere_points(300)
solver = vtkSphericalOTSolver()
solver.SetInputData(make_sphere_diracs(points, [10.0 ** (0.5 * (1.0 + p[2])) for p in points]))
solver.Update()
diagram = solver.GetOutput(1)
check(field_value(solver.GetOutput(0), "Converged") == 1, "300 Diracs: the solver converges")
check(diagram.GetNumberOfCells() == 300, "300 Diracs: 300 cells in the power diagram")

# Under Xvfb, Debian's VTK 9.2 renders the first picture of a process black: draw one to waste.
render_power_diagram(solver, None, 200)
pictures = {
    "texture": render_texture(out, sphere, 1000),
    "circles": render_circles(out, None, 800, circles=40, radius=0.22),
    "power_diagram": render_power_diagram(solver, None, 600),
}
# The diagram seen from 20 degrees above the equator, north up: the cells grow northwards.
window = pictures["power_diagram"]
camera = window.GetRenderers().GetFirstRenderer().GetActiveCamera()
camera.Elevation(-70.0)
camera.OrthogonalizeViewUp()
window.GetRenderers().GetFirstRenderer().ResetCameraClippingRange()
window.Render()
for name, window in pictures.items():
    check_image(window, os.path.join(baseline_dir, f"TestSphereImage_{name}.png"), f"{name}: ")
finish()
