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

import math
import sys
from collections import defaultdict

import numpy as np
from otparam import vtkAreaPreservingParam
from vtkmodules.util.numpy_support import numpy_to_vtk, vtk_to_numpy
from vtkmodules.vtkCommonCore import vtkPoints
from vtkmodules.vtkCommonDataModel import vtkPolyData
from vtkmodules.vtkFiltersCore import vtkDelaunay2D


def deep_cap(n, half_angle_deg=150.0, seed=1):
    """Spherical cap around +z, Delaunay on the sphere (via stereographic projection from -z)."""
    rng = np.random.default_rng(seed)
    zmin = math.cos(math.radians(half_angle_deg))
    area = 2 * math.pi * (1 - zmin)
    spacing = math.sqrt(area / n * 2 / math.sqrt(3))
    rb = math.sin(math.radians(half_angle_deg))
    nb = int(round(2 * math.pi * rb / spacing))
    ni = n - nb
    z = rng.uniform(zmin, 1.0, 12 * ni)  # uniform on the sphere: z uniform
    phi = rng.uniform(0, 2 * math.pi, 12 * ni)
    s = np.sqrt(1 - z * z)
    pts = np.c_[s * np.cos(phi), s * np.sin(phi), z]
    # Half a spacing away from the boundary circle, then thinned greedily to a minimum
    # distance (no slivers), cells of a bucket grid holding the points kept.
    polar = np.arccos(np.clip(pts[:, 2], -1, 1))
    pts = pts[polar < math.radians(half_angle_deg) - 0.5 * spacing]
    keep, grid, r = [], defaultdict(list), 0.6 * spacing

    def too_close(p, key):
        neighbours = ((key[0] + dx, key[1] + dy, key[2] + dz)
                      for dx in (-1, 0, 1) for dy in (-1, 0, 1) for dz in (-1, 0, 1))
        return any(np.dot(p - q, p - q) < r * r for cell in neighbours for q in grid[cell])

    for p in pts:
        key = tuple((p // r).astype(int))
        if not too_close(p, key):
            grid[key].append(p)
            keep.append(p)
        if len(keep) >= ni:
            break
    ang = np.arange(nb) * 2 * math.pi / nb
    bnd = np.c_[rb * np.cos(ang), rb * np.sin(ang), np.full(nb, zmin)]
    allp = np.vstack([np.array(keep), bnd])
    proj = allp[:, :2] / (1 + allp[:, 2:3])
    planar = vtkPoints()
    planar.SetData(numpy_to_vtk(np.c_[proj, np.zeros(len(proj))], deep=1))
    pd = vtkPolyData()
    pd.SetPoints(planar)
    delaunay = vtkDelaunay2D()
    delaunay.SetInputData(pd)
    delaunay.Update()
    out = vtkPolyData()
    out.DeepCopy(delaunay.GetOutput())
    lifted = vtkPoints()
    lifted.SetDataTypeToDouble()
    lifted.SetData(numpy_to_vtk(allp, deep=1))
    out.SetPoints(lifted)
    return out


def lambert(points, half_angle_deg=150.0):
    """Lambert's azimuthal equal-area projection of the cap, scaled to the unit disk."""
    x, y, z = points.T
    scale = math.sin(math.radians(half_angle_deg / 2))
    return np.c_[x, y] / np.sqrt(2 * (1 + z))[:, None] / scale


def best_rotation_error(uv, exact):
    """Largest and mean distance after the best rotation (and either orientation)."""
    best = None
    for flip in (1.0, -1.0):
        mirrored = exact * [1, flip]
        angle = math.atan2((mirrored[:, 0] * uv[:, 1] - mirrored[:, 1] * uv[:, 0]).sum(),
                           (mirrored * uv).sum())
        rotation = np.array([[math.cos(angle), -math.sin(angle)],
                             [math.sin(angle), math.cos(angle)]])
        error = np.linalg.norm(uv - mirrored @ rotation.T, axis=1)
        if best is None or error.max() < best[0]:
            best = (error.max(), error.mean(), error)
    return best


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
