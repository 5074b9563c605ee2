"""Helpers shared by the example scripts: surfaces (generated, read), an X display for
rendering, PNG output."""

import math
import os
import shutil
import sys


def ensure_display(args):
    """Re-runs the calling script under xvfb-run when there is no X display to render into
    (Debian's VTK renders through X only: no EGL, no OSMesa)."""
    if args.no_picture or os.environ.get("DISPLAY") or os.environ.get("OTPARAM_UNDER_XVFB"):
        return
    xvfb = shutil.which("xvfb-run")
    if xvfb is None:
        sys.exit("No X display and no xvfb-run: install xvfb or pass --no-picture.")
    os.environ["OTPARAM_UNDER_XVFB"] = "1"
    # -a searches for a free display from -n on; starting at a number of our own (not 99 as
    # every other xvfb-run does) avoids reusing a display whose server is still shutting down.
    first_display = str(200 + os.getpid() % 300)
    os.execv(xvfb, [xvfb, "-a", "-n", first_display, "-s", "-screen 0 1600x1600x24",
                    sys.executable] + sys.argv)


def save_png(window, path):
    """Writes what a vtkRenderWindow shows (back buffer) as a PNG."""
    from vtkmodules.vtkIOImage import vtkPNGWriter
    from vtkmodules.vtkRenderingCore import vtkWindowToImageFilter
    grab = vtkWindowToImageFilter()
    grab.SetInput(window)
    grab.ReadFrontBufferOff()
    grab.Update()
    writer = vtkPNGWriter()
    writer.SetFileName(path)
    writer.SetInputConnection(grab.GetOutputPort())
    writer.Write()


def ring_surface(rings, height):
    """A height field over the unit disk, z = height(x, y), sampled on concentric rings of 6k
    points (k = 1..rings, staggered ring to ring for better triangles) zipped into
    counter-clockwise triangles."""
    from vtkmodules.vtkCommonCore import vtkPoints
    from vtkmodules.vtkCommonDataModel import vtkCellArray, vtkPolyData

    points = vtkPoints()
    points.SetDataTypeToDouble()
    polys = vtkCellArray()
    points.InsertNextPoint(0.0, 0.0, height(0.0, 0.0))
    inner, inner_start = [0], 0.0
    for k in range(1, rings + 1):
        count, radius = 6 * k, k / rings
        start = (k % 2) * math.pi / count
        outer = []
        for j in range(count):
            angle = start + 2.0 * math.pi * j / count
            x, y = radius * math.cos(angle), radius * math.sin(angle)
            outer.append(points.InsertNextPoint(x, y, height(x, y)))
        ni, i, o = len(inner), 0, 0
        while (ni > 1 and i < ni) or o < count:  # zip the two rings in order of angle
            if o < count and (ni == 1 or i == ni or start + 2 * math.pi * (o + 1) / count
                              < inner_start + 2 * math.pi * (i + 1) / ni):
                polys.InsertNextCell(3, (inner[i % ni], outer[o], outer[(o + 1) % count]))
                o += 1
            else:
                polys.InsertNextCell(3, (inner[i % ni], outer[o % count], inner[(i + 1) % ni]))
                i += 1
        inner, inner_start = outer, start
    surface = vtkPolyData()
    surface.SetPoints(points)
    surface.SetPolys(polys)
    return surface


def polar_patch(center, radii, angles, closed):
    """Points center + r (cos a, sin a) for every r in radii (increasing; a first radius of 0
    gives one centre point) and a in angles, as a vtkPolyData of counter-clockwise triangles;
    closed joins the last angle to the first (a full ring)."""
    from vtkmodules.vtkCommonCore import vtkPoints
    from vtkmodules.vtkCommonDataModel import vtkCellArray, vtkPolyData

    points, polys = vtkPoints(), vtkCellArray()
    points.SetDataTypeToDouble()
    rows = []
    for r in radii:
        if r == 0.0:
            rows.append([points.InsertNextPoint(center[0], center[1], 0.0)] * len(angles))
            continue
        rows.append([points.InsertNextPoint(center[0] + r * math.cos(a),
                                            center[1] + r * math.sin(a), 0.0) for a in angles])
    columns = len(angles) if closed else len(angles) - 1
    for inner, outer in zip(rows, rows[1:]):
        for j in range(columns):
            k = (j + 1) % len(angles)
            polys.InsertNextCell(3, (inner[j], outer[j], outer[k]))
            if inner[j] != inner[k]:  # not a fan around the centre point
                polys.InsertNextCell(3, (inner[j], outer[k], inner[k]))
    patch = vtkPolyData()
    patch.SetPoints(points)
    patch.SetPolys(polys)
    return patch


