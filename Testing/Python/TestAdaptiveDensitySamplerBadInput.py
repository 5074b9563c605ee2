"""Every bad input of vtkAdaptiveDensitySampler: a vtkErrorMacro naming the problem (and the
offending ids), RequestData failing, the output empty, the input untouched, and the filter
working again once the input is fixed. Also the runs that succeed with a warning: points used
by no triangle, the MaximumNumberOfSamples cap, and an abort (empty output, no error)."""

import math

from otparam import vtkAdaptiveDensitySampler
from otparam_test_utils import (add_cells, cell_lists, grid_triangle_list, check_failed_run, MessageRecorder, check, field_value, finish,
                                make_domain, ring_disk, same, snapshot)
from vtkmodules.vtkCommonCore import (vtkCommand, vtkDoubleArray, vtkIntArray,
                                      vtkStringArray)
from vtkmodules.vtkCommonDataModel import vtkCellArray, vtkDataObject, vtkPolyData

POINTS, CELLS = vtkDataObject.FIELD_ASSOCIATION_POINTS, vtkDataObject.FIELD_ASSOCIATION_CELLS
NAN, INF = float("nan"), float("inf")
N = 5  # the square: an N x N grid of points on [-1, 1]^2, 2 (N-1)^2 triangles
SAMPLES = 200  # NumberOfSamples of the runs that succeed (the default, 1000, is slower)


def density_value(x, y):
    return 1.0 + 4.0 * x * x + y


def add_double_array(attributes, name, values, components=1):
    array = vtkDoubleArray()
    array.SetName(name)
    array.SetNumberOfComponents(components)
    for v in values:
        if components == 1:
            array.InsertNextValue(v)
        else:
            array.InsertNextTuple([v] * components)
    attributes.AddArray(array)
    return array


def with_arrays(data):
    """Point array AreaDensity (positive), cell array CellDensity (positive, per triangle),
    and arrays the filter must not touch (point Height, cell Label)."""
    points = [data.GetPoint(i) for i in range(data.GetNumberOfPoints())]
    add_double_array(data.GetPointData(), "AreaDensity", [density_value(p[0], p[1]) for p in points])
    add_double_array(data.GetPointData(), "Height", [0.5 * i for i in range(len(points))])
    add_double_array(data.GetCellData(), "CellDensity",
                     [1.0 + 0.1 * c for c in range(data.GetNumberOfCells())])
    label = vtkIntArray()
    label.SetName("Label")
    for c in range(data.GetNumberOfCells()):
        label.InsertNextValue(c)
    data.GetCellData().AddArray(label)
    return data


def flat_disk_geometry(rings=4):
    """The unit disk as a ring disk: boundary points on the unit circle."""
    return ring_disk(rings, lambda t, azimuth: (t * math.cos(azimuth), t * math.sin(azimuth), 0.0))


def good_disk(rings=4):
    return with_arrays(make_domain(*flat_disk_geometry(rings)))


def grid_points(n=N, x0=-1.0, y0=-1.0, size=2.0):
    return [(x0 + size * i / (n - 1), y0 + size * j / (n - 1), 0.0)
            for j in range(n) for i in range(n)]


def grid_triangles(n=N, offset=0):
    return grid_triangle_list(n, offset)


def mesh(points, triangles):
    return with_arrays(make_domain(points, triangles))


def good_square():
    """25 points, 32 triangles on [-1, 1]^2."""
    return mesh(grid_points(), grid_triangles())



# ---- Bad densities.
def with_density(kind, index, value, name=None):
    data = good_disk()
    attributes = data.GetPointData() if kind == "point" else data.GetCellData()
    attributes.GetArray(name or ("AreaDensity" if kind == "point" else "CellDensity")).SetValue(
        index, value)
    return data


def with_densities(kind, values_by_index):
    data = good_disk()
    array = (data.GetPointData().GetArray("AreaDensity") if kind == "point"
             else data.GetCellData().GetArray("CellDensity"))
    for index, value in values_by_index.items():
        array.SetValue(index, value)
    return data


