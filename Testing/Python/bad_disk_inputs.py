"""Bad disk-like surfaces (and bad normalization point ids), shared by the bad-input tests of
vtkConformalDiskMap and vtkAreaPreservingParam, plus the good disk they are variations of."""

import math

from otparam_test_utils import add_cells, grid_triangle_list, make_domain
from vtkmodules.vtkCommonCore import vtkDoubleArray, vtkIntArray
from vtkmodules.vtkCommonDataModel import vtkCellArray, vtkPolyData
from vtkmodules.vtkFiltersSources import vtkSphereSource

N = 5  # the good disk: an N x N grid of points, 2 (N-1)^2 triangles
CENTRE = (N * N) // 2  # the grid's middle point, interior
NAN, INF = float("nan"), float("inf")


def grid_points(n=N, x0=-1.0, y0=-1.0, size=2.0):
    """Row-major n x n grid on the square [x0, x0 + size] x [y0, y0 + size], lifted to the
    paraboloid z = 0.3 (x^2 + y^2) so the surface is not flat."""
    points = []
    for j in range(n):
        for i in range(n):
            x, y = x0 + size * i / (n - 1), y0 + size * j / (n - 1)
            points.append((x, y, 0.3 * (x * x + y * y)))
    return points


def grid_triangles(n=N, offset=0):
    return grid_triangle_list(n, offset)


def with_arrays(data):
    """Adds a point array and a cell array (the snapshot then also watches them)."""
    height = vtkDoubleArray()
    height.SetName("Height")
    for i in range(data.GetNumberOfPoints()):
        height.InsertNextValue(0.5 * i)
    data.GetPointData().AddArray(height)
    label = vtkIntArray()
    label.SetName("Label")
    for c in range(data.GetNumberOfCells()):
        label.InsertNextValue(c)
    data.GetCellData().AddArray(label)
    return data


def mesh(points, triangles):
    return with_arrays(make_domain(points, triangles))


def good_disk():
    """25 points, 32 triangles, one boundary loop of 16 points, 9 interior points."""
    return mesh(grid_points(), grid_triangles())



def replace_triangle(index, new):
    triangles = grid_triangles()
    triangles[index] = new
    return mesh(grid_points(), triangles)


def with_point(index, xyz):
    data = good_disk()
    data.GetPoints().SetPoint(index, *xyz)
    return data


def with_unreferenced_point(index, xyz=(5.0, 5.0, 5.0)):
    """The good disk with one more point, used by no triangle, inserted as input point
    `index` (later points and the triangles' ids shift by one)."""
    points = grid_points()
    points.insert(index, xyz)
    triangles = [tuple(v + 1 if v >= index else v for v in t) for t in grid_triangles()]
    return mesh(points, triangles)


def nan_after_unreferenced_point():
    # Grid point 12 is input point 13 here; the message must name 13.
    data = with_unreferenced_point(3)
    data.GetPoints().SetPoint(CENTRE + 1, 0.0, NAN, 0.0)
    return data


def points_only():
    data = good_disk()
    data.SetPolys(vtkCellArray())
    return data



def strips_only():
    # The good grid as triangle strips, one per row: a surface, but not made of triangles.
    data = make_domain(grid_points(), [])
    strips = []
    for j in range(N - 1):
        strip = []
        for i in range(N):
            strip += [j * N + i, (j + 1) * N + i]
        strips.append(strip)
    return add_cells(data, "Strips", strips)


def with_quad():
    # Grid square 2 as one quad (cell 4) instead of triangles 4 and 5.
    triangles = grid_triangles()
    a, b, c = triangles[4]
    d = triangles[5][2]
    triangles[4:6] = [(a, b, c, d)]
    return mesh(grid_points(), triangles)


def sphere():
    source = vtkSphereSource()
    source.SetThetaResolution(8)
    source.SetPhiResolution(6)
    source.Update()
    data = vtkPolyData()
    data.DeepCopy(source.GetOutput())
    return data


def annulus(segments=12, radii=(0.5, 0.75, 1.0)):
    # (vtkDiskSource of this VTK orders its points wrongly: vtkTriangleFilter then drops all
    # its quads; and with inner radius 0 it keeps `segments` copies of the centre point, so
    # it is an annulus too. Built here instead.)
    points = [(r * math.cos(2 * math.pi * k / segments), r * math.sin(2 * math.pi * k / segments),
               0.0) for r in radii for k in range(segments)]
    triangles = []
    for ring in range(len(radii) - 1):
        for k in range(segments):
            a, b = ring * segments + k, ring * segments + (k + 1) % segments
            c, d = b + segments, a + segments
            triangles += [(a, b, c), (a, c, d)]
    return mesh(points, triangles)


