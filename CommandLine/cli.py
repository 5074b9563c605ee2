"""otparam: area-preserving parameterizations of many surfaces, in one process or on MPI ranks.

    otparam IN... -o OUTDIR [--domain auto|disk|sphere] [--samples N] [--tolerance T] ...
    mpiexec -n 8 otparam cohort/ -o maps/

Every input surface (OFF, OBJ, PLY, STL, VTP, VTK; a directory or a glob expands to the
surfaces in it) goes through vtkAreaPreservingParam; OUTDIR gets <name>.vtp per surface (the
surface with its coordinates, distortion arrays and figures) and summary.csv (one row per
surface). Under mpiexec every rank runs this script in ParaView's pvbatch (the `otparam`
launcher does that) and takes the next surface, largest first, from a counter on rank 0
(an MPI one-sided fetch-and-add), so a slow surface never idles the others. Installed as
otparam/cli.py in the `otparam` package: `python3 -m otparam.cli --help`.
"""

import argparse
import csv
import glob
import hashlib
import json
import os
import sys
import time

SURFACE_EXTENSIONS = (".off", ".obj", ".ply", ".stl", ".vtp", ".vtk")
SUMMARY_COLUMNS = ("name", "status", "rank", "seconds", "vertices", "triangles", "domain",
                   "converged", "relative_error", "iterations", "samples", "area", "angle",
                   "flips", "parameters", "input", "message")
DOMAINS = {"auto": 0, "disk": 1, "sphere": 2}
SAMPLING = {"adaptive": 0, "uniform": 1, "vertices": 2}
EXIT_OK, EXIT_SOME_FAILED, EXIT_USAGE = 0, 1, 2


def parse_arguments(argv):
    parser = argparse.ArgumentParser(
        prog="otparam",
        description="Area-preserving parameterizations of surfaces by semi-discrete optimal "
                    "transport (OTParam): disk-like surfaces onto the unit disk, closed genus-0 "
                    "surfaces onto the unit sphere. Writes OUTDIR/<name>.vtp per input and "
                    "OUTDIR/summary.csv. Under `mpiexec -n N otparam ...` the surfaces are "
                    "shared out over N ranks of ParaView's pvbatch.",
        epilog="Exit status: 0 when every surface was mapped, 1 when some failed (each failure "
               "is a row of summary.csv with its message), 2 on a usage error. "
               "Columns of summary.csv: " + ", ".join(SUMMARY_COLUMNS) + ". "
               "Cohorts on a cluster: docs/cohorts.md.")
    parser.add_argument("inputs", nargs="+", metavar="IN",
                        help="surface files (" + ", ".join(SURFACE_EXTENSIONS) + "), "
                             "directories (their surface files, not recursive) or globs")
    parser.add_argument("-o", "--output", required=True, metavar="OUTDIR",
                        help="output directory (created if needed)")
    parser.add_argument("--domain", choices=DOMAINS, default="auto",
                        help="auto (default): closed surfaces, and closed scans whose holes "
                             "are all small, onto the sphere; others onto the disk")
    parser.add_argument("--samples", type=int, default=0, metavar="N",
                        help="samples (Diracs) of the transport; 0 (default): automatic, 5000 "
                             "or one per 50 points, whichever is more")
    parser.add_argument("--tolerance", type=float, default=1e-10, metavar="T",
                        help="relative mass error at which the transport stops (default 1e-10)")
    parser.add_argument("--max-iterations", type=int, default=200, metavar="K",
                        help="Newton iterations of the transport at most (default 200)")
    parser.add_argument("--sampling", choices=SAMPLING, default="adaptive",
                        help="adaptive (default), uniform, or the mesh vertices")
    parser.add_argument("--no-fill-holes", action="store_true",
                        help="refuse surfaces with holes instead of filling them (a disk's "
                             "extra boundary loops, a closed scan's holes)")
    parser.add_argument("--no-area-correction", action="store_true",
                        help="skip the composition's area-correction sweeps")
    parser.add_argument("--correction-sweeps", type=int, default=200, metavar="K",
                        help="area-correction sweeps at most (default 200)")
    parser.add_argument("--thorough-correction", action="store_true",
                        help="a thorough area correction: lower area and angle distortion for "
                             "about twice the correction's time")
    parser.add_argument("--obj", action="store_true",
                        help="also write <name>.obj with texture coordinates in [0, 1]^2 "
                             "(the disk inscribed in the unit square, or longitude/latitude on "
                             "the sphere) for Blender, MeshLab, ...")
    parser.add_argument("--timeout", type=float, default=3600.0, metavar="SECONDS",
                        help="give up a surface after this long, as a failed row (default "
                             "3600; 0: no limit)")
    parser.add_argument("--resume", action="store_true",
                        help="skip surfaces done by an earlier run with the same parameters "
                             "(their .vtp exists, or their failure is in summary.csv)")
    parser.add_argument("--retry-failed", action="store_true",
                        help="with --resume, run the surfaces that failed before again")
    parser.add_argument("-q", "--quiet", action="store_true",
                        help="no progress lines, only the final tally")
    arguments = parser.parse_args(argv)
    for name, low in (("samples", 0), ("max_iterations", 1), ("correction_sweeps", 0)):
        if getattr(arguments, name) < low:
            parser.error(f"--{name.replace('_', '-')} must be >= {low}")
    if 0 < arguments.samples < 3:
        parser.error("--samples must be 0 (automatic) or >= 3")
    if not 0.0 < arguments.tolerance < 1.0:
        parser.error("--tolerance must be in (0, 1)")
    if arguments.timeout < 0.0:
        parser.error("--timeout must be >= 0")
    return arguments


