"""Helpers shared by the Python tests: inputs for the filters and checks on their outputs."""

import math
import random
import sys

from vtkmodules.util.misc import calldata_type
from vtkmodules.util.vtkConstants import VTK_STRING
from vtkmodules.vtkCommonCore import vtkCommand, vtkDoubleArray, vtkIdList, vtkIntArray, vtkPoints
from vtkmodules.vtkCommonDataModel import vtkCellArray, vtkPolyData

FAILURES = []


def check(condition, message):
    """Records a failed check (all checks run, the script fails at the end)."""
    if not condition:
        FAILURES.append(message)
        print("FAIL:", message, flush=True)
    return condition


def image_test_arguments():
    """(baseline file or directory, temp dir) of a regression-image test, from its command
    line; VTK's image comparison writes into the temp dir."""
    import os
    from vtkmodules.test import Testing
    baseline, temp_dir = sys.argv[1], sys.argv[2]
    Testing.VTK_TEMP_DIR = temp_dir
    os.makedirs(temp_dir, exist_ok=True)
    return baseline, temp_dir


def check_image(window, baseline, label=""):
    """Compares the window with the baseline PNG (VTK's regression test, threshold 0.15)."""
    from vtkmodules.test import Testing
    try:
        Testing.compareImage(window, baseline, threshold=0.15)
    except RuntimeError as error:
        check(False, f"{label}image differs from {baseline}: {error}")


def finish():
    if FAILURES:
        print(f"{len(FAILURES)} check(s) failed", flush=True)
        sys.exit(1)
    print("all checks passed", flush=True)


def random_disk_points(n, seed, radius=0.95):
    """n points uniform in the disk of the given radius (rejection sampling, fixed seed)."""
    rng = random.Random(seed)
    points = []
    while len(points) < n:
        x, y = rng.uniform(-radius, radius), rng.uniform(-radius, radius)
        if x * x + y * y < radius * radius:
            points.append((x, y))
    return points


def fibonacci_sphere_points(n):
    """n points spread evenly on the unit sphere (the Fibonacci lattice), as (x, y, z)."""
    golden = math.pi * (3.0 - math.sqrt(5.0))
    points = []
    for i in range(n):
        z = 1.0 - (2.0 * i + 1.0) / n
        r = math.sqrt(max(0.0, 1.0 - z * z))
        points.append((r * math.cos(golden * i), r * math.sin(golden * i), z))
    return points


def random_sphere_points(n, seed):
    """n points uniform on the unit sphere (normalized Gaussians, fixed seed), as (x, y, z)."""
    rng = random.Random(seed)
    points = []
    while len(points) < n:
        p = [rng.gauss(0.0, 1.0) for _ in range(3)]
        r = math.sqrt(sum(c * c for c in p))
        if r > 1e-3:
            points.append(tuple(c / r for c in p))
    return points


def make_sphere_diracs(points, masses):
    """vtkPolyData with the given (x, y, z) points and point array Mass."""
    return make_diracs([p[:2] for p in points], masses, z=[p[2] for p in points])


def make_diracs(points, masses, z=None):
    """vtkPolyData with the given (x, y) points (z = 0 unless given) and point array Mass."""
    vtk_points = vtkPoints()
    vtk_points.SetDataTypeToDouble()
    for i, (x, y) in enumerate(points):
        vtk_points.InsertNextPoint(x, y, 0.0 if z is None else z[i])
    mass = vtkDoubleArray()
    mass.SetName("Mass")
    for m in masses:
        mass.InsertNextValue(m)
    data = vtkPolyData()
    data.SetPoints(vtk_points)
    data.GetPointData().AddArray(mass)
    return data


def make_domain(points, triangles, density=None):
    """Planar source domain: (x, y, z) points, triangles (or polygons), optional Density."""
    vtk_points = vtkPoints()
    vtk_points.SetDataTypeToDouble()
    for p in points:
        vtk_points.InsertNextPoint(*p)
    polys = vtkCellArray()
    for cell in triangles:
        polys.InsertNextCell(len(cell), cell)
    data = vtkPolyData()
    data.SetPoints(vtk_points)
    data.SetPolys(polys)
    if density is not None:
        array = vtkDoubleArray()
        array.SetName("Density")
        for d in density:
            array.InsertNextValue(d)
        data.GetPointData().AddArray(array)
    return data


def square_domain(half=1.0, density=None):
    """The square [-half, half]^2 as 2 triangles."""
    points = [(-half, -half, 0.0), (half, -half, 0.0), (half, half, 0.0), (-half, half, 0.0)]
    return make_domain(points, [(0, 1, 2), (0, 2, 3)], density)


