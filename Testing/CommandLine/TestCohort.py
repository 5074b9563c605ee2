"""The command line tool on a small cohort: 6 shared meshes (disks, a closed surface) and 2
broken ones written here (a non-manifold fin, a closed torus of genus 1).

- `mpiexec -n 2 otparam DIR -o OUT`: 6 rows mapped with their .vtp, 2 failed rows with their
  messages, both ranks used, exit status 1.
- The same with --resume: nothing is mapped again (every row resumed, no output rewritten).
- One process (no mpiexec): the same .vtp outputs, array for array (timings aside).
- --obj: the OBJ read back has the .vtp's points and triangles, and its texture coordinates
  in [0, 1]^2 (the disk inscribed in the unit square, longitude/latitude on the sphere).
- PLY, STL, legacy VTK and VTP inputs, named by a glob.
- --timeout: a surface past it is a failed row naming the stage.
- Usage errors: exit status 2 with a message.
- Thread counts: a surface of 273k points (CHOLMOD's supernodal factorization on OpenBLAS in its
  conformal map) gives the same .vtp with OMP_NUM_THREADS=1 and =2.

Usage: TestCohort.py <otparam launcher> <mpiexec> <shared meshes dir> <work dir>
"""

import csv
import os
import shutil
import subprocess
import sys

from otparam import vtkOTParamMeshReader
from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.vtkIOXML import vtkXMLPolyDataReader
import numpy

otparam, mpiexec, meshes, work = sys.argv[1:5]
SHARED = ("hand_stein_810.obj", "hemisphere_2k.obj", "face_dense_gpp_5k.obj",
          "spot_closed_3k.obj", "chinese_lion_17k.off", "face_choi_bff_17k.obj")
failures = []


def check(condition, message):
    print(("ok   " if condition else "FAIL ") + message, flush=True)
    if not condition:
        failures.append(message)


def write_broken(cohort):
    with open(os.path.join(cohort, "fin_nonmanifold.off"), "w") as f:
        f.write("OFF\n5 3 0\n0 0 0\n1 0 0\n0 1 0\n0 -1 0\n0 0 1\n3 0 1 2\n3 1 0 3\n3 0 1 4\n")
    import math
    n, m = 24, 12
    points = [((1 + 0.4 * math.cos(2 * math.pi * j / m)) * math.cos(2 * math.pi * i / n),
               (1 + 0.4 * math.cos(2 * math.pi * j / m)) * math.sin(2 * math.pi * i / n),
               0.4 * math.sin(2 * math.pi * j / m)) for i in range(n) for j in range(m)]
    triangles = []
    for i in range(n):
        for j in range(m):
            a, b = i * m + j, ((i + 1) % n) * m + j
            c, d = ((i + 1) % n) * m + (j + 1) % m, i * m + (j + 1) % m
            triangles += [(a, b, c), (a, c, d)]
    with open(os.path.join(cohort, "torus_genus1.off"), "w") as f:
        f.write(f"OFF\n{len(points)} {len(triangles)} 0\n")
        f.writelines("%r %r %r\n" % p for p in points)
        f.writelines("3 %d %d %d\n" % t for t in triangles)