def mapping_parameters(arguments):
    """What the maps depend on; written into every output so --resume can compare."""
    from otparam import __version__
    return {"otparam": __version__, "domain": arguments.domain, "samples": arguments.samples,
            "tolerance": arguments.tolerance, "max_iterations": arguments.max_iterations,
            "sampling": arguments.sampling, "fill_holes": not arguments.no_fill_holes,
            "area_correction": not arguments.no_area_correction,
            "correction_sweeps": arguments.correction_sweeps,
            # Only when set: the default's key (and earlier runs' --resume) stays as it was.
            **({"thorough_correction": True} if arguments.thorough_correction else {})}


def parameters_key(parameters):
    text = json.dumps(parameters, sort_keys=True)
    return text, hashlib.sha1(text.encode()).hexdigest()[:12]


# ---- Inputs -----------------------------------------------------------------------------------

def expand_inputs(patterns):
    """(files, patterns matching nothing): files in command-line order, directories and globs
    expanded (sorted), each file once. A named file is kept whatever its extension (refused
    later, as a row)."""
    files, seen, unmatched = [], set(), []

    def add(path):
        real = os.path.realpath(path)
        if real not in seen:
            seen.add(real)
            files.append(path)

    for pattern in patterns:
        if os.path.isdir(pattern):
            found = [os.path.join(pattern, entry) for entry in sorted(os.listdir(pattern))
                     if entry.lower().endswith(SURFACE_EXTENSIONS)]
            found = [path for path in found if os.path.isfile(path)]
        elif os.path.exists(pattern):
            found = [pattern]
        else:
            found = [path for path in sorted(glob.glob(pattern)) if os.path.isfile(path)]
        for path in found:
            add(path)
        if not found:
            unmatched.append(pattern)
    return files, unmatched


def output_names(files):
    """<stem> per input; inputs sharing a stem (face.obj, face.off) get <stem>_<extension>."""
    stems = [os.path.splitext(os.path.basename(f))[0] for f in files]
    return [stem if stems.count(stem) == 1
            else f"{stem}_{os.path.splitext(f)[1].lstrip('.').lower()}"
            for stem, f in zip(stems, files)]