class MessageRecorder:
    """Collects the text of ErrorEvent / WarningEvent of a vtkObject (and keeps the log quiet)."""

    def __init__(self, obj, event=vtkCommand.ErrorEvent):
        self.messages = []

        @calldata_type(VTK_STRING)
        def callback(_caller, _event, text):
            self.messages.append(text)

        self._callback = callback
        obj.AddObserver(event, callback)

    def text(self):
        return "\n".join(self.messages)


def update_recorded(algorithm, data):
    """Runs `algorithm` on `data`; returns the recorders of its errors and warnings."""
    algorithm.SetInputData(data)
    errors = MessageRecorder(algorithm)
    warnings = MessageRecorder(algorithm, vtkCommand.WarningEvent)
    algorithm.Update()
    return errors, warnings


def check_ignored_cells(name, algorithm, surface):
    """`surface` (triangles only) with a line and a vertex cell added, as vtkCleanPolyData
    leaves collapsed triangles: `algorithm` maps the triangles with one warning naming the
    ignored cells, and output 0's cell arrays follow the triangles (vtkPolyData numbers its
    vertex and line cells first)."""
    triangles = surface.GetNumberOfPolys()
    add_cells(add_cells(surface, "Lines", [(0, 1)]), "Verts", [(2,)])
    cell_ids = vtkIntArray()
    cell_ids.SetName("InputCellId")
    for c in range(surface.GetNumberOfCells()):
        cell_ids.InsertNextValue(c)
    surface.GetCellData().AddArray(cell_ids)
    algorithm.SetInputData(surface)
    errors = MessageRecorder(algorithm)
    warnings = MessageRecorder(algorithm, vtkCommand.WarningEvent)
    algorithm.Update()
    out = algorithm.GetOutput()
    check(not errors.messages and len(warnings.messages) == 1
          and "1 vertex cell(s) and 1 line cell(s) are ignored" in warnings.text(),
          f"{name}: mapped, one warning names the ignored cells ({errors.text()}{warnings.text()})")
    mapped = out.GetCellData().GetArray("InputCellId")
    check(out.GetNumberOfPolys() == triangles and mapped is not None
          and [int(mapped.GetValue(c)) for c in range(triangles)] == list(range(2, 2 + triangles)),
          f"{name}: output cell arrays follow the input's triangles")


def check_failed_run(name, errors, pipeline_errors, words):
    """A bad-input run: exactly one error that mentions each of `words` (a tuple = any of
    them), and RequestData reporting failure to the pipeline."""
    text = errors.text()
    lower = text.lower()
    print(f"{name}: {text.strip().splitlines()[-1] if text else '(no error)'}", flush=True)
    check(len(errors.messages) == 1, f"{name}: exactly one error ({len(errors.messages)})")
    for word in words:
        options = word if isinstance(word, tuple) else (word,)
        check(any(option in lower for option in options), f"{name}: message mentions {options}")
    check("returned failure" in pipeline_errors.text(),
          f"{name}: RequestData reports failure to the pipeline")


def field_value(data, name):
    array = data.GetFieldData().GetAbstractArray(name)
    if array is None:
        return None
    if array.IsA("vtkStringArray"):
        return array.GetValue(0)
    return array.GetTuple1(0)


def snapshot(data):
    """Everything of a vtkPolyData that a filter could modify, for an equality check."""
    result = {"mtime": data.GetMTime(), "npoints": data.GetNumberOfPoints()}
    points = data.GetPoints()
    result["points"] = (
        [points.GetPoint(i) for i in range(points.GetNumberOfPoints())] if points else None
    )
    arrays = {}
    for attributes in (data.GetPointData(), data.GetCellData(), data.GetFieldData()):
        for k in range(attributes.GetNumberOfArrays()):
            array = attributes.GetAbstractArray(k)
            if array.IsA("vtkDataArray"):
                values = [array.GetTuple(t) for t in range(array.GetNumberOfTuples())]
            else:
                values = [array.GetVariantValue(t).ToString() for t in range(array.GetNumberOfValues())]
            arrays[(attributes.GetClassName(), array.GetName())] = values
    result["arrays"] = arrays
    result["ncells"] = data.GetNumberOfCells()
    return result


