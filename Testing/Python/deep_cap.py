"""The deep spherical cap of issue 20's faithful-composition check, and its exact area-preserving
map: a cap of half-angle 150 degrees around +z, Delaunay on the sphere, and Lambert's azimuthal
equal-area projection scaled to the unit disk. Shared by TestAreaPreservingParam.py and
Testing/Benchmark/cap_vs_lambert.py."""

import math
from collections import defaultdict

import numpy as np
from vtkmodules.util.numpy_support import numpy_to_vtk
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