def largest_first(files):
    def size(path):
        try:
            return os.path.getsize(path)
        except OSError:
            return 0
    return sorted(range(len(files)), key=lambda i: (-size(files[i]), files[i]))


# ---- One surface ------------------------------------------------------------------------------

class SurfaceError(Exception):
    """A surface that cannot be mapped; its message becomes the summary row's."""


class Messages:
    """VTK errors and warnings of the algorithms watched, as text (not printed by VTK)."""

    def __init__(self):
        self.errors, self.warnings = [], []

    def watch(self, algorithm):
        from vtkmodules.util.misc import calldata_type
        from vtkmodules.util.vtkConstants import VTK_STRING

        @calldata_type(VTK_STRING)
        def on_error(caller, event, text):
            self.errors.append(self.strip(text))

        @calldata_type(VTK_STRING)
        def on_warning(caller, event, text):
            self.warnings.append(self.strip(text))

        algorithm.AddObserver("ErrorEvent", on_error)
        algorithm.AddObserver("WarningEvent", on_warning)
        # The executive's "returned failure for request" repeats the error above.
        algorithm.GetExecutive().AddObserver("ErrorEvent", lambda caller, event: None)

    @staticmethod
    def strip(text):
        """VTK's 'ERROR: In file, line N\\nclass (0x...): message' -> 'message'."""
        text = str(text).strip()
        return text.split("): ", 1)[1].strip() if "): " in text else text


def make_reader(extension):
    if extension in (".off", ".obj"):
        from otparam import vtkOTParamMeshReader
        return vtkOTParamMeshReader()
    if extension == ".ply":
        from vtkmodules.vtkIOPLY import vtkPLYReader
        return vtkPLYReader()
    if extension == ".stl":
        from vtkmodules.vtkIOGeometry import vtkSTLReader
        return vtkSTLReader()  # merges the soup's coincident points
    if extension == ".vtp":
        from vtkmodules.vtkIOXML import vtkXMLPolyDataReader
        return vtkXMLPolyDataReader()
    if extension == ".vtk":
        from vtkmodules.vtkIOLegacy import vtkGenericDataObjectReader
        return vtkGenericDataObjectReader()
    return None


def read_surface(path):
    """The file as a vtkPolyData of triangles (polygons and strips triangulated, vertices and
    lines dropped), or SurfaceError."""
    extension = os.path.splitext(path)[1].lower()
    if not os.path.isfile(path):
        raise SurfaceError(f"cannot read {path}: no such file")
    reader = make_reader(extension)
    if reader is None:
        raise SurfaceError(f"unsupported file type '{extension}' (OTParam reads "
                           + ", ".join(SURFACE_EXTENSIONS) + ")")
    messages = Messages()
    messages.watch(reader)
    reader.SetFileName(path)
    reader.Update()
    if messages.errors:
        hint = ""
        if extension == ".vtp" and "parsing" in messages.errors[0]:
            hint = (" (Debian 12's VTK cannot read .vtp files with appended data, VTK's default: "
                    "write them with inline data, e.g. SetDataModeToBinary())")
        raise SurfaceError(f"reading {os.path.basename(path)}: {messages.errors[0]}{hint}")
    data = reader.GetOutputDataObject(0)
    if data is None or not data.IsA("vtkDataSet") or data.GetNumberOfCells() == 0:
        raise SurfaceError(f"reading {os.path.basename(path)}: no surface cells in the file")
    return as_triangles(data)


