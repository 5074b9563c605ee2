"""The crowding tests' surfaces (TestCrowding.py on the disk, TestCrowdingSphere.py on the
sphere) and the run both use."""

import math

from otparam import vtkAreaPreservingParam
from otparam_test_utils import MessageRecorder, field_value, make_domain
from vtkmodules.vtkCommonCore import vtkCommand


def finger(length_over_radius, rho=0.2, n=24, closed=False):
    """The disk with a finger; closed: with a half sphere below the disk (genus 0)."""
    h = 2 * math.pi / n  # spacing relative to the local radius
    rings = []  # (r, z)
    if closed:
        below = max(2, int(round((math.pi / 2) / h)))
        rings += [(math.cos(a), math.sin(a))
                  for a in (-math.pi / 2 + k * (math.pi / 2) / below for k in range(1, below))]
    r = 1.0
    while r > rho * (1 + 0.5 * h):
        rings.append((r, 0.0))
        r *= math.exp(-h)
    # A sharp bend from the plane into the tube, as scans have.
    z = 0.0
    length = length_over_radius * rho
    while z < length:
        rings.append((rho, z))
        z += h * rho
    cap = max(2, int(round((math.pi / 2) / h)))
    for k in range(cap):
        a = (k / cap) * math.pi / 2
        rings.append((rho * math.cos(a), length + rho * math.sin(a)))
    points, triangles = [], []
    for k, (r, z) in enumerate(rings):
        off = 0.5 * (k % 2)
        for j in range(n):
            a = 2 * math.pi * (j + off) / n
            points.append((r * math.cos(a), r * math.sin(a), z))
    for k in range(len(rings) - 1):
        a0, b0 = k * n, (k + 1) * n
        for j in range(n):
            j1 = (j + 1) % n
            if k % 2 == 0:
                triangles += [(a0 + j, b0 + j, a0 + j1), (a0 + j1, b0 + j, b0 + j1)]
            else:
                triangles += [(a0 + j, b0 + j, b0 + j1), (a0 + j, b0 + j1, a0 + j1)]
    tip = len(points)
    points.append((0.0, 0.0, length + rho))
    last = (len(rings) - 1) * n
    for j in range(n):
        triangles.append((last + j, tip, last + (j + 1) % n))
    if closed:
        south = len(points)
        points.append((0.0, 0.0, -1.0))
        triangles += [(j, (j + 1) % n, south) for j in range(n)]
    return make_domain(points, triangles)