def same(a, b):
    """Equality that treats NaN == NaN (the bad-input tests put NaNs in)."""
    if isinstance(a, float) and isinstance(b, float):
        return a == b or (math.isnan(a) and math.isnan(b))
    if isinstance(a, (list, tuple)) and isinstance(b, (list, tuple)):
        return len(a) == len(b) and all(same(x, y) for x, y in zip(a, b))
    if isinstance(a, dict) and isinstance(b, dict):
        return a.keys() == b.keys() and all(same(a[k], b[k]) for k in a)
    return a == b


def shared_data_dir():
    """../shared/data beside the checkout (CMake passes OTPARAM_SHARED_DATA_DIR)."""
    import os
    here = os.path.dirname(os.path.abspath(__file__))
    return os.environ.get("OTPARAM_SHARED_DATA_DIR",
                          os.path.join(here, "..", "..", "..", "shared", "data"))


def shared_mesh(name):
    import os
    return os.path.join(shared_data_dir(), "meshes", name)


def read_mesh(path):
    """A shared .off/.obj mesh as vtkPolyData (double points, triangles), numbering kept: the
    project's vtkOTParamMeshReader (VTK 9.2 has no OFF reader, and its OBJ reader may split
    vertices)."""
    from otparam import vtkOTParamMeshReader
    reader = vtkOTParamMeshReader()
    reader.SetFileName(path)
    reader.Update()
    data = vtkPolyData()
    data.ShallowCopy(reader.GetOutput())
    data.GetFieldData().Initialize()  # only the file's geometry, as the tests expect
    return data


def param_metrics():
    """The scorer that produced reference-figures.md (../shared/tools/param_metrics.py)."""
    import importlib.util
    import os
    path = os.path.join(shared_data_dir(), "..", "tools", "param_metrics.py")
    spec = importlib.util.spec_from_file_location("param_metrics", path)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def ring_disk(rings, lift):
    """Concentric rings of 6k points (k = 1..rings, staggered) around a centre, zipped into
    counter-clockwise triangles: 1 + 3 rings (rings + 1) points, 6 rings^2 triangles. Point
    (t, azimuth), t = k / rings, goes to lift(t, azimuth) = (x, y, z)."""
    points, triangles = [lift(0.0, 0.0)], []
    inner, inner_start = [0], 0.0
    for k in range(1, rings + 1):
        count = 6 * k
        start = (k % 2) * math.pi / count
        outer = []
        for j in range(count):
            outer.append(len(points))
            points.append(lift(k / rings, start + 2.0 * math.pi * j / count))
        ni, i, o = len(inner), 0, 0
        while (ni > 1 and i < ni) or o < count:
            if o < count and (ni == 1 or i == ni or start + 2 * math.pi * (o + 1) / count
                              < inner_start + 2 * math.pi * (i + 1) / ni):
                triangles.append((inner[i % ni], outer[o], outer[(o + 1) % count]))
                o += 1
            else:
                triangles.append((inner[i % ni], outer[o % count], inner[(i + 1) % ni]))
                i += 1
        inner, inner_start = outer, start
    return points, triangles


def grid_triangle_list(n, offset=0):
    """Each grid square (a, b, c, d) counter-clockwise -> triangles (a, b, c), (a, c, d)."""
    triangles = []
    for j in range(n - 1):
        for i in range(n - 1):
            a = offset + j * n + i
            b, c, d = a + 1, a + n + 1, a + n
            triangles += [(a, b, c), (a, c, d)]
    return triangles


def cell_lists(data):
    """The connectivity of every cell type (snapshot() only counts cells)."""
    ids = vtkIdList()
    result = []
    for cells in (data.GetVerts(), data.GetLines(), data.GetPolys(), data.GetStrips()):
        one = []
        if cells is not None:
            for c in range(cells.GetNumberOfCells()):
                cells.GetCellAtId(c, ids)
                one.append([ids.GetId(k) for k in range(ids.GetNumberOfIds())])
        result.append(one)
    return result


def add_cells(data, kind, cells):
    array = vtkCellArray()
    for cell in cells:
        array.InsertNextCell(len(cell), cell)
    getattr(data, "Set" + kind)(array)
    return data


def check_abort(algorithm, after=0.05):
    """Aborts `algorithm` once its progress passes `after`: the output must stay empty and a
    warning must say so."""
    def abort(obj, _event):
        if obj.GetProgress() > after:
            obj.SetAbortExecute(1)

    algorithm.AddObserver(vtkCommand.ProgressEvent, abort)
    warnings = MessageRecorder(algorithm, vtkCommand.WarningEvent)
    algorithm.Update()
    check(algorithm.GetOutput().GetNumberOfPoints() == 0, "abort leaves the output empty")
    check("abort" in warnings.text().lower(), "abort is reported")
