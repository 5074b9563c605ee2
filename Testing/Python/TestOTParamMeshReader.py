"""vtkOTParamMeshReader: every shared mesh with the point and triangle counts its README states;
hostile files (truncated, wrong counts, NaN, indices out of range, binary junk) give one clear
error naming the line and an empty output, never a crash; and the export round trip of a
parameterized surface: VTK's vtkOBJWriter writes the texture coordinates, this reader reads
back the same points, triangles and texture coordinates to 1e-12 relative."""

import os
import re
import tempfile

from otparam import vtkAreaPreservingParam, vtkOTParamMeshReader
from otparam_test_utils import (MessageRecorder, check, check_failed_run, finish, shared_data_dir,
                                shared_mesh)
from vtkmodules.vtkCommonCore import vtkCommand
from vtkmodules.vtkCommonExecutionModel import vtkAlgorithm
from vtkmodules.vtkIOGeometry import vtkOBJWriter


def readme_counts():
    """{file: (vertices, triangles)} from the tables of ../shared/data/meshes/README.md."""
    counts = {}
    with open(os.path.join(shared_data_dir(), "meshes", "README.md")) as f:
        for line in f:
            cells = [c.strip() for c in line.strip().strip("|").split("|")]
            if len(cells) > 3 and re.fullmatch(r"[\w.-]+\.(off|obj)", cells[0]):
                counts[cells[0]] = (int(cells[1].split()[0]), int(cells[2]))
    return counts


def read(path):
    reader = vtkOTParamMeshReader()
    reader.SetFileName(path)
    errors = MessageRecorder(reader)
    pipeline_errors = MessageRecorder(reader.GetExecutive())
    reader.Update()
    return reader.GetOutput(), errors, pipeline_errors


# ---- Every shared mesh.
counts = readme_counts()
check(len(counts) == 13, f"the README lists 13 meshes ({len(counts)})")
for name, (vertices, triangles) in sorted(counts.items()):
    data, errors, _ = read(shared_mesh(name))
    check(not errors.messages, f"{name}: read without error ({errors.text()})")
    check(data.GetNumberOfPoints() == vertices,
          f"{name}: {data.GetNumberOfPoints()} points, README {vertices}")
    check(data.GetNumberOfPolys() == triangles,
          f"{name}: {data.GetNumberOfPolys()} triangles, README {triangles}")
    check(data.GetNumberOfCells() == data.GetNumberOfPolys(), f"{name}: triangles only")
face, _, _ = read(shared_mesh("face_dense_gpp_5k.obj"))
check(face.GetPointData().GetTCoords() is None,
      "face_dense_gpp_5k.obj (texture indices, no vt lines): no texture coordinates")
check(vtkOTParamMeshReader.CanReadFile("a/B.OFF") == 1 and
      vtkOTParamMeshReader.CanReadFile("x.obj") == 1 and
      vtkOTParamMeshReader.CanReadFile("x.vtp") == 0, "CanReadFile: .off and .obj, any case")

# ---- Hostile files: one error naming the problem (and its line), an empty output.
work = tempfile.mkdtemp(prefix="otparam_reader_")
good_off = "OFF\n4 2 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n3 0 1 2\n3 0 2 3\n"
hostile = [
    ("truncated.off", good_off[:good_off.index("1 1 0")], ("vertices", "ends")),
    ("counts.off", "OFF\n1000 2 0\n0 0 0\n1 0 0\n1 1 0\n3 0 1 2\n", ("1000",)),
    ("nan.off", "OFF\n3 1 0\n0 0 0\nnan 0 0\n0 1 0\n3 0 1 2\n", ("line 4", "finite")),
    ("range.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 7\n", ("line 6", "7")),
    ("range.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n", ("line 4", "9")),
    ("zero.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 0 1 2\n", ("line 4",)),
    ("inf.obj", "v 0 0 0\nv 1 inf 0\nv 0 1 0\nf 1 2 3\n", ("line 2", "finite")),
    ("empty.obj", "", ("no vertices",)),
    ("nofaces.off", "OFF\n3 0 0\n0 0 0\n1 0 0\n0 1 0\n", ("no faces",)),
    ("junk.obj", bytes(range(256)) * 8, ("binary",)),
    ("huge.off", "OFF\n2000000000 1 0\n0 0 0\n", ("2000000000",)),
]
for name, content, words in hostile:
    path = os.path.join(work, name)
    with open(path, "wb") as f:
        f.write(content if isinstance(content, bytes) else content.encode())
    data, errors, pipeline_errors = read(path)
    check_failed_run(name, errors, pipeline_errors, words)
    check(data.GetNumberOfPoints() == 0 and data.GetNumberOfCells() == 0, f"{name}: empty output")
data, errors, pipeline_errors = read(os.path.join(work, "missing.off"))
check_failed_run("missing file", errors, pipeline_errors, ("missing.off",))
data, errors, pipeline_errors = read(os.path.join(work, "mesh.stl"))
check_failed_run("other extension", errors, pipeline_errors, (".off",))

# ---- Export round trip: a parameterized surface as OBJ with its texture coordinates.
for mesh, tcoords_name in (("hemisphere_2k.obj", "AreaPreservingCoordinates"),
                           ("spot_closed_3k.obj", "SphericalTextureCoordinates")):
    source, _, _ = read(shared_mesh(mesh))
    param = vtkAreaPreservingParam()
    param.SetInputData(source)
    param.SetNumberOfSamples(2000)
    param.Update()
    mapped = param.GetOutput()
    tcoords = mapped.GetPointData().GetTCoords()
    check(tcoords is not None and tcoords.GetName() == tcoords_name,
          f"{mesh}: the map's texture coordinates are {tcoords_name}")
    obj = os.path.join(work, mesh.replace(".obj", "_mapped.obj"))
    writer = vtkOBJWriter()
    writer.SetInputData(mapped)
    writer.SetFileName(obj)
    check(writer.Write() == 1, f"{mesh}: vtkOBJWriter wrote {obj}")
    back, errors, _ = read(obj)
    check(not errors.messages, f"{mesh}: the written OBJ reads back ({errors.text()})")
    n = mapped.GetNumberOfPoints()
    check(back.GetNumberOfPoints() == n and back.GetNumberOfPolys() == mapped.GetNumberOfPolys(),
          f"{mesh}: same point and triangle counts")
    back_tcoords = back.GetPointData().GetTCoords()
    check(back_tcoords is not None, f"{mesh}: texture coordinates read back")
    if back_tcoords is None or back.GetNumberOfPoints() != n:
        continue
    scale = max(abs(v) for i in range(n) for v in mapped.GetPoint(i)) or 1.0
    worst_point = max(abs(a - b) for i in range(n)
                      for a, b in zip(mapped.GetPoint(i), back.GetPoint(i))) / scale
    worst_uv = max(abs(a - b) for i in range(n)
                   for a, b in zip(tcoords.GetTuple2(i), back_tcoords.GetTuple2(i)))
    same_triangles = all(
        [mapped.GetCell(c).GetPointId(k) for k in range(3)] ==
        [back.GetCell(c).GetPointId(k) for k in range(3)] for c in range(mapped.GetNumberOfCells()))
    print(f"{mesh}: round trip points {worst_point:.1e}, texture coordinates {worst_uv:.1e}")
    check(worst_point <= 1e-12, f"{mesh}: points to 1e-12 relative ({worst_point:.1e})")
    check(worst_uv <= 1e-12, f"{mesh}: texture coordinates to 1e-12 ({worst_uv:.1e})")
    check(same_triangles, f"{mesh}: same triangles")

finish()