def append_polydata(*parts):
    """The parts as one vtkPolyData (coincident points are not merged)."""
    from vtkmodules.vtkFiltersCore import vtkAppendPolyData
    append = vtkAppendPolyData()
    for part in parts:
        append.AddInputData(part)
    append.Update()
    return append.GetOutput()


def annulus(inner_radius=0.4, outer_radius=1.0, rings=8, sectors=96):
    """A triangulated annulus centred at the origin: a target support with a hole."""
    radii = [inner_radius + (outer_radius - inner_radius) * k / rings for k in range(rings + 1)]
    angles = [2.0 * math.pi * j / sectors for j in range(sectors)]
    return polar_patch((0.0, 0.0), radii, angles, closed=True)


def two_half_disks(gap=0.2, radius=0.8, rings=12, sectors=48):
    """Two half-disks of the same area facing away from each other, their flat sides gap apart
    on either side of the y axis: a target support with two components."""
    radii = [radius * k / rings for k in range(rings + 1)]
    left = [math.pi / 2 + math.pi * j / sectors for j in range(sectors + 1)]
    right = [-math.pi / 2 + math.pi * j / sectors for j in range(sectors + 1)]
    return append_polydata(polar_patch((-gap / 2, 0.0), radii, left, closed=False),
                           polar_patch((gap / 2, 0.0), radii, right, closed=False))


def letter_c(rings=8, sectors=72):
    """A thick letter C (an annular sector open to the right): a non-convex target support."""
    radii = [0.45 + 0.45 * k / rings for k in range(rings + 1)]
    opening = math.pi / 4
    angles = [opening + (2.0 * math.pi - 2.0 * opening) * j / sectors for j in range(sectors + 1)]
    return polar_patch((0.0, 0.0), radii, angles, closed=False)


def read_surface(path):
    """A triangle surface from any file VTK reads, or .off / .obj (vtkOTParamMeshReader)."""
    from vtkmodules.vtkFiltersCore import vtkTriangleFilter

    extension = path.lower().rsplit(".", 1)[-1]
    if extension in ("off", "obj"):
        # The project's reader: VTK 9.2 has no OFF reader, and its OBJ reader splits vertices
        # at texture seams and crashes on texture indices without vt lines.
        from otparam import vtkOTParamMeshReader
        reader = vtkOTParamMeshReader()
        reader.SetFileName(path)
        reader.Update()
        if reader.GetOutput().GetNumberOfPoints() == 0:
            sys.exit(f"cannot read {path} (see the error above)")
        return reader.GetOutput()
    if extension == "vtp":
        from vtkmodules.vtkIOXML import vtkXMLPolyDataReader as Reader
    elif extension == "vtk":
        from vtkmodules.vtkIOLegacy import vtkPolyDataReader as Reader
    elif extension == "ply":
        from vtkmodules.vtkIOPLY import vtkPLYReader as Reader
    elif extension == "stl":
        from vtkmodules.vtkIOGeometry import vtkSTLReader as Reader
    else:
        sys.exit(f"unknown surface format: {path} (.vtp, .vtk, .ply, .stl, .obj, .off)")
    reader = Reader()
    reader.SetFileName(path)
    triangles = vtkTriangleFilter()  # polygons and strips -> triangles
    triangles.SetInputConnection(reader.GetOutputPort())
    triangles.PassVertsOff()
    triangles.PassLinesOff()
    triangles.Update()
    return triangles.GetOutput()


