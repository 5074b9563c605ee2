"""The deep spherical cap against its exact area-preserving map (issue 20's faithful-composition
check): a cap of half-angle 150 degrees, Delaunay on the sphere (stereographic projection, then
vtkDelaunay2D), mapped by vtkAreaPreservingParam with the area correction on and off, each
compared with Lambert's azimuthal equal-area projection (scaled to the unit disk) after the best
rotation. Also prints Lambert's own mean |log area ratio| on the mesh: the per-triangle area
error of the exact map at this resolution.

Usage (from the repository, after building):
  PYTHONPATH=build/lib/python3/dist-packages /usr/bin/python3 \
      Testing/Benchmark/cap_vs_lambert.py [vertices (6000)]
"""

import os
import sys

import numpy as np
from otparam import vtkAreaPreservingParam
from vtkmodules.util.numpy_support import vtk_to_numpy

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "Python"))
from deep_cap import best_rotation_error, deep_cap, lambert  # noqa: E402


def area_error(points, triangles, uv):
    """Mean (area-weighted) and largest |log area ratio| of a map given at the vertices."""
    a, b, c = (points[triangles[:, k]] for k in range(3))
    surface = 0.5 * np.linalg.norm(np.cross(b - a, c - a), axis=1)
    p, q, r = (uv[triangles[:, k]] for k in range(3))
    disk = 0.5 * np.abs((q - p)[:, 0] * (r - p)[:, 1] - (q - p)[:, 1] * (r - p)[:, 0])
    fraction = surface / surface.sum()
    log_ratio = np.log(disk / disk.sum() / fraction)
    return (fraction * np.abs(log_ratio)).sum(), np.abs(log_ratio).max()


def main():
    cap = deep_cap(int(sys.argv[1]) if len(sys.argv) > 1 else 6000)
    points = vtk_to_numpy(cap.GetPoints().GetData())
    triangles = vtk_to_numpy(cap.GetPolys().GetConnectivityArray()).reshape(-1, 3)
    lam_mean, lam_max = area_error(points, triangles, lambert(points))
    print(f"cap of 150 degrees: {cap.GetNumberOfPoints()} vertices; Lambert's own mean |log area "
          f"ratio| {lam_mean:.4f} (max {lam_max:.2f})")
    print("| area correction | max distance | mean distance | mean |log area ratio| | flips |")
    print("|---|---|---|---|---|")
    for correction in (1, 0):
        param = vtkAreaPreservingParam()
        param.SetInputData(cap)
        param.SetAreaCorrection(correction)
        param.Update()
        out = param.GetOutput()
        uv = vtk_to_numpy(out.GetPointData().GetArray("AreaPreservingCoordinates"))
        largest, mean, _ = best_rotation_error(uv, lambert(points))
        field = out.GetFieldData()
        print(f"| {'on' if correction else 'off'} | {largest:.4f} | {mean:.5f} | "
              f"{field.GetArray('MeanAbsLogAreaRatio').GetValue(0):.4f} | "
              f"{field.GetArray('FlippedTriangles').GetValue(0):.0f} |")


if __name__ == "__main__":
    main()