def torus_with_hole(nu=8, nv=6, big=2.0, small=0.7, holes=1):
    points = []
    for i in range(nu):
        for j in range(nv):
            u, v = 2 * math.pi * i / nu, 2 * math.pi * j / nv
            radius = big + small * math.cos(v)
            points.append((radius * math.cos(u), radius * math.sin(u), small * math.sin(v)))
    triangles = []
    for i in range(nu):
        for j in range(nv):
            a, b = i * nv + j, ((i + 1) % nu) * nv + j
            c, d = ((i + 1) % nu) * nv + (j + 1) % nv, i * nv + (j + 1) % nv
            triangles += [(a, b, c), (a, c, d)]
    # One square removed per hole: one boundary loop each (the second hole half way round).
    removed = [0, 2 * ((nu // 2) * nv + nv // 2)][:holes]
    triangles = [t for k, t in enumerate(triangles) if not any(k in (r, r + 1) for r in removed)]
    return mesh(points, triangles)


def three_triangles_on_an_edge():
    # Interior edge (6, 12) (the diagonal of grid square 5, triangles 10 and 11) gets a third
    # triangle through a new point above it.
    points = grid_points() + [(-0.25, -0.25, 1.0)]
    return mesh(points, grid_triangles() + [(6, 12, N * N)])


def touching_disks():
    # Second grid on [1, 3]^2: its corner (1, 1) is the first grid's corner, point 24.
    points = grid_points() + grid_points(x0=1.0, y0=1.0)[1:]
    second = [tuple(N * N - 1 if v == N * N else v - 1 for v in t)
              for t in grid_triangles(offset=N * N)]
    return mesh(points, grid_triangles() + second)


def two_disks():
    points = grid_points() + grid_points(x0=3.0, y0=0.0)
    return mesh(points, grid_triangles() + grid_triangles(offset=N * N))


def triangle_soup():
    """The good disk with no point shared: each triangle has its own three points (an STL file
    read without merging its points)."""
    points = grid_points()
    soup = [points[v] for t in grid_triangles() for v in t]
    return mesh(soup, [(3 * k, 3 * k + 1, 3 * k + 2) for k in range(len(soup) // 3)])


def slit_disk(n=7, unreferenced_first=False):
    """An n x n grid cut along the middle row's interior points but its two ends: the triangles
    above the row use copies of those points (a seam whose points are not shared, as exports
    split along texture seams), which makes the cut a second boundary loop of zero area.
    `unreferenced_first`: a point used by no triangle first, which shifts every id by one."""
    points, triangles = grid_points(n), grid_triangles(n)
    row = n // 2
    copy = {}
    for i in range(2, n - 2):
        copy[row * n + i] = len(points)
        points.append(points[row * n + i])
    above = [tuple(copy.get(v, v) for v in t) if sum(v // n for v in t) > 3 * row else t
             for t in triangles]
    if unreferenced_first:
        return mesh([(5.0, 5.0, 5.0)] + points, [tuple(v + 1 for v in t) for t in above])
    return mesh(points, above)


def zero_area():
    # Boundary edge (0, 1) of triangle 0 gets a second triangle (1, 0, m) with m its midpoint:
    # topologically still a disk, geometrically flat.
    p0, p1 = grid_points()[0], grid_points()[1]
    middle = tuple(0.5 * (a + b) for a, b in zip(p0, p1))
    return mesh(grid_points() + [middle], grid_triangles() + [(1, 0, N * N)])


def collapsed_edge():
    return with_point(CENTRE, grid_points()[CENTRE + 1])


def nearly_collapsed_edge():
    """The centre 1e-14 from its right neighbour, as a single-precision export leaves a pole's
    points (VTK's parametric ellipsoid: its triangles there have zero area)."""
    x, y, z = grid_points()[CENTRE + 1]
    return with_point(CENTRE, (x - 1e-14, y, z))


def reversed_triangle():
    a, b, c = grid_triangles()[13]
    return replace_triangle(13, (a, c, b))


def single_triangle():
    return mesh([(0, 0, 0), (1, 0, 0), (0, 1, 0)], [(0, 1, 2)])


# Inputs every filter that takes a surface must reject (vtkConformalDiskMap and the filters
# that run it): name, input, settings, words the message must contain (lower case; a tuple
# means any of them).
SURFACE_CASES = [
    ("no points", vtkPolyData(), {}, ["empty"]),
    ("points but no triangles", points_only(), {}, ["empty", "triangles"]),
    ("closed surface", sphere(), {}, ["closed", "euler characteristic 2", "vtkconformalspheremap"]),
    ("annulus without FillHoles", annulus(), {"FillHoles": 0}, ["2 boundary loops", "fillholes"]),
    ("torus with two holes", torus_with_hole(holes=2), {}, ["2 boundary loops", "genus 1"]),
    ("torus with one hole", torus_with_hole(), {}, ["genus 1", "euler characteristic -1"]),
    ("three triangles on an edge", three_triangles_on_an_edge(), {},
     [("non-manifold", "same direction"), "triangles 11 and 32", "(6, 12)"]),
    ("disks touching at a vertex", touching_disks(), {}, ["non-manifold vertex", "point 24 "]),
    ("two components", two_disks(), {}, ["2 connected components", "keep the largest"]),
    ("triangle soup", triangle_soup(), {},
     ["32 connected components", "94 of its points lie exactly where another point is",
      "vtkcleanpolydata"]),
    ("interior slit", slit_disk(), {},
     ["2 boundary loops", "through point 22) is a slit, not a hole", "6 of its points",
      "vtkcleanpolydata"]),
    ("interior slit without FillHoles", slit_disk(), {"FillHoles": 0},
     ["2 boundary loops, and boundary loop 2", "is a slit, not a hole", "vtkcleanpolydata"]),
    # Ids in messages are input ids.
    ("interior slit after an unreferenced point", slit_disk(unreferenced_first=True), {},
     ["through point 23) is a slit, not a hole"]),
    ("a quad", with_quad(), {}, ["triangle", "polygon id(s) 4 "]),
    ("triangle strip", add_cells(good_disk(), "Strips", [(0, 1, 5, 6)]), {},
     ["triangle", "1 triangle strips"]),
    ("triangle strips only", strips_only(), {}, ["triangle", "4 triangle strips"]),
    ("only line and vertex cells", add_cells(points_only(), "Lines", [(0, 1), (1, 2)]), {},
     ["no triangles", "2 line cells"]),
    ("zero-area triangle", zero_area(), {}, ["zero area", "triangle ids 32", "collinear"]),
    # The centre moved onto its right neighbour: the two triangles on their edge collapse, and
    # the message names the clean that removes them (TestAreaPreservingParamBadInput runs it).
    ("coincident points", collapsed_edge(), {},
     ["zero area", "coincident points", "vtkcleanpolydata", "convertpolystolines off"]),
    ("nearly coincident points", nearly_collapsed_edge(), {},
     ["zero area", "almost at the same place", "vtkcleanpolydata", "tolerance"]),
    ("NaN coordinate", with_point(12, (NAN, 0.0, 0.0)), {}, ["nan", "point ids 12"]),
    ("infinite coordinate", with_point(7, (0.0, INF, 0.0)), {}, ["infinite", "point ids 7"]),
    ("-infinite z", with_point(20, (-1.0, 1.0, -INF)), {}, ["infinite", "point ids 20"]),
    # Ids in messages are input ids, also when unreferenced points shift the mesh's ids.
    ("NaN after an unreferenced point", nan_after_unreferenced_point(), {},
     ["nan", "point ids 13"]),
    ("one triangle reversed", reversed_triangle(), {}, ["oriented", "13"]),
    ("point used twice", replace_triangle(9, (7, 8, 7)), {}, ["triangle 9", "point 7 twice"]),
    ("point id out of range", replace_triangle(9, (7, 8, 25)), {},
     ["triangle 9", "point id 25", "outside"]),
    ("negative point id", replace_triangle(9, (7, -1, 8)), {}, ["triangle 9", "point id -1"]),
    ("no interior point", single_triangle(), {}, ["no interior vertex"]),
    ("CenterPointId too large", good_disk(), {"CenterPointId": N * N},
     ["centerpointid = 25", "not a point id"]),
    ("CenterPointId < -1", good_disk(), {"CenterPointId": -2},
     ["centerpointid = -2", "not a point id"]),
    ("AlignPointId too large", good_disk(), {"AlignPointId": 1000},
     ["alignpointid = 1000", "not a point id"]),
    ("AlignPointId < -1", good_disk(), {"AlignPointId": -7},
     ["alignpointid = -7", "not a point id"]),
    ("CenterPointId on the boundary", good_disk(), {"CenterPointId": 3},
     ["centerpointid = 3", "boundary"]),
    ("AlignPointId inside", good_disk(), {"AlignPointId": CENTRE},
     ["alignpointid = 12", "not a boundary point"]),
    ("CenterPointId on no triangle", with_unreferenced_point(10), {"CenterPointId": 10},
     ["centerpointid = 10", "belongs to no triangle"]),
    ("AlignPointId on no triangle", with_unreferenced_point(25), {"AlignPointId": 25},
     ["alignpointid = 25", "belongs to no triangle"]),
]
