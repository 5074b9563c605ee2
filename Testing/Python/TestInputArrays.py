"""The input's point and cell arrays reach every output that carries the input's triangles: the
whole map's surface (port 0) and its disk or sphere mesh (port 1), and the conformal maps'
outputs. Where points used by no triangle are left out, each output point carries the values of
its input point (vtkOriginalPointIds). Normals stay behind on the disk and the sphere: they are
the surface's, and would shade the image as if it were the surface."""

import numpy as np
from otparam import vtkAreaPreservingParam, vtkConformalDiskMap, vtkConformalSphereMap
from otparam_test_utils import check, finish, make_domain, ring_disk, update_recorded
from vtkmodules.util.numpy_support import numpy_to_vtk, numpy_to_vtkIdTypeArray, vtk_to_numpy
from vtkmodules.vtkCommonCore import vtkPoints
from vtkmodules.vtkCommonDataModel import vtkCellArray, vtkPolyData
from vtkmodules.vtkFiltersCore import vtkPolyDataNormals
from vtkmodules.vtkFiltersSources import vtkSphereSource


def with_arrays(surface):
    """The surface with one unused point put first (every id shifts by one), smooth point
    normals, a point array `Thickness` (the point's x + 2 y + 3 z) and a cell array `Label`
    (the triangle's index)."""
    normals = vtkPolyDataNormals()
    normals.SetInputData(surface)
    normals.SplittingOff()
    normals.ComputeCellNormalsOn()
    normals.Update()
    smooth = normals.GetOutput()
    xyz = np.vstack([[5.0, 5.0, 5.0], vtk_to_numpy(smooth.GetPoints().GetData())])
    triangles = vtk_to_numpy(smooth.GetPolys().GetConnectivityArray()).reshape(-1, 3) + 1
    data = vtkPolyData()
    points = vtkPoints()
    points.SetData(numpy_to_vtk(xyz, deep=True))
    data.SetPoints(points)
    polys = vtkCellArray()
    polys.SetData(numpy_to_vtkIdTypeArray(np.arange(0, 3 * len(triangles) + 1, 3), deep=True),
                  numpy_to_vtkIdTypeArray(triangles.ravel().astype(np.int64), deep=True))
    data.SetPolys(polys)
    point_normals = vtk_to_numpy(smooth.GetPointData().GetNormals())
    point_normals = numpy_to_vtk(np.vstack([[0.0, 0.0, 1.0], point_normals]), deep=True)
    point_normals.SetName("Normals")
    data.GetPointData().SetNormals(point_normals)
    thickness = numpy_to_vtk(xyz @ np.array([1.0, 2.0, 3.0]), deep=True)
    thickness.SetName("Thickness")
    data.GetPointData().AddArray(thickness)
    cell_normals = numpy_to_vtk(vtk_to_numpy(smooth.GetCellData().GetNormals()), deep=True)
    cell_normals.SetName("CellNormals")
    data.GetCellData().SetNormals(cell_normals)
    label = numpy_to_vtk(np.arange(len(triangles), dtype=np.int32), deep=True)
    label.SetName("Label")
    data.GetCellData().AddArray(label)
    return data


def check_carried(name, data, output, points_kept, normals_expected):
    pd, cd = output.GetPointData(), output.GetCellData()
    thickness, label = pd.GetArray("Thickness"), cd.GetArray("Label")
    if points_kept:
        expected = vtk_to_numpy(data.GetPointData().GetArray("Thickness"))
    else:
        ids = vtk_to_numpy(pd.GetArray("vtkOriginalPointIds"))
        expected = vtk_to_numpy(data.GetPointData().GetArray("Thickness"))[ids]
        check(output.GetNumberOfPoints() == data.GetNumberOfPoints() - 1 and 0 not in ids,
              f"{name}: the unused point is left out")
    check(thickness is not None and np.array_equal(vtk_to_numpy(thickness), expected),
          f"{name}: point array Thickness carried, point by point")
    check(label is not None and np.array_equal(vtk_to_numpy(label),
                                               np.arange(data.GetNumberOfCells())),
          f"{name}: cell array Label carried, triangle by triangle")
    has_normals = pd.GetNormals() is not None or cd.GetNormals() is not None
    check(has_normals == normals_expected,
          f"{name}: normals {'kept' if normals_expected else 'left behind'}")


disk = with_arrays(make_domain(*ring_disk(12, lambda t, a: (t * np.cos(a), t * np.sin(a),
                                                             0.3 * t * t))))
sphere_source = vtkSphereSource()
sphere_source.SetThetaResolution(24)
sphere_source.SetPhiResolution(16)
sphere_source.Update()
sphere = with_arrays(sphere_source.GetOutput())


def run(name, algorithm, data, warning):
    """Runs `algorithm` on `data`: no error, and one warning about the unused point, which says
    `warning`."""
    errors, warnings = update_recorded(algorithm, data)
    check(not errors.messages and len(warnings.messages) == 1 and warning in warnings.text(),
          f"{name}: mapped, the unused point named ({errors.text()}{warnings.text()})")


for domain_name, data in (("disk", disk), ("sphere", sphere)):
    param = vtkAreaPreservingParam()
    param.SetNumberOfSamples(300)
    run(f"{domain_name}, whole map", param, data, "keep NaN map coordinates")
    check_carried(f"{domain_name}, whole map, port 0", data, param.GetOutputDataObject(0),
                  points_kept=True, normals_expected=True)
    check_carried(f"{domain_name}, whole map, port 1", data, param.GetOutputDataObject(1),
                  points_kept=False, normals_expected=False)
    conformal = vtkConformalDiskMap() if domain_name == "disk" else vtkConformalSphereMap()
    run(f"{domain_name}, {conformal.GetClassName()}", conformal, data, "left out of the output")
    check_carried(f"{domain_name}, {conformal.GetClassName()}", data, conformal.GetOutput(),
                  points_kept=False, normals_expected=False)
    check(data.GetPointData().GetNormals() is not None
          and data.GetCellData().GetNormals() is not None
          and data.GetPointData().GetArray("Thickness") is not None,
          f"{domain_name}: the input keeps its arrays")

finish()
