"""vtkConformalDiskMap on every shared mesh: no flips, boundary on the circle, distortion
below CGAL's discrete conformal map, its own figures equal to those of the reference scorer,
and the output arrays, ids, progress and abort behave as documented."""

import math
import time

import numpy as np
from otparam import vtkConformalDiskMap
from otparam_test_utils import (MessageRecorder, check_abort, check, field_value, finish,
                                make_domain, param_metrics, read_mesh, same, shared_mesh,
                                snapshot)
from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.vtkCommonCore import vtkCommand

# CGAL 5.5.1 DCM on each mesh (reference-figures.md): mean angle error (degrees), mean K.
CGAL = {
    "hand_stein_810.obj": (10.28, 1.480),
    "hemisphere_2k.obj": (0.65, 1.020),
    "face_dense_gpp_5k.obj": (2.96, 1.152),
    "face_choi_bff_17k.obj": (6.57, 1.328),
    "chinese_lion_17k.off": (2.64, 1.100),
    "ogre_face_20k.obj": (3.57, 1.166),
    "face_maxplanck_partial_32k.obj": (3.76, 1.168),
    "brain_cortex_cut_48k.off": (2.85, 1.104),
    "hand_choi_53k.off": (2.49, 1.086),
    "bust_aphrodite_56k.obj": (None, None),
}
# The hemisphere's conformal boundary is arc length by symmetry, CGAL's choice: both maps
# reach K = 1.0202650, above the table's rounded 1.020; compare at the table's precision.
K_ROUNDING = {"hemisphere_2k.obj": 5e-4}

scorer = param_metrics()


def arrays(data):
    return vtk_to_numpy(data.GetPoints().GetData()), vtk_to_numpy(
        data.GetPolys().GetConnectivityArray()).reshape(-1, 3)


print(f"{'mesh':32s} {'verts':>6s} {'s':>6s} {'angle':>7s} {'CGAL':>6s} {'K':>7s} "
      f"{'CGAL':>6s} {'ears':>4s} {'its':>4s}")
for name, (cgal_angle, cgal_k) in CGAL.items():
    surface = read_mesh(shared_mesh(name))
    before = snapshot(surface) if surface.GetNumberOfPoints() < 3000 else None
    mapper = vtkConformalDiskMap()
    mapper.SetInputData(surface)
    errors = MessageRecorder(mapper)
    start = time.perf_counter()
    mapper.Update()
    seconds = time.perf_counter() - start
    out = mapper.GetOutput()
    check(not errors.messages, f"{name}: no error ({errors.text()})")
    if out.GetNumberOfPoints() == 0:
        continue
    figures = {k: field_value(out, k) for k in (
        "MeanAngleDistortion", "MaximumAngleDistortion", "MeanQuasiConformalDilatation",
        "FlippedTriangles", "MaximumBoundaryRadiusError", "ClippedEars", "Iterations",
        "MeanAbsLogAreaRatio", "MaximumAbsLogAreaRatio", "CenterPointId", "AlignPointId")}
    print(f"{name:32s} {surface.GetNumberOfPoints():6d} {seconds:6.2f} "
          f"{figures['MeanAngleDistortion']:7.3f} {cgal_angle or 0:6.2f} "
          f"{figures['MeanQuasiConformalDilatation']:7.4f} {cgal_k or 0:6.3f} "
          f"{int(figures['ClippedEars']):4d} {int(figures['Iterations']):4d}", flush=True)

    p3, triangles = arrays(surface)
    uv_points, out_triangles = arrays(out)
    check(np.array_equal(triangles, out_triangles), f"{name}: same triangles in the same order")
    check(figures["FlippedTriangles"] == 0, f"{name}: no flipped triangle")
    check(figures["MaximumBoundaryRadiusError"] <= 1e-12, f"{name}: boundary on the circle")
    check(np.all(uv_points[:, 2] == 0.0), f"{name}: points in z = 0")
    if cgal_angle is not None:
        check(figures["MeanAngleDistortion"] < cgal_angle, f"{name}: angle below CGAL DCM")
        check(figures["MeanQuasiConformalDilatation"] < cgal_k + K_ROUNDING.get(name, 0.0),
              f"{name}: K below CGAL DCM")

    # The figures agree with the reference scorer on the same data.
    uv = vtk_to_numpy(out.GetPointData().GetTCoords())
    check(np.array_equal(uv, uv_points[:, :2]), f"{name}: texture coordinates = (u, v)")
    reference = scorer.score(p3.astype(float), triangles.astype(int), uv.astype(float))
    for ours, theirs in (("MeanAngleDistortion", "angle_mean_abs_deg"),
                         ("MeanQuasiConformalDilatation", "qc_K_mean"),
                         ("MeanAbsLogAreaRatio", "area_mean_abs_log"),
                         ("MaximumAbsLogAreaRatio", "area_max_abs_log"),
                         ("FlippedTriangles", "flips"),
                         ("MaximumBoundaryRadiusError", "boundary_radius_err")):
        tolerance = 1e-12 if ours == "MaximumBoundaryRadiusError" else 1e-9 * abs(reference[theirs]) + 1e-12
        check(abs(figures[ours] - reference[theirs]) <= tolerance,
              f"{name}: {ours} {figures[ours]} = scorer's {theirs} {reference[theirs]}")

    # Arrays: Coordinates3D are the input points; the density integrates to pi over the image.
    check(np.array_equal(vtk_to_numpy(out.GetPointData().GetArray("Coordinates3D")), p3),
          f"{name}: Coordinates3D = input points")
    a, b, c = (uv_points[out_triangles[:, k], :2] for k in range(3))
    disk_area = 0.5 * ((b[:, 0] - a[:, 0]) * (c[:, 1] - a[:, 1]) - (b[:, 1] - a[:, 1]) * (c[:, 0] - a[:, 0]))
    density = vtk_to_numpy(out.GetCellData().GetArray("AreaDensity"))
    check(abs((density * disk_area).sum() - math.pi) < 1e-9, f"{name}: AreaDensity integrates to pi")
    point_density = vtk_to_numpy(out.GetPointData().GetArray("AreaDensity"))
    check(np.all(point_density > 0) and np.all(np.isfinite(point_density)),
          f"{name}: point AreaDensity positive")
    ids = vtk_to_numpy(out.GetPointData().GetArray("vtkOriginalPointIds"))
    check(np.array_equal(ids, np.arange(len(p3))), f"{name}: identity vtkOriginalPointIds")
    center = int(figures["CenterPointId"])
    align = int(figures["AlignPointId"])
    check(np.hypot(*uv[center]) < 1e-14, f"{name}: centre point at the origin")
    check(uv[align, 0] == 1.0 and uv[align, 1] == 0.0, f"{name}: align point at (1, 0)")
    if before is not None:
        check(same(snapshot(surface), before), f"{name}: input not modified")

