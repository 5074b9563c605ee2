"""Every bad input of vtkAreaPreservingParam: what its stages reject is rejected with the stage's
message prefixed by its name, its own parameters are checked before any work, and in every case
RequestData fails, all three outputs are empty, the input is untouched, and the filter works
again once the input is fixed. Abort leaves the outputs empty."""

import math

from bad_disk_inputs import (INF, NAN, SURFACE_CASES, collapsed_edge, good_disk,
                             nearly_collapsed_edge, reversed_triangle, slit_disk, triangle_soup,
                             with_unreferenced_point)
from otparam import vtkAreaPreservingParam
from otparam_test_utils import (MessageRecorder, cell_lists, check, check_abort, check_failed_run,
                                check_ignored_cells,
                                field_value, finish, same, snapshot)
from vtkmodules.vtkCommonCore import vtkCommand
from vtkmodules.vtkFiltersCore import vtkCleanPolyData

# The conformal map is the first stage: every bad surface is its to reject. A closed surface is
# bad only for the disk (Domain Automatic maps it onto the sphere: TestAreaPreservingParamSphere).
CASES = [(name, surface, dict(settings, Domain=1) if name == "closed surface" else settings,
          ["conformal map: "] + words)
         for name, surface, settings, words in SURFACE_CASES]
CASES += [
    ("NumberOfSamples 2", good_disk(), {"NumberOfSamples": 2}, ["numberofsamples", "at least 3"]),
    ("NumberOfSamples negative", good_disk(), {"NumberOfSamples": -100},
     ["numberofsamples", "at least 3"]),
    ("SamplingMode 3", good_disk(), {"SamplingMode": 3}, ["samplingmode", "got 3"]),
    ("SamplingMode -1", good_disk(), {"SamplingMode": -1}, ["samplingmode", "got -1"]),
    ("Tolerance zero", good_disk(), {"Tolerance": 0.0}, ["tolerance", "positive"]),
    ("Tolerance negative", good_disk(), {"Tolerance": -1e-6}, ["tolerance", "positive"]),
    ("Tolerance NaN", good_disk(), {"Tolerance": NAN}, ["tolerance", "nan"]),
    ("Tolerance infinite", good_disk(), {"Tolerance": INF}, ["tolerance", "finite"]),
    ("MaximumNumberOfIterations 0", good_disk(), {"MaximumNumberOfIterations": 0},
     ["maximumnumberofiterations", "at least 1"]),
    ("MaximumCorrectionSweeps negative", good_disk(), {"MaximumCorrectionSweeps": -1},
     ["maximumcorrectionsweeps", "at least 0"]),
    ("NumberOfHistogramBins 0", good_disk(), {"NumberOfHistogramBins": 0},
     ["numberofhistogrambins", "got 0"]),
    ("NumberOfHistogramBins huge", good_disk(), {"NumberOfHistogramBins": 10 ** 9},
     ["numberofhistogrambins", "got 1000000000"]),
]


def outputs_empty(algorithm):
    surface, disk, table = (algorithm.GetOutputDataObject(p) for p in range(3))
    return all(d.GetNumberOfPoints() == 0 and d.GetNumberOfCells() == 0
               and d.GetPointData().GetNumberOfArrays() == 0
               and d.GetCellData().GetNumberOfArrays() == 0
               and d.GetFieldData().GetNumberOfArrays() == 0 for d in (surface, disk)) \
        and table.GetNumberOfRows() == 0 and table.GetNumberOfColumns() == 0


for name, surface, settings, words in CASES:
    before = snapshot(surface)
    before_cells = cell_lists(surface)
    param = vtkAreaPreservingParam()
    param.SetNumberOfSamples(200)
    for prop, value in settings.items():
        getattr(param, "Set" + prop)(value)
    param.SetInputData(surface)
    errors = MessageRecorder(param)
    warnings = MessageRecorder(param, vtkCommand.WarningEvent)
    pipeline_errors = MessageRecorder(param.GetExecutive())
    param.Update()

    check_failed_run(name, errors, pipeline_errors, words)
    check(not warnings.messages, f"{name}: no warning besides the error ({warnings.text()})")
    check(outputs_empty(param), f"{name}: all three outputs are empty")
    check(same(snapshot(surface), before) and cell_lists(surface) == before_cells,
          f"{name}: the input is not modified")