def as_triangles(data):
    from vtkmodules.vtkFiltersCore import vtkTriangleFilter
    from vtkmodules.vtkFiltersGeometry import vtkGeometryFilter
    if not data.IsA("vtkPolyData"):
        surface = vtkGeometryFilter()
        surface.SetInputData(data)
        surface.Update()
        data = surface.GetOutput()
    only_triangles = (data.GetNumberOfVerts() == 0 and data.GetNumberOfLines() == 0
                      and data.GetNumberOfStrips() == 0
                      and data.GetPolys().IsHomogeneous() == 3)
    if only_triangles:
        return data
    triangles = vtkTriangleFilter()
    triangles.PassVertsOff()
    triangles.PassLinesOff()
    triangles.SetInputData(data)
    triangles.Update()
    return triangles.GetOutput()


def make_filter(arguments):
    from otparam import vtkAreaPreservingParam
    param = vtkAreaPreservingParam()
    param.SetDomain(DOMAINS[arguments.domain])
    param.SetNumberOfSamples(arguments.samples)
    param.SetTolerance(arguments.tolerance)
    param.SetMaximumNumberOfIterations(arguments.max_iterations)
    param.SetSamplingMode(SAMPLING[arguments.sampling])
    param.SetFillHoles(not arguments.no_fill_holes)
    param.SetAreaCorrection(not arguments.no_area_correction)
    param.SetMaximumCorrectionSweeps(arguments.correction_sweeps)
    param.SetThoroughAreaCorrection(arguments.thorough_correction)
    return param


def map_surface(surface, arguments, report):
    """Runs vtkAreaPreservingParam on the surface: (mapped surface, warnings) or SurfaceError.
    report(stage) is called whenever the filter enters a new stage; past the timeout the
    filter is aborted (it checks between steps of every stage)."""
    param = make_filter(arguments)
    messages = Messages()
    messages.watch(param)
    start, stage = time.monotonic(), [""]

    def on_progress(caller, event):
        text = caller.GetProgressText() or ""
        if text and text != stage[0]:
            stage[0] = text
            report(text)
        if arguments.timeout > 0 and time.monotonic() - start > arguments.timeout:
            caller.SetAbortExecute(1)

    param.AddObserver("ProgressEvent", on_progress)
    param.SetInputData(surface)
    param.Update()
    elapsed = time.monotonic() - start
    if arguments.timeout > 0 and elapsed > arguments.timeout and param.GetAbortExecute():
        raise SurfaceError(f"timed out after {elapsed:.1f} s in stage '{stage[0]}' "
                           f"(--timeout {arguments.timeout:g}; raise it, or lower --samples)")
    if messages.errors:
        raise SurfaceError(messages.errors[0])
    output = param.GetOutput()
    if output.GetNumberOfPoints() == 0:
        raise SurfaceError("; ".join(messages.warnings) or "the map came out empty")
    mapped = type(output)()
    mapped.ShallowCopy(output)
    return mapped, messages.warnings


def figures_of(mapped):
    fd = mapped.GetFieldData()

    def value(name):
        array = fd.GetArray(name)
        return array.GetValue(0) if array is not None else ""

    domain = {1: "disk", 2: "sphere"}.get(value("Domain"), "")
    return {"domain": domain, "converged": value("Converged"),
            "relative_error": value("RelativeError"), "iterations": value("Iterations"),
            "samples": value("NumberOfSamples"), "area": value("MeanAbsLogAreaRatio"),
            "angle": value("MeanAngleDistortion"), "flips": value("FlippedTriangles")}


def write_outputs(mapped, path_stem, parameters_text, write_obj):
    """<stem>.vtp (and <stem>.obj): written beside, then renamed, so an interrupted run
    never leaves a half file that --resume would take for done."""
    from vtkmodules.vtkCommonCore import vtkStringArray
    from vtkmodules.vtkIOXML import vtkXMLPolyDataWriter
    stamp = vtkStringArray()
    stamp.SetName("OTParamParameters")
    stamp.InsertNextValue(parameters_text)
    mapped.GetFieldData().AddArray(stamp)
    writer = vtkXMLPolyDataWriter()
    writer.SetDataModeToBinary()  # inline: Debian 12's VTK cannot read appended data back
    writer.SetInputData(mapped)
    write_atomically(writer, path_stem + ".vtp")
    if write_obj:
        from vtkmodules.vtkIOGeometry import vtkOBJWriter
        obj = vtkOBJWriter()
        obj.SetInputData(with_unit_square_texture(mapped))
        write_atomically(obj, path_stem + ".obj")