def all_zero(kind):
    data = good_disk()
    array = (data.GetPointData().GetArray("AreaDensity") if kind == "point"
             else data.GetCellData().GetArray("CellDensity"))
    array.Fill(0.0)
    return data


def without_density():
    data = good_disk()
    data.GetPointData().RemoveArray("AreaDensity")
    return data


def density_only_per_cell():
    # AreaDensity exists, but as a cell array: the default (a point array) is still missing.
    data = without_density()
    add_double_array(data.GetCellData(), "AreaDensity", [1.0] * data.GetNumberOfCells())
    return data


def string_density():
    data = without_density()
    array = vtkStringArray()
    array.SetName("AreaDensity")
    for i in range(data.GetNumberOfPoints()):
        array.InsertNextValue("dense")
    data.GetPointData().AddArray(array)
    return data


def vector_density():
    data = without_density()
    add_double_array(data.GetPointData(), "AreaDensity", [1.0] * data.GetNumberOfPoints(), 2)
    return data


def field_density():
    data = good_disk()
    add_double_array(data.GetFieldData(), "Global", [1.0])
    return data


# ---- Bad domains.
def points_only():
    data = good_disk()
    data.SetPolys(vtkCellArray())
    return data


def with_point(index, xyz):
    data = good_disk()
    data.GetPoints().SetPoint(index, *xyz)
    return data



def with_quad():
    # Grid square 2 as one quad (cell 4) instead of triangles 4 and 5.
    triangles = grid_triangles()
    a, b, c = triangles[4]
    d = triangles[5][2]
    triangles[4:6] = [(a, b, c, d)]
    return mesh(grid_points(), triangles)


def strips_only():
    data = make_domain(grid_points(), [])
    strips = []
    for j in range(N - 1):
        strip = []
        for i in range(N):
            strip += [j * N + i, (j + 1) * N + i]
        strips.append(strip)
    add_cells(data, "Strips", strips)
    add_double_array(data.GetPointData(), "AreaDensity", [1.0] * N * N)
    return data


def replace_triangle(index, new):
    triangles = grid_triangles()
    triangles[index] = new
    return mesh(grid_points(), triangles)


def annulus(segments=12, radii=(0.5, 0.75, 1.0)):
    points = [(r * math.cos(2 * math.pi * k / segments), r * math.sin(2 * math.pi * k / segments),
               0.0) for r in radii for k in range(segments)]
    triangles = []
    for ring in range(len(radii) - 1):
        for k in range(segments):
            a, b = ring * segments + k, ring * segments + (k + 1) % segments
            c, d = b + segments, a + segments
            triangles += [(a, b, c), (a, c, d)]
    return mesh(points, triangles)


def square_with_hole():
    # The 4 x 4 grid without grid square 5 (triangles 10 and 11), an interior square.
    triangles = grid_triangles()
    del triangles[10:12]
    return mesh(grid_points(), triangles)


def two_squares():
    points = grid_points() + grid_points(x0=3.0, y0=0.0)
    return mesh(points, grid_triangles() + grid_triangles(offset=N * N))