# Chosen centre and align points, progress and abort on the coarse hand.
surface = read_mesh(shared_mesh("hand_stein_810.obj"))
mapper = vtkConformalDiskMap()
mapper.SetInputData(surface)
mapper.Update()
out = mapper.GetOutput()
uv = vtk_to_numpy(out.GetPointData().GetTCoords())
radius = np.hypot(uv[:, 0], uv[:, 1])
interior = int(np.argmax((radius > 0.3) & (radius < 0.6)))
boundary = [int(i) for i in np.nonzero(np.abs(radius - 1.0) < 1e-12)[0]]
mapper.SetCenterPointId(interior)
mapper.SetAlignPointId(boundary[3])
progress = []
mapper.AddObserver(vtkCommand.ProgressEvent, lambda obj, _e: progress.append(obj.GetProgress()))
mapper.Update()
uv = vtk_to_numpy(mapper.GetOutput().GetPointData().GetTCoords())
check(np.hypot(*uv[interior]) < 1e-14, "CenterPointId goes to the origin")
check(uv[boundary[3], 0] == 1.0 and uv[boundary[3], 1] == 0.0, "AlignPointId goes to (1, 0)")
check(len(progress) >= 3 and progress[-1] == 1.0 and progress == sorted(progress),
      f"progress reported and increasing ({len(progress)} events)")

aborting = vtkConformalDiskMap()
aborting.SetInputData(surface)
aborting.SetMaximumNumberOfIterations(50)
check_abort(aborting, after=0.1)

# A closed scan with one small hole (a triangle cut out of the spot) is a disk, but the map
# squeezes the whole surface through it: a warning names the hole's size and the sphere.
spot = read_mesh(shared_mesh("spot_closed_3k.obj"))
spot_triangles = vtk_to_numpy(spot.GetPolys().GetConnectivityArray()).reshape(-1, 3)
holed = make_domain(vtk_to_numpy(spot.GetPoints().GetData()).tolist(),
                    [tuple(int(v) for v in t) for k, t in enumerate(spot_triangles) if k != 500])
small = vtkConformalDiskMap()
small.SetInputData(holed)
warnings = MessageRecorder(small, vtkCommand.WarningEvent)
small.Update()
check(small.GetOutput().GetNumberOfPoints() == holed.GetNumberOfPoints()
      and "boundary loop is small" in warnings.text() and "vtkConformalSphereMap" in warnings.text(),
      f"spot with one small hole: mapped, with a warning that names the sphere ({warnings.text()})")

finish()