def with_unit_square_texture(mapped):
    """The map with texture coordinates in [0, 1]^2, where Blender and MeshLab put an image (they
    repeat it outside): the disk's (u, v) in [-1, 1]^2 become ((u + 1) / 2, (v + 1) / 2), the
    disk inscribed in the image; the sphere's longitude / latitude already are. Points used by
    no triangle (NaN) get (0, 0)."""
    import numpy
    from vtkmodules.util.numpy_support import numpy_to_vtk, vtk_to_numpy
    from vtkmodules.vtkCommonDataModel import vtkPolyData
    tcoords = vtk_to_numpy(mapped.GetPointData().GetTCoords()).astype(float)
    domain = mapped.GetFieldData().GetArray("Domain")
    if domain is not None and domain.GetValue(0) == 1:
        tcoords = 0.5 * (tcoords + 1.0)
    tcoords = numpy.nan_to_num(tcoords, nan=0.0)
    square = numpy_to_vtk(numpy.ascontiguousarray(tcoords), deep=True)
    square.SetName("TextureCoordinates")
    copy = vtkPolyData()
    copy.ShallowCopy(mapped)  # its own point data (sharing the arrays): mapped keeps its tcoords
    copy.GetPointData().SetTCoords(square)
    return copy


def write_atomically(writer, path):
    partial = path + ".partial"
    writer.SetFileName(partial)
    if writer.Write() != 1:
        raise SurfaceError(f"cannot write {path}")
    os.replace(partial, path)


def process_surface(path, name, arguments, parameters, rank):
    """One summary row: the surface read, mapped and written, or its failure."""
    start = time.monotonic()
    row = {"name": name, "rank": rank, "input": path, "parameters": parameters[1]}

    def report(stage):
        if not arguments.quiet:
            print(f"[rank {rank}] {name}: {stage} ({time.monotonic() - start:.1f} s)",
                  flush=True)

    try:
        report("reading")
        surface = read_surface(path)
        row.update(vertices=surface.GetNumberOfPoints(), triangles=surface.GetNumberOfCells())
        mapped, warnings = map_surface(surface, arguments, report)
        row.update(figures_of(mapped))
        report("writing")
        write_outputs(mapped, os.path.join(arguments.output, name), parameters[0], arguments.obj)
        row.update(status="ok" if row["converged"] == 1 and not warnings else "warning",
                   message="; ".join(warnings))
    except SurfaceError as error:
        row.update(status="failed", message=str(error))
    except Exception as error:  # noqa: BLE001  a bug of ours must not end the other surfaces
        row.update(status="failed", message=f"internal error ({type(error).__name__}: {error})")
    row["seconds"] = round(time.monotonic() - start, 3)
    if not arguments.quiet:
        detail = row["message"] if row["status"] == "failed" else (
            f"area {row.get('area', 0):.4f}, angle {row.get('angle', 0):.2f} deg, "
            f"flips {row.get('flips')}")
        print(f"[rank {rank}] {name}: {row['status']} in {row['seconds']:.1f} s ({detail})",
              flush=True)
    return row


# ---- Resuming ---------------------------------------------------------------------------------

def finished_output(vtp_path):
    """(OTParamParameters stamp, surface) of an output an earlier run wrote, or (None, None)."""
    from vtkmodules.vtkIOXML import vtkXMLPolyDataReader
    if not os.path.isfile(vtp_path):
        return None, None
    reader = vtkXMLPolyDataReader()
    reader.SetFileName(vtp_path)
    reader.Update()
    data = reader.GetOutput()
    stamp = data.GetFieldData().GetAbstractArray("OTParamParameters")
    return (stamp.GetValue(0) if stamp is not None and stamp.GetNumberOfValues() else None), data