def density_disk_actors(disk):
    """The disk image coloured per triangle by log10 of its AreaDensity cell array (a blue -
    white - red map symmetric around 0) and the matching scalar bar: (actor, bar)."""
    from vtkmodules.vtkCommonCore import vtkDoubleArray
    from vtkmodules.vtkCommonDataModel import vtkPolyData
    from vtkmodules.vtkRenderingAnnotation import vtkScalarBarActor
    from vtkmodules.vtkRenderingCore import vtkActor, vtkColorTransferFunction, vtkPolyDataMapper

    density = disk.GetCellData().GetArray("AreaDensity")
    log_density = vtkDoubleArray()
    log_density.SetName("log10 AreaDensity")
    for t in range(density.GetNumberOfTuples()):
        log_density.InsertNextValue(math.log10(max(density.GetValue(t), 1e-300)))
    colored = vtkPolyData()
    colored.SetPoints(disk.GetPoints())
    colored.SetPolys(disk.GetPolys())
    colored.GetCellData().SetScalars(log_density)
    low, high = log_density.GetRange()
    colors = vtkColorTransferFunction()
    bound = max(abs(low), abs(high), 1e-3)
    colors.AddRGBPoint(-bound, 0.23, 0.30, 0.75)
    colors.AddRGBPoint(0.0, 0.87, 0.87, 0.87)
    colors.AddRGBPoint(bound, 0.71, 0.02, 0.15)
    mapper = vtkPolyDataMapper()
    mapper.SetInputData(colored)
    mapper.SetScalarModeToUseCellData()
    mapper.SetLookupTable(colors)
    mapper.UseLookupTableScalarRangeOn()
    actor = vtkActor()
    actor.SetMapper(mapper)
    bar = vtkScalarBarActor()
    bar.SetLookupTable(colors)
    bar.SetTitle("log10 AreaDensity")
    bar.SetNumberOfLabels(5)
    bar.SetPosition(0.86, 0.1)
    bar.SetWidth(0.12)
    bar.SetHeight(0.8)
    for prop in (bar.GetTitleTextProperty(), bar.GetLabelTextProperty()):
        prop.SetColor(0.1, 0.1, 0.1)
        prop.ShadowOff()
        prop.ItalicOff()
    return actor, bar


def circle_image(size=1024, per_row=16):
    """Dark disks on a hexagonal grid over white: through a map, their shapes show its
    distortion (circles stay circles through a conformal map, equal areas through an
    area-preserving one)."""
    from vtkmodules.vtkCommonCore import vtkUnsignedCharArray
    from vtkmodules.vtkCommonDataModel import vtkImageData
    image = vtkImageData()
    image.SetDimensions(size, size, 1)
    colors = vtkUnsignedCharArray()
    colors.SetNumberOfComponents(3)
    colors.SetNumberOfTuples(size * size)
    spacing = size / per_row
    radius2 = (0.36 * spacing) ** 2
    row_height = spacing * math.sqrt(3) / 2
    for j in range(size):
        row = round(j / row_height)
        cy = row * row_height
        shift = 0.5 * spacing * (row % 2)
        for i in range(size):
            cx = round((i - shift) / spacing) * spacing + shift
            inside = (i - cx) ** 2 + (j - cy) ** 2 <= radius2
            colors.SetTuple3(j * size + i, *((40, 70, 150) if inside else (245, 245, 245)))
    image.GetPointData().SetScalars(colors)
    return image


def view_along_mean_normal(renderer, normals, elevation):
    """Points the renderer's camera along the mean of the point normals of `normals` (a
    vtkPolyData with normals), tilted by `elevation` degrees, and resets it to the data: a
    camera from the data alone, so pictures are deterministic."""
    renderer.ResetCamera()
    camera = renderer.GetActiveCamera()
    n = [0.0, 0.0, 0.0]
    array = normals.GetPointData().GetNormals()
    for i in range(array.GetNumberOfTuples()):
        for k, value in enumerate(array.GetTuple3(i)):
            n[k] += value
    length = math.sqrt(sum(c * c for c in n)) or 1.0
    focal = camera.GetFocalPoint()
    distance = camera.GetDistance()
    camera.SetPosition(*(focal[k] + distance * n[k] / length for k in range(3)))
    camera.SetViewUp(*((0.0, 1.0, 0.0) if abs(n[1]) < 0.9 * length else (0.0, 0.0, 1.0)))
    camera.OrthogonalizeViewUp()
    camera.Elevation(elevation)
    camera.OrthogonalizeViewUp()
    renderer.ResetCamera()
    return camera
