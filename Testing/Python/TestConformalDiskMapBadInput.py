"""Every bad input of vtkConformalDiskMap: a vtkErrorMacro naming the problem (and the
offending ids), RequestData failing, the output empty, the input untouched, and the filter
working again once the input is fixed. Also: points used by no triangle are not an error."""

from bad_disk_inputs import (CENTRE, INF, N, NAN, SURFACE_CASES, good_disk, reversed_triangle,
                             with_unreferenced_point)
from otparam import vtkConformalDiskMap
from otparam_test_utils import (MessageRecorder, cell_lists, check, check_failed_run,
                                check_ignored_cells, field_value,
                                finish, same, snapshot, update_recorded)
from vtkmodules.vtkCommonCore import vtkCommand


CASES = SURFACE_CASES + [
    ("Tolerance zero", good_disk(), {"Tolerance": 0.0}, ["tolerance", "positive"]),
    ("Tolerance negative", good_disk(), {"Tolerance": -1e-6}, ["tolerance", "positive"]),
    ("Tolerance NaN", good_disk(), {"Tolerance": NAN}, ["tolerance", "nan"]),
    ("Tolerance infinite", good_disk(), {"Tolerance": INF}, ["tolerance", "finite"]),
    ("MaximumNumberOfIterations negative", good_disk(), {"MaximumNumberOfIterations": -1},
     ["maximumnumberofiterations", "at least 0"]),
]

for name, surface, settings, words in CASES:
    before = snapshot(surface)
    before_cells = cell_lists(surface)
    mapper = vtkConformalDiskMap()
    for prop, value in settings.items():
        getattr(mapper, "Set" + prop)(value)
    mapper.SetInputData(surface)
    errors = MessageRecorder(mapper)
    warnings = MessageRecorder(mapper, vtkCommand.WarningEvent)
    pipeline_errors = MessageRecorder(mapper.GetExecutive())
    mapper.Update()

    check_failed_run(name, errors, pipeline_errors, words)
    check(not warnings.messages, f"{name}: no warning besides the error ({warnings.text()})")
    output = mapper.GetOutput()
    check(output.GetNumberOfPoints() == 0 and output.GetNumberOfCells() == 0
          and output.GetPointData().GetNumberOfArrays() == 0
          and output.GetCellData().GetNumberOfArrays() == 0
          and output.GetFieldData().GetNumberOfArrays() == 0, f"{name}: output is empty")
    check(same(snapshot(surface), before) and cell_lists(surface) == before_cells,
          f"{name}: the input is not modified")

# The good disk itself maps cleanly (else the cases above would not isolate one problem each).
mapper = vtkConformalDiskMap()
mapper.SetInputData(good_disk())
errors = MessageRecorder(mapper)
warnings = MessageRecorder(mapper, vtkCommand.WarningEvent)
mapper.Update()
out = mapper.GetOutput()
check(not errors.messages and not warnings.messages,
      f"good disk: no error or warning ({errors.text()}{warnings.text()})")
check(out.GetNumberOfPoints() == N * N and out.GetNumberOfCells() == 2 * (N - 1) ** 2,
      "good disk: every point and triangle in the output")
check(field_value(out, "FlippedTriangles") == 0, "good disk: no flipped triangle")
radius_error = field_value(out, "MaximumBoundaryRadiusError")
check(radius_error is not None and radius_error <= 1e-12, "good disk: boundary on the unit circle")
check(field_value(out, "CenterPointId") == CENTRE, "good disk: the middle point goes to the centre")

# Points used by no triangle are not an error: a warning, left out of the output, and
# vtkOriginalPointIds maps output points to input ids.
EXTRA = 10
surface = with_unreferenced_point(EXTRA)
before = snapshot(surface)
mapper = vtkConformalDiskMap()
errors, warnings = update_recorded(mapper, surface)
out = mapper.GetOutput()
check(not errors.messages, f"unreferenced point: no error ({errors.text()})")
check(len(warnings.messages) == 1 and "belong to no triangle" in warnings.text()
      and "1 input point" in warnings.text(), f"unreferenced point: one warning ({warnings.text()})")
check(out.GetNumberOfPoints() == surface.GetNumberOfPoints() - 1,
      "unreferenced point: left out of the output")
original = out.GetPointData().GetArray("vtkOriginalPointIds")
expected = [i for i in range(surface.GetNumberOfPoints()) if i != EXTRA]
check(original is not None and original.GetNumberOfTuples() == len(expected)
      and [original.GetValue(i) for i in range(original.GetNumberOfTuples())] == expected,
      "unreferenced point: vtkOriginalPointIds maps output points to input ids")
coordinates = out.GetPointData().GetArray("Coordinates3D")
heights = out.GetPointData().GetArray("Height")
check(coordinates is not None and heights is not None
      and all(coordinates.GetTuple3(i) == surface.GetPoint(expected[i])
              and heights.GetValue(i) == 0.5 * expected[i] for i in range(len(expected))),
      "unreferenced point: output point i is input point vtkOriginalPointIds[i]")
check(cell_lists(surface)[2] == [[expected[v] for v in t] for t in cell_lists(out)[2]],
      "unreferenced point: same triangles, renumbered")
check(field_value(out, "CenterPointId") == CENTRE + 1 and field_value(out, "FlippedTriangles") == 0,
      "unreferenced point: the map is that of the good disk (CenterPointId in input ids)")
check(same(snapshot(surface), before), "unreferenced point: the input is not modified")

# A failed run does not poison the filter: fix the input (or the setting) and it works.
mapper = vtkConformalDiskMap()
mapper.SetInputData(reversed_triangle())
MessageRecorder(mapper)
MessageRecorder(mapper.GetExecutive())
mapper.Update()
check(mapper.GetOutput().GetNumberOfPoints() == 0, "reversed triangle: empty output")
errors = MessageRecorder(mapper)
mapper.SetInputData(good_disk())
mapper.SetTolerance(-1.0)
mapper.Update()
check(len(errors.messages) == 1 and mapper.GetOutput().GetNumberOfPoints() == 0,
      "fixed input, bad Tolerance: still one error and an empty output")
errors = MessageRecorder(mapper)
mapper.SetTolerance(1e-7)
mapper.Update()
out = mapper.GetOutput()
check(not errors.messages, f"fixed input: no error ({errors.text()})")
check(out.GetNumberOfPoints() == N * N and field_value(out, "FlippedTriangles") == 0,
      "fixed input: maps without flipped triangles")

check_ignored_cells("conformal disk map, with a line and a vertex cell", vtkConformalDiskMap(),
                    good_disk())
finish()