def square_fingers(lengths, n=24, closed=False):
    """An n x n grid of unit cells with, per finger, a 2 x 2-cell hole whose 8-point loop is
    extruded into a square tube of that many cells (one ring per cell), capped by a point:
    coarser tubes than finger()'s, several on one disk. `closed`: the grid's rim joined to an
    apex 4 above its centre, a closed surface with the fingers as limbs."""
    index, points, triangles = {}, [], []

    def point(x, y, z=0.0):
        if (x, y, z) not in index:
            index[(x, y, z)] = len(points)
            points.append((float(x), float(y), float(z)))
        return index[(x, y, z)]
    centres = [(4 + 6 * k, n // 2) for k in range(len(lengths))]
    holes = {(cx + i, cy + j) for cx, cy in centres for i in (-1, 0) for j in (-1, 0)}
    for i in range(n):
        for j in range(n):
            if (i, j) in holes:
                continue
            a, b, c, d = point(i, j), point(i + 1, j), point(i + 1, j + 1), point(i, j + 1)
            triangles += [(a, b, c), (a, c, d)] if (i + j) % 2 else [(a, b, d), (b, c, d)]
    for (cx, cy), length in zip(centres, lengths):
        loop = [(cx - 1, cy - 1), (cx, cy - 1), (cx + 1, cy - 1), (cx + 1, cy),
                (cx + 1, cy + 1), (cx, cy + 1), (cx - 1, cy + 1), (cx - 1, cy)]
        previous = [point(x, y) for x, y in loop]
        for k in range(1, length + 1):
            ring = [point(x, y, -k) for x, y in loop]
            for m in range(8):
                a, b = previous[m], previous[(m + 1) % 8]
                triangles += [(a, b, ring[m]), (b, ring[(m + 1) % 8], ring[m])]
            previous = ring
        tip = point(cx, cy, -length - 1)
        triangles += [(previous[(m + 1) % 8], tip, previous[m]) for m in range(8)]
    if closed:
        rim = ([(i, 0) for i in range(n)] + [(n, j) for j in range(n)]
               + [(i, n) for i in range(n, 0, -1)] + [(0, j) for j in range(n, 0, -1)])
        rim = [point(x, y) for x, y in rim]
        apex = point(n / 2, n / 2, 4.0)
        triangles += [(rim[(k + 1) % len(rim)], rim[k], apex) for k in range(len(rim))]
    return make_domain(points, triangles)


def quadruped(leg=2.0, tail=1.6, tail_radius=0.06, resolution=160):
    """A procedural four-legged animal, closed (genus 0): an ellipsoid body with four legs
    (capsules of radius 0.11 and length 0.8 + `leg`), a tail (a bent chain of capsules of
    `tail_radius`, `tail` long), a neck and a head, blended by a smooth minimum and extracted by
    flying edges on a grid of `resolution` cells along its longest side: a marching-cubes mesh
    as scans give, slivers included. The default's legs hang about 2.5 below the body, L / rho
    ~23, and its tail is L / rho ~24."""
    import numpy as np
    from vtkmodules.util.numpy_support import numpy_to_vtk
    from vtkmodules.vtkCommonDataModel import vtkImageData
    from vtkmodules.vtkFiltersCore import (vtkCleanPolyData, vtkFlyingEdges3D,
                                           vtkPolyDataConnectivityFilter)

    lo = np.array([-1.5 - tail, -0.8, -1.3 - leg])
    hi = np.array([2.5, 0.8, 1.4 + 0.5 * tail])
    n = np.ceil((hi - lo) / ((hi - lo).max() / resolution)).astype(int) + 1
    grid = np.stack(np.meshgrid(*[np.linspace(lo[k], hi[k], n[k]) for k in range(3)],
                                indexing="ij"), axis=-1)

    def capsule(a, b, r):
        a, b = np.array(a), np.array(b)
        h = np.clip(((grid - a) @ (b - a)) / ((b - a) @ (b - a)), 0.0, 1.0)
        return np.linalg.norm(grid - a - h[..., None] * (b - a), axis=-1) - r

    def blend(f, g, k=0.08):
        h = np.clip(0.5 + 0.5 * (g - f) / k, 0.0, 1.0)
        return g * (1 - h) + f * h - k * h * (1 - h)

    f = 0.45 * (np.linalg.norm(grid / np.array([1.3, 0.5, 0.45]), axis=-1) - 1.0)
    for x in (-0.9, 0.9):
        for y in (-0.25, 0.25):
            f = blend(f, capsule((x, y, -0.1), (x, y, -0.9 - leg), 0.11))
    start, along = np.array([-1.2, 0.0, 0.15]), np.array([-1.0, 0.0, 0.4]) / math.hypot(1.0, 0.4)
    bend = [start + (k / 12) * tail * along + (0, 0, 0.1 * math.sin(k / 4)) for k in range(13)]
    for a, b in zip(bend, bend[1:]):
        f = blend(f, capsule(a, b, tail_radius), 0.03)
    f = blend(f, capsule((1.1, 0, 0.2), (1.7, 0, 0.9), 0.18))
    f = blend(f, 0.22 * (np.linalg.norm((grid - (1.95, 0, 1.0)) / (0.4, 0.22, 0.22), axis=-1) - 1))
    image = vtkImageData()
    image.SetDimensions(*(int(k) for k in n))
    image.SetOrigin(*lo)
    image.SetSpacing(*((hi - lo) / (n - 1)))
    image.GetPointData().SetScalars(numpy_to_vtk(f.transpose(2, 1, 0).ravel().copy()))
    surface = vtkFlyingEdges3D()
    surface.SetInputData(image)
    surface.SetValue(0, 0.0)
    surface.ComputeNormalsOff()
    largest = vtkPolyDataConnectivityFilter()
    largest.SetInputConnection(surface.GetOutputPort())
    largest.SetExtractionModeToLargestRegion()
    clean = vtkCleanPolyData()
    clean.SetInputConnection(largest.GetOutputPort())
    clean.Update()
    return clean.GetOutput()


def opened_at(surface, x):
    """`surface` with the part beyond the plane at `x` (normal along +x) clipped off, as a user
    opens a closed surface with VTK's clip filter: one boundary loop where the plane cuts."""
    from vtkmodules.vtkCommonDataModel import vtkPlane
    from vtkmodules.vtkFiltersCore import vtkClipPolyData, vtkCleanPolyData, vtkTriangleFilter

    plane = vtkPlane()
    plane.SetOrigin(x, 0.0, 0.0)
    plane.SetNormal(-1.0, 0.0, 0.0)
    clip = vtkClipPolyData()
    clip.SetInputData(surface)
    clip.SetClipFunction(plane)
    clean = vtkCleanPolyData()
    clean.SetInputConnection(clip.GetOutputPort())
    triangles = vtkTriangleFilter()
    triangles.SetInputConnection(clean.GetOutputPort())
    triangles.Update()
    return triangles.GetOutput()


def run(length_over_radius, closed=False):
    param = vtkAreaPreservingParam()
    param.SetInputData(finger(length_over_radius, closed=closed))
    errors = MessageRecorder(param)
    warnings = MessageRecorder(param, vtkCommand.WarningEvent)
    param.Update()
    out = param.GetOutput()
    fig = {}
    if out.GetNumberOfPoints():
        fig = {k: field_value(out, k) for k in (
            "Converged", "RelativeError", "FlippedTriangles", "MeanAbsLogAreaRatio",
            "ConformalMaximumAbsLogAreaRatio", "TransportStages", "Domain")}
    print(f"{'closed, ' if closed else ''}L/rho {length_over_radius:4.1f}: {fig}", flush=True)
    return fig, errors, warnings