# A failed run does not poison the filter: fix the input and it works.
param = vtkAreaPreservingParam()
param.SetNumberOfSamples(200)
param.SetInputData(reversed_triangle())
MessageRecorder(param)
MessageRecorder(param.GetExecutive())
param.Update()
check(outputs_empty(param), "reversed triangle: empty outputs")
errors = MessageRecorder(param)
warnings = MessageRecorder(param, vtkCommand.WarningEvent)
surface = good_disk()
param.SetInputData(surface)
param.Update()
out = param.GetOutput()
check(not errors.messages and not warnings.messages,
      f"fixed input: no error or warning ({errors.text()}{warnings.text()})")
check(out.GetNumberOfPoints() == surface.GetNumberOfPoints()
      and field_value(out, "FlippedTriangles") == 0 and field_value(out, "Converged") == 1,
      "fixed input: converged, every point, no flipped triangle")

def map_after_clean(name, surface, tolerance, convert_polys_to_lines, points, polys):
    """The clean a message names, then the map: `points` points and `polys` triangles left,
    converged with no flip."""
    clean = vtkCleanPolyData()
    clean.SetInputData(surface)
    clean.SetTolerance(tolerance)
    clean.SetConvertPolysToLines(convert_polys_to_lines)
    param = vtkAreaPreservingParam()
    param.SetNumberOfSamples(200)
    param.SetInputConnection(clean.GetOutputPort())
    errors = MessageRecorder(param)
    param.Update()
    out = param.GetOutput()
    check(not errors.messages and out.GetNumberOfPoints() == points
          and out.GetNumberOfPolys() == polys
          and field_value(out, "FlippedTriangles") == 0 and field_value(out, "Converged") == 1,
          f"{name} after vtkCleanPolyData: {points} points, {polys} triangles, mapped "
          f"({errors.text()})")


# The collapsed edges: one point fewer, the two collapsed triangles gone (as line cells,
# ignored, or dropped).
GRID_POINTS, GRID_TRIANGLES = good_disk().GetNumberOfPoints(), good_disk().GetNumberOfPolys()
map_after_clean("coincident points", collapsed_edge(), 0.0, False, GRID_POINTS - 1,
                GRID_TRIANGLES - 2)
# The seam and the soup: the clean merges their points, and the grids map whole.
map_after_clean("interior slit", slit_disk(), 0.0, False, 49, slit_disk().GetNumberOfPolys())
map_after_clean("triangle soup", triangle_soup(), 0.0, False, GRID_POINTS, GRID_TRIANGLES)
# With the clean's default ConvertPolysToLines: the collapsed triangles become line cells.
map_after_clean("nearly coincident points, Tolerance 1e-6", nearly_collapsed_edge(), 1e-6, True,
                GRID_POINTS - 1, GRID_TRIANGLES - 2)

# A point used by no triangle: the output keeps every input point, that one with NaN
# coordinates, and the one warning says so (not the conformal stage's "left out").
surface = with_unreferenced_point(3)
param = vtkAreaPreservingParam()
param.SetNumberOfSamples(200)
param.SetInputData(surface)
errors = MessageRecorder(param)
warnings = MessageRecorder(param, vtkCommand.WarningEvent)
param.Update()
out = param.GetOutput()
uv = out.GetPointData().GetArray("AreaPreservingCoordinates")
check(not errors.messages and out.GetNumberOfPoints() == surface.GetNumberOfPoints()
      and all(math.isnan(c) for c in uv.GetTuple2(3))
      and not any(math.isnan(c) for c in uv.GetTuple2(4)),
      f"unreferenced point: kept, NaN coordinates, the others mapped ({errors.text()})")
check(len(warnings.messages) == 1 and "1 input point(s) belong to no triangle and keep NaN"
      in warnings.text() and "left out" not in warnings.text(),
      f"unreferenced point: one warning that says NaN ({warnings.text()})")

# Abort: the outputs stay empty and a warning says so.
param = vtkAreaPreservingParam()
param.SetNumberOfSamples(2000)
param.SetInputData(good_disk())
check_abort(param, after=0.3)
check(outputs_empty(param), "abort: all three outputs are empty")

check_ignored_cells("disk map, with a line and a vertex cell", vtkAreaPreservingParam(),
                    good_disk())
finish()