def earlier_rows(output_dir):
    """Rows of the last summary.csv and of the journal an interrupted run left, by name."""
    rows = {}
    sources = [os.path.join(output_dir, "summary.csv")]
    journal = os.path.join(output_dir, ".otparam-journal")
    if os.path.isdir(journal):
        sources += [os.path.join(journal, f) for f in sorted(os.listdir(journal))]
    for source in sources:
        if os.path.isfile(source):
            with open(source, newline="") as f:
                for row in csv.DictReader(f):
                    rows[row.get("name")] = row
    return rows


def resumed_row(name, arguments, parameters, earlier, rank):
    """The row of a surface an earlier run finished with these parameters, or None."""
    before = earlier.get(name)
    if before is None or before.get("parameters") != parameters[1]:
        before = None
    stamp, data = finished_output(os.path.join(arguments.output, name + ".vtp"))
    if stamp == parameters[0]:
        row = dict(before) if before is not None else dict(
            name=name, status="ok", parameters=parameters[1], vertices=data.GetNumberOfPoints(),
            triangles=data.GetNumberOfCells(), **figures_of(data))
    elif before is not None and before.get("status") == "failed" and not arguments.retry_failed:
        row = dict(before)
    else:
        return None
    row.update(rank=rank, seconds=0.0)
    row["message"] = ("resumed: " + row.get("message", "")).rstrip(": ")
    return row


# ---- Ranks ------------------------------------------------------------------------------------

def launched_by_mpi():
    return any(v in os.environ for v in ("OMPI_COMM_WORLD_SIZE", "PMI_SIZE", "PMIX_RANK"))


class Ranks:
    """The processes sharing the cohort: MPI's COMM_WORLD under mpiexec, else this one.
    Surfaces are handed out by a fetch-and-add on a counter in rank 0's memory (MPI one-sided
    communication), so every rank, rank 0 included, maps surfaces and takes the next one as
    soon as it is free."""

    def __init__(self):
        self.comm, self.rank, self.size, self.taken = None, 0, 1, 0
        if launched_by_mpi():
            from mpi4py import MPI
            self.mpi, self.comm = MPI, MPI.COMM_WORLD
            self.rank, self.size = self.comm.Get_rank(), self.comm.Get_size()
        if self.size > 1:
            import numpy
            self.one = numpy.ones(1, dtype=numpy.int64)
            self.taken_buffer = numpy.zeros(1, dtype=numpy.int64)
            self.window = self.mpi.Win.Allocate(8 if self.rank == 0 else 0, 8, comm=self.comm)
            if self.rank == 0:
                self.window.Lock(0)
                self.window.Put(numpy.zeros(1, dtype=numpy.int64), 0)
                self.window.Unlock(0)
            self.comm.Barrier()

    def next_index(self):
        if self.size == 1:
            self.taken += 1
            return self.taken - 1
        self.window.Lock(0, self.mpi.LOCK_SHARED)
        self.window.Fetch_and_op(self.one, self.taken_buffer, 0, 0, self.mpi.SUM)
        self.window.Unlock(0)
        return int(self.taken_buffer[0])

    def gather(self, rows):
        """Every rank's rows on rank 0 (None elsewhere)."""
        if self.size == 1:
            return rows
        everyone = self.comm.gather(rows, root=0)
        return [row for part in everyone for row in part] if self.rank == 0 else None

    def finish(self):
        if self.size > 1:
            self.window.Free()


# ---- The cohort -------------------------------------------------------------------------------