def run(arguments, env=None):
    environment = {k: v for k, v in os.environ.items()
                   if k not in ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS")}
    result = subprocess.run(arguments, capture_output=True, text=True,
                            env=dict(environment, **(env or {})))
    print(f"$ {' '.join(arguments)}  -> exit {result.returncode}\n{result.stdout}", flush=True)
    return result


def summary(out):
    with open(os.path.join(out, "summary.csv"), newline="") as f:
        return {row["name"]: row for row in csv.DictReader(f)}


def read_vtp(path):
    reader = vtkXMLPolyDataReader()
    reader.SetFileName(path)
    reader.Update()
    return reader.GetOutput()


def differences(a, b):
    """Names of what differs between two outputs (points, arrays; Seconds* aside)."""
    different = []
    if not numpy.array_equal(vtk_to_numpy(a.GetPoints().GetData()),
                             vtk_to_numpy(b.GetPoints().GetData())):
        different.append("points")
    for attributes in ("GetPointData", "GetCellData", "GetFieldData"):
        left, right = getattr(a, attributes)(), getattr(b, attributes)()
        for i in range(left.GetNumberOfArrays()):
            array = left.GetAbstractArray(i)
            other = right.GetAbstractArray(array.GetName())
            if array.GetName().startswith("Seconds") or not array.IsA("vtkDataArray"):
                continue
            if other is None or not numpy.array_equal(vtk_to_numpy(array), vtk_to_numpy(other),
                                                      equal_nan=True):
                different.append(array.GetName())
    return different


shutil.rmtree(work, ignore_errors=True)
cohort = os.path.join(work, "cohort")
os.makedirs(cohort)
for mesh in SHARED:
    os.symlink(os.path.join(meshes, mesh), os.path.join(cohort, mesh))
write_broken(cohort)
mapped = [os.path.splitext(m)[0] for m in SHARED]
common = ["--samples", "2000"]

# ---- Two MPI ranks.
out_mpi = os.path.join(work, "out-mpi")
result = run([mpiexec, "--allow-run-as-root", "--oversubscribe", "-n", "2", otparam, cohort,
              "-o", out_mpi, "--obj"] + common)
check(result.returncode == 1, f"mpiexec -n 2: exit status 1 when some surfaces fail "
                              f"({result.returncode})")
rows = summary(out_mpi)
check(len(rows) == 8, f"8 rows in summary.csv ({len(rows)})")
for name in mapped:
    row = rows.get(name, {})
    check(row.get("status") in ("ok", "warning") and row.get("converged") == "1"
          and row.get("flips") == "0" and os.path.isfile(os.path.join(out_mpi, name + ".vtp")),
          f"{name}: mapped, converged, no flip, {name}.vtp written "
          f"({row.get('status')}, area {row.get('area')})")
for name, words in (("fin_nonmanifold", "non-manifold"), ("torus_genus1", "genus 1")):
    row = rows.get(name, {})
    check(row.get("status") == "failed" and words in row.get("message", "")
          and not os.path.exists(os.path.join(out_mpi, name + ".vtp")),
          f"{name}: a failed row saying '{words}' ({row.get('message')})")
ranks_used = {row["rank"] for row in rows.values()}
check(ranks_used == {"0", "1"}, f"both ranks mapped surfaces ({sorted(ranks_used)})")
check(rows.get("spot_closed_3k", {}).get("domain") == "sphere"
      and rows.get("face_choi_bff_17k", {}).get("domain") == "disk",
      "the closed surface went to the sphere, the others to the disk")

# ---- --resume: nothing new.
stamps = {f: os.stat(os.path.join(out_mpi, f)).st_mtime_ns for f in os.listdir(out_mpi)
          if f.endswith(".vtp")}
result = run([mpiexec, "--allow-run-as-root", "--oversubscribe", "-n", "2", otparam, cohort,
              "-o", out_mpi, "--resume"] + common)
again = summary(out_mpi)
check(result.returncode == 1 and len(again) == 8
      and all(row["message"].startswith("resumed") for row in again.values()),
      "--resume: every row resumed, the failures kept, exit status 1")
check(all(os.stat(os.path.join(out_mpi, f)).st_mtime_ns == t for f, t in stamps.items()),
      "--resume: no output rewritten")

# ---- One process: the same outputs.
out_one = os.path.join(work, "out-one")
result = run([otparam, cohort, "-o", out_one, "-q"] + common)
check(result.returncode == 1 and len(summary(out_one)) == 8, "one process: 8 rows, exit 1")
for name in mapped:
    a, b = os.path.join(out_mpi, name + ".vtp"), os.path.join(out_one, name + ".vtp")
    different = differences(read_vtp(a), read_vtp(b)) if os.path.isfile(b) else ["missing"]
    check(not different, f"{name}.vtp: one process and 2 MPI ranks agree bit for bit "
                         f"({different or 'identical'})")

# ---- --obj: texture coordinates for Blender/MeshLab (in the unit square, where they put the
# image), read back.
for name, disk in (("face_dense_gpp_5k", True), ("spot_closed_3k", False)):
    vtp = read_vtp(os.path.join(out_mpi, name + ".vtp"))
    reader = vtkOTParamMeshReader()
    reader.SetFileName(os.path.join(out_mpi, name + ".obj"))
    reader.Update()
    obj = reader.GetOutput()
    tcoords = obj.GetPointData().GetTCoords()
    map_tcoords = vtk_to_numpy(vtp.GetPointData().GetTCoords())
    expected = 0.5 * (map_tcoords + 1.0) if disk else map_tcoords
    same = (obj.GetNumberOfPoints() == vtp.GetNumberOfPoints()
            and obj.GetNumberOfCells() == vtp.GetNumberOfCells() and tcoords is not None
            and numpy.allclose(vtk_to_numpy(tcoords), expected, rtol=0, atol=1e-12)
            and numpy.allclose(vtk_to_numpy(obj.GetPoints().GetData()),
                               vtk_to_numpy(vtp.GetPoints().GetData()), rtol=1e-12, atol=0))
    check(same, f"{name}.obj: the points and triangles of {name}.vtp, its texture coordinates "
                f"{'moved into the unit square' if disk else 'as they are'}")
    uv = vtk_to_numpy(tcoords)
    check(uv.min() >= 0.0 and uv.max() <= 1.0, f"{name}.obj: texture coordinates in [0, 1]^2")
    if disk:
        radius = numpy.hypot(uv[:, 0] - 0.5, uv[:, 1] - 0.5)
        check(abs(radius.max() - 0.5) <= 1e-12,
              f"{name}.obj: the disk inscribed in the unit square ({radius.max():.15f})")

# ---- Other formats: the hemisphere written as PLY, STL (a soup: merged on reading), legacy VTK
# and VTP maps as the OBJ does.
from vtkmodules.vtkIOGeometry import vtkSTLWriter
from vtkmodules.vtkIOLegacy import vtkPolyDataWriter
from vtkmodules.vtkIOPLY import vtkPLYWriter
from vtkmodules.vtkIOXML import vtkXMLPolyDataWriter
formats = os.path.join(work, "formats")
os.makedirs(formats)
hemisphere = vtkOTParamMeshReader()
hemisphere.SetFileName(os.path.join(meshes, "hemisphere_2k.obj"))
for writer, extension in ((vtkPLYWriter(), "ply"), (vtkSTLWriter(), "stl"),
                          (vtkPolyDataWriter(), "vtk"), (vtkXMLPolyDataWriter(), "vtp")):
    writer.SetInputConnection(hemisphere.GetOutputPort())
    writer.SetFileName(os.path.join(formats, f"hemisphere.{extension}"))
    if extension == "vtp":
        writer.SetDataModeToBinary()  # inline: Debian 12's VTK cannot read appended data
    writer.Write()
out_formats = os.path.join(work, "out-formats")
result = run([otparam, os.path.join(formats, "*.*"), "-o", out_formats, "-q"] + common)
by_name = summary(out_formats)
check(result.returncode == 0 and sorted(by_name) == ["hemisphere_ply", "hemisphere_stl",
                                                      "hemisphere_vtk", "hemisphere_vtp"]
      and all(row["status"] == "ok" and row["vertices"] == "2051" for row in by_name.values()),
      "PLY, STL, VTK and VTP (a glob; same stem: <stem>_<extension>) map with 2051 vertices "
      f"each ({ {name: (row['status'], row['vertices']) for name, row in by_name.items()} })")

# ---- A timeout is a failed row naming the stage; the filter is aborted, not the run.
out_timeout = os.path.join(work, "out-timeout")
result = run([otparam, os.path.join(cohort, "face_choi_bff_17k.obj"),
              os.path.join(cohort, "hemisphere_2k.obj"), "-o", out_timeout, "--timeout", "0.01"])
late = summary(out_timeout).get("face_choi_bff_17k", {})
check(result.returncode == 1 and late.get("status") == "failed"
      and "timed out" in late.get("message", "") and "stage" in late.get("message", ""),
      f"--timeout: a failed row saying where it stopped ({late.get('message')})")

# ---- Thread counts: the same map with 1 and 2 OpenMP threads, at a size where the conformal map
# factors with CHOLMOD's supernodal code on OpenBLAS (whose last bits change with its own thread
# count, which the launcher keeps at one).
from vtkmodules.vtkFiltersModeling import vtkLoopSubdivisionFilter
large = os.path.join(work, "large")
os.makedirs(large)
face = vtkOTParamMeshReader()
face.SetFileName(os.path.join(meshes, "face_choi_bff_17k.obj"))
subdivide = vtkLoopSubdivisionFilter()
subdivide.SetNumberOfSubdivisions(2)
subdivide.SetInputConnection(face.GetOutputPort())
writer = vtkXMLPolyDataWriter()
writer.SetInputConnection(subdivide.GetOutputPort())
writer.SetFileName(os.path.join(large, "face_273k.vtp"))
writer.SetDataModeToBinary()
writer.Write()
maps = {}
for threads in ("1", "2"):
    out_threads = os.path.join(work, "out-threads-" + threads)
    result = run([otparam, large, "-o", out_threads, "-q"], env={"OMP_NUM_THREADS": threads})
    row = summary(out_threads).get("face_273k", {})
    maps[threads] = read_vtp(os.path.join(out_threads, "face_273k.vtp")) \
        if row.get("status") == "ok" else None
check(all(maps.values()) and maps["1"].GetNumberOfPoints() > 270000
      and not differences(maps["1"], maps["2"]),
      "273k points, OMP_NUM_THREADS 1 and 2: the same .vtp, array for array "
      f"({differences(maps['1'], maps['2']) if all(maps.values()) else 'not mapped'})")

# ---- Usage errors.
result = run([otparam, os.path.join(work, "no-such-dir"), "-o", os.path.join(work, "x")])
check(result.returncode == 2 and "no surface files" in result.stderr,
      f"no input surface: exit 2 with a message ({result.stderr.strip()})")
result = run([otparam, cohort, "-o", os.path.join(work, "x"), "--samples", "-5"])
check(result.returncode == 2 and "--samples" in result.stderr,
      f"absurd --samples: exit 2 naming the option ({result.stderr.strip()[-80:]})")

print(f"{len(failures)} check(s) failed" if failures else "all checks passed")
sys.exit(1 if failures else 0)