def l_shape():
    # The grid without its top-right quarter (a concave corner at the origin).
    triangles = [t for k, t in enumerate(grid_triangles()) if not (k // 2 % 4 >= 2 and k // 8 >= 2)]
    return mesh(grid_points(), triangles)


def bow_tie():
    # Grid squares 0 and 5 only: they share the grid point 6 and nothing else.
    triangles = grid_triangles()
    return mesh(grid_points(), triangles[0:2] + triangles[10:12])


def overlapping_triangle():
    # Triangle 0 twice: the triangles cover more than their convex hull.
    return mesh(grid_points(), grid_triangles() + [grid_triangles()[0]])


def crossing_triangle():
    # A triangle with points of its own laid across the grid's corner: no edge shared, but the
    # boundary crosses itself (CGAL's mesher crashed on such a domain).
    points = grid_points() + [(0.5, 0.5, 0.0), (1.5, 0.5, 0.0), (0.5, 1.5, 0.0)]
    n = len(grid_points())
    return mesh(points, grid_triangles() + [(n, n + 1, n + 2)])


def zero_area():
    # Triangle (0, 1, 2) of three points on the bottom edge.
    return mesh(grid_points(), grid_triangles() + [(0, 1, 2)])


def lifted_point():
    data = good_disk()
    data.GetPoints().SetPoint(6, 0.2, 0.1, 0.1)
    return data


# name, input, settings, words the message must contain (lower case; a tuple means any of
# them). Settings: property -> value; "Array": (association, name) for SetInputArrayToProcess.
CASES = [
    # -- the domain
    ("no points", vtkPolyData(), {}, ["empty"]),
    ("points but no triangles", points_only(), {}, ["empty", "triangles"]),
    ("NaN coordinate", with_point(12, (NAN, 0.0, 0.0)), {}, ["nan", "point id(s) 12"]),
    ("infinite coordinate", with_point(7, (0.0, INF, 0.0)), {}, ["infinite", "point id(s) 7"]),
    ("non-planar domain", lifted_point(), {}, ["not planar", "z = 0", "point id(s) 6 "]),
    ("a point slightly off the plane", with_point(3, (0.3, 0.2, -1e-3)), {},
     ["not planar", "point id(s) 3 "]),
    ("a quad", with_quad(), {}, ["triangles", "polygon id(s) 4 "]),
    ("triangle strip", add_cells(good_square(), "Strips", [(0, 1, 5, 6)]), {},
     ["triangles only", "1 triangle strips"]),
    ("triangle strips only", strips_only(), {}, ["triangles only", "4 triangle strips"]),
    ("line cell", add_cells(good_square(), "Lines", [(0, 1)]), {},
     ["triangles only", "1 line cells"]),
    ("vertex cells", add_cells(good_square(), "Verts", [(0,), (3,)]), {},
     ["triangles only", "2 vertex cells"]),
    ("point id out of range", replace_triangle(9, (7, 8, 25)), {},
     ["triangle id(s) 9", "outside"]),
    ("negative point id", replace_triangle(9, (7, -1, 8)), {}, ["triangle id(s) 9", "outside"]),
    ("two squares touching at a corner", bow_tie(), {},
     ["not supported", "touches itself"]),
    ("overlapping triangles", overlapping_triangle(), {}, ["not supported", "overlap"]),
    ("a triangle across others", crossing_triangle(), {},
     ["not supported", "boundary crosses itself", "triangles overlap"]),
    ("zero-area triangle", zero_area(), {}, ["not supported", "triangle 32", "zero area"]),
    # -- the density
    ("density array missing", without_density(), {},
     ["missing", "point array 'areadensity'"]),
    ("named density array missing", good_disk(), {"Array": (POINTS, "Rho")},
     ["missing", "point array 'rho'"]),
    ("density only per cell", density_only_per_cell(), {},
     ["missing", "point array 'areadensity'", "cell array of that name"]),
    ("cell density array missing", good_disk(), {"Array": (CELLS, "Height")},
     ["missing", "cell array 'height'", "point array of that name"]),
    ("field-data density", field_density(), {"Array": (vtkDataObject.FIELD_ASSOCIATION_NONE,
                                                       "Global")},
     ["point or a cell array"]),
    ("string density", string_density(), {}, ["'areadensity'", "not numeric"]),
    ("two-component density", vector_density(), {}, ["'areadensity'", "2 components"]),
    ("NaN density", with_density("point", 5, NAN), {}, ["nan", "point id(s) 5."]),
    ("infinite density", with_density("point", 17, INF), {}, ["infinite", "point id(s) 17."]),
    ("negative density", with_densities("point", {3: -1.0, 9: -1e-12}), {},
     ["negative", "point id(s) 3, 9 ", "-1"]),
    ("all-zero density", all_zero("point"), {}, ["zero everywhere", "61 points"]),
    ("NaN cell density", with_density("cell", 4, NAN), {"Array": (CELLS, "CellDensity")},
     ["nan", "cell array 'celldensity'", "cell id(s) 4."]),
    ("negative cell density", with_densities("cell", {0: -2.0, 95: -3.0}),
     {"Array": (CELLS, "CellDensity")}, ["negative", "cell id(s) 0, 95 "]),
    ("all-zero cell density", all_zero("cell"), {"Array": (CELLS, "CellDensity")},
     ["zero everywhere", "96 triangles"]),
    # -- the properties
    ("NumberOfSamples 2", good_disk(), {"NumberOfSamples": 2},
     ["numberofsamples", "at least 3", "got 2"]),
    ("NumberOfSamples 0", good_disk(), {"NumberOfSamples": 0}, ["numberofsamples", "at least 3"]),
    ("NumberOfSamples negative", good_disk(), {"NumberOfSamples": -100},
     ["numberofsamples", "at least 3"]),
    ("NumberOfSamples above the cap", good_disk(),
     {"NumberOfSamples": 5000, "MaximumNumberOfSamples": 4999},
     ["numberofsamples = 5000", "maximumnumberofsamples = 4999"]),
    ("MinimumAngle 0", good_disk(), {"MinimumAngle": 0.0}, ["minimumangle", "(0, 30]"]),
    ("MinimumAngle negative", good_disk(), {"MinimumAngle": -10.0}, ["minimumangle", "(0, 30]"]),
    ("MinimumAngle above 30", good_disk(), {"MinimumAngle": 30.5},
     ["minimumangle", "(0, 30]", "30.5"]),
    ("MinimumAngle NaN", good_disk(), {"MinimumAngle": NAN}, ["minimumangle", "nan"]),
    ("SamplingMode 3", good_disk(), {"SamplingMode": 3}, ["samplingmode", "got 3"]),
    ("SamplingMode -1", good_disk(), {"SamplingMode": -1}, ["samplingmode", "got -1"]),
    ("SizeRule 2", good_disk(), {"SizeRule": 2}, ["sizerule", "got 2"]),
    ("SizeRule -1", good_disk(), {"SizeRule": -1}, ["sizerule", "got -1"]),
]


def sampler(data, settings=None):
    filter_ = vtkAdaptiveDensitySampler()
    filter_.SetNumberOfSamples(SAMPLES)
    for prop, value in (settings or {}).items():
        if prop == "Array":
            filter_.SetInputArrayToProcess(0, 0, 0, *value)
        else:
            getattr(filter_, "Set" + prop)(value)
    filter_.SetInputData(data)
    return filter_


def is_empty(output):
    return (output.GetNumberOfPoints() == 0 and output.GetNumberOfCells() == 0
            and output.GetPointData().GetNumberOfArrays() == 0
            and output.GetCellData().GetNumberOfArrays() == 0
            and output.GetFieldData().GetNumberOfArrays() == 0)


for name, domain, settings, words in CASES:
    before = snapshot(domain)
    before_cells = cell_lists(domain)
    filter_ = sampler(domain, settings)
    errors = MessageRecorder(filter_)
    warnings = MessageRecorder(filter_, vtkCommand.WarningEvent)
    pipeline_errors = MessageRecorder(filter_.GetExecutive())
    filter_.Update()

    check_failed_run(name, errors, pipeline_errors, words)
    check(not warnings.messages, f"{name}: no warning besides the error ({warnings.text()})")
    check(is_empty(filter_.GetOutput()), f"{name}: output is empty")
    check(same(snapshot(domain), before) and cell_lists(domain) == before_cells,
          f"{name}: the input is not modified")


def good_run(name, data, settings=None, expect_warnings=()):
    """A run that must succeed: no error, exactly the expected warnings (substrings), Mass
    summing to SourceMass, the field data present. Returns the output."""
    before = snapshot(data)
    filter_ = sampler(data, settings)
    errors = MessageRecorder(filter_)
    warnings = MessageRecorder(filter_, vtkCommand.WarningEvent)
    filter_.Update()
    out = filter_.GetOutput()
    check(not errors.messages, f"{name}: no error ({errors.text()})")
    check(len(warnings.messages) == len(expect_warnings)
          and all(w in warnings.text() for w in expect_warnings),
          f"{name}: warnings {list(expect_warnings)} ({warnings.text()})")
    n = out.GetNumberOfPoints()
    mass = out.GetPointData().GetArray("Mass")
    check(n >= 3 and mass is not None and mass.GetNumberOfTuples() == n
          and mass.GetDataTypeAsString() == "double", f"{name}: {n} samples with a double Mass")
    source_mass = field_value(out, "SourceMass")
    total = math.fsum(mass.GetValue(i) for i in range(n)) if mass else 0.0
    check(source_mass is not None and abs(total - source_mass) <= 1e-9 * source_mass,
          f"{name}: Mass sums to SourceMass ({total} vs {source_mass})")
    check(field_value(out, "NumberOfSamples") == n
          and out.GetFieldData().GetArray("NumberOfSamples").IsA("vtkIntArray"),
          f"{name}: field data NumberOfSamples (int) = {n}")
    for array in ("MassCoefficientOfVariation", "MinimumAngle", "Epsilon", "RefinementRuns",
                  "Capped", "Relaxed", "SecondsRefinement", "SecondsMasses", "SecondsTotal"):
        check(field_value(out, array) is not None, f"{name}: field data {array}")
    check(all(abs(out.GetPoint(i)[2]) == 0.0 for i in range(n)), f"{name}: samples at z = 0")
    check(out.GetNumberOfPolys() == out.GetNumberOfCells() > 0
          and out.GetNumberOfVerts() == 0, f"{name}: triangles only, no vertex cells")
    check(same(snapshot(data), before), f"{name}: the input is not modified")
    return out


# The good inputs run cleanly (else the cases above would not isolate one problem each).
out = good_run("good disk", good_disk())
check(abs(field_value(out, "SourceMass") - math.pi) <= 1e-12, "good disk: source mass pi")
check(abs(out.GetNumberOfPoints() - SAMPLES) <= 0.1 * SAMPLES,
      f"good disk: {out.GetNumberOfPoints()} samples, within 10% of {SAMPLES}")
check(field_value(out, "Capped") == 0, "good disk: not capped")
out = good_run("good square", good_square())
check(abs(field_value(out, "SourceMass") - 4.0) <= 1e-12, "good square: source mass = area 4")
good_run("per-triangle density", good_disk(), {"Array": (CELLS, "CellDensity")})
good_run("points then cells", density_only_per_cell(),
         {"Array": (vtkDataObject.FIELD_ASSOCIATION_POINTS_THEN_CELLS, "AreaDensity")})
out = good_run("mesh vertices", good_disk(), {"SamplingMode": 2})
check(out.GetNumberOfPoints() == 61 and out.GetNumberOfCells() == 96,
      "mesh vertices: the domain's own 61 points and 96 triangles")
good_run("uniform, paper's size rule", good_disk(), {"SamplingMode": 1, "SizeRule": 1})
good_run("density zero at two points", with_densities("point", {0: 0.0, 1: 0.0}))
# A density that vanishes on a region: the domain is its support (triangles where it is not
# identically zero), so every sample gets a positive Mass.
square = good_square()
density = square.GetPointData().GetArray("AreaDensity")
for i in range(square.GetNumberOfPoints()):
    density.SetValue(i, max(0.0, square.GetPoint(i)[0]))
out = good_run("density zero on half the square", square)
mass = out.GetPointData().GetArray("Mass")
check(all(mass.GetValue(i) > 0.0 for i in range(out.GetNumberOfPoints()))
      and all(out.GetPoint(i)[0] >= -0.5 - 1e-12 for i in range(out.GetNumberOfPoints())),
      "density zero on half the square: positive masses, samples only where x >= -0.5")

# Domains with holes, several components or concave corners are target supports (the sampler
# samples them, boundaries included).
for name, domain, warnings in [
        ("annulus (a hole)", annulus(), ()), ("square with a hole", square_with_hole(), ()),
        ("two components", two_squares(), ()),
        ("non-convex domain", l_shape(), ["4 input point(s) belong to no triangle"])]:
    out = good_run(name, domain, expect_warnings=warnings)
    check(out.GetNumberOfPoints() > 100, f"{name}: sampled")

# Points used by no triangle are ignored, with a warning (only when the run succeeds).
points, triangles = flat_disk_geometry()
points.insert(0, (5.0, 5.0, 3.0))  # off the plane and outside: ignored all the same
triangles = [tuple(v + 1 for v in t) for t in triangles]
data = mesh(points, triangles)
data.GetPointData().GetArray("AreaDensity").SetValue(0, NAN)
out = good_run("unreferenced point", data, expect_warnings=["1 input point(s) belong to no triangle"])
check(abs(field_value(out, "SourceMass") - math.pi) <= 1e-12,
      "unreferenced point: still the unit disk")

# MaximumNumberOfSamples hit: a full output, Capped = 1, one warning that names the cap.
peak = good_disk(8)
density = peak.GetPointData().GetArray("AreaDensity")
for i in range(peak.GetNumberOfPoints()):
    x, y, _ = peak.GetPoint(i)
    density.SetValue(i, 1.0 + 1e6 * math.exp(-((x - 0.3) ** 2 + y * y) / 0.001))
out = good_run("capped", peak, {"NumberOfSamples": 300, "MaximumNumberOfSamples": 300},
               expect_warnings=["MaximumNumberOfSamples = 300"])
check(field_value(out, "Capped") == 1, "capped: Capped = 1")
check(out.GetNumberOfPoints() <= 300 + 3, f"capped: {out.GetNumberOfPoints()} samples <= the cap")

# Abort: a warning, an empty output, and no failure reported to the pipeline.
filter_ = sampler(good_disk())
errors = MessageRecorder(filter_)
warnings = MessageRecorder(filter_, vtkCommand.WarningEvent)
pipeline_errors = MessageRecorder(filter_.GetExecutive())
progress = []


def abort_on_progress(caller, _event):
    progress.append(caller.GetProgress())
    caller.SetAbortExecute(1)


filter_.AddObserver(vtkCommand.ProgressEvent, abort_on_progress)
filter_.Update()
check(not errors.messages and not pipeline_errors.messages,
      f"abort: no error ({errors.text()}{pipeline_errors.text()})")
check(len(warnings.messages) == 1 and "Aborted" in warnings.text(),
      f"abort: one warning 'Aborted' ({warnings.text()})")
check(is_empty(filter_.GetOutput()), "abort: output is empty")
check(len(progress) >= 1, "abort: progress was reported")

# Progress goes from 0 to 1 on a normal run.
filter_ = sampler(good_disk())
progress = []
filter_.AddObserver(vtkCommand.ProgressEvent, lambda caller, _e: progress.append(caller.GetProgress()))
filter_.Update()
check(len(progress) >= 3 and progress[-1] == 1.0 and progress == sorted(progress),
      f"progress: increasing up to 1 ({progress[:3]} ... {progress[-2:]})")

# A failed run does not poison the filter: fix the input (or the setting) and it works.
filter_ = sampler(with_density("point", 5, NAN))
MessageRecorder(filter_)
MessageRecorder(filter_.GetExecutive())
filter_.Update()
check(filter_.GetOutput().GetNumberOfPoints() == 0, "NaN density: empty output")
errors = MessageRecorder(filter_)
filter_.SetInputData(good_disk())
filter_.SetMinimumAngle(40.0)
filter_.Update()
check(len(errors.messages) == 1 and filter_.GetOutput().GetNumberOfPoints() == 0,
      "fixed input, bad MinimumAngle: still one error and an empty output")
errors = MessageRecorder(filter_)
filter_.SetMinimumAngle(30.0)
filter_.Update()
out = filter_.GetOutput()
check(not errors.messages, f"fixed input: no error ({errors.text()})")
check(abs(out.GetNumberOfPoints() - SAMPLES) <= 0.1 * SAMPLES
      and field_value(out, "MinimumAngle") >= 30.0 - 1e-9,
      f"fixed input: {out.GetNumberOfPoints()} samples, smallest angle "
      f"{field_value(out, 'MinimumAngle')}")

finish()