def journal_writer(output_dir, rank):
    """Appends each finished row to OUTDIR/.otparam-journal/rank<k>.csv (flushed), so --resume
    after an interrupted run knows the failures it already met."""
    journal = os.path.join(output_dir, ".otparam-journal")
    os.makedirs(journal, exist_ok=True)
    handle = open(os.path.join(journal, f"rank{rank}.csv"), "a", newline="")
    writer = csv.DictWriter(handle, fieldnames=SUMMARY_COLUMNS, extrasaction="ignore")
    if handle.tell() == 0:
        writer.writeheader()

    def record(row):
        writer.writerow(row)
        handle.flush()
    return record, handle


def run_rank(files, names, arguments, ranks):
    parameters = parameters_key(mapping_parameters(arguments))
    earlier = earlier_rows(arguments.output) if arguments.resume else {}
    order = largest_first(files)
    record, handle = journal_writer(arguments.output, ranks.rank)
    rows = []
    while True:
        taken = ranks.next_index()
        if taken >= len(order):
            break
        i = order[taken]
        row = resumed_row(names[i], arguments, parameters, earlier, ranks.rank) \
            if arguments.resume else None
        if row is None:
            row = process_surface(files[i], names[i], arguments, parameters, ranks.rank)
        elif not arguments.quiet:
            print(f"[rank {ranks.rank}] {names[i]}: {row['status']}, resumed", flush=True)
        record(row)
        rows.append(row)
    handle.close()
    return rows


def write_summary(rows, output_dir):
    rows = sorted(rows, key=lambda row: row["name"])
    path = os.path.join(output_dir, "summary.csv")
    with open(path + ".partial", "w", newline="") as f:
        writer = csv.DictWriter(f, fieldnames=SUMMARY_COLUMNS, extrasaction="ignore")
        writer.writeheader()
        writer.writerows(rows)
    os.replace(path + ".partial", path)
    journal = os.path.join(output_dir, ".otparam-journal")
    for entry in os.listdir(journal):
        os.remove(os.path.join(journal, entry))
    os.rmdir(journal)
    return path


def tally(rows, seconds, ranks, summary_path):
    count = {status: sum(row["status"] == status for row in rows)
             for status in ("ok", "warning", "failed")}
    resumed = sum(str(row.get("message", "")).startswith("resumed") for row in rows)
    print(f"otparam: {len(rows)} surface(s): {count['ok']} ok, {count['warning']} with "
          f"warnings, {count['failed']} failed ({resumed} resumed); {seconds:.1f} s on "
          f"{ranks} rank(s); summary: {summary_path}", flush=True)
    for row in rows:
        if row["status"] == "failed":
            print(f"  failed: {row['name']}: {row['message']}", flush=True)
    return EXIT_SOME_FAILED if count["failed"] else EXIT_OK


def main(argv=None):
    arguments = parse_arguments(sys.argv[1:] if argv is None else argv)
    start = time.monotonic()
    ranks = Ranks()
    if ranks.rank == 0:
        os.makedirs(arguments.output, exist_ok=True)
    if ranks.size > 1:
        ranks.comm.Barrier()
    files, unmatched = expand_inputs(arguments.inputs)
    if ranks.rank == 0:
        for pattern in unmatched:
            print(f"otparam: {pattern}: no surface files ({', '.join(SURFACE_EXTENSIONS)})",
                  file=sys.stderr, flush=True)
    if not files:
        if ranks.rank == 0:
            print("otparam: no surface files to map", file=sys.stderr, flush=True)
        return EXIT_USAGE
    names = output_names(files)
    rows = ranks.gather(run_rank(files, names, arguments, ranks))
    ranks.finish()
    if ranks.rank != 0:
        return EXIT_OK  # rank 0 reports the cohort's status (one exit code for mpiexec)
    summary = write_summary(rows, arguments.output)
    return tally(rows, time.monotonic() - start, ranks.size, summary)


if __name__ == "__main__":
    status = main()
    # pvbatch finalizes MPI only when its script ends: sys.exit(0) would skip that, and
    # mpiexec would call the run aborted. A failure's exit status still needs sys.exit.
    if status != EXIT_OK:
        sys.exit(status)
