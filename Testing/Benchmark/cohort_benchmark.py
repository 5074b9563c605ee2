#!/usr/bin/env python3
"""Wall time of the command line `otparam` on a cohort, on 1 and 2 MPI ranks, as a table.

    Testing/Benchmark/cohort_benchmark.py build/bin/otparam [--repeat 3] [--meshes DIR] [MESH...]

Default cohort: the 10 shared disk meshes (../shared/data/meshes, 810 to 56k vertices). Each
configuration runs --repeat times, interleaved (the machine drifts); the table gives min,
median and max wall seconds, the speed-up of the medians over one process, and per surface
the median seconds and peak memory of one process (from summary.csv and /usr/bin/time).
Configurations: `mpiexec -n 1` and `mpiexec -n 2` (pvbatch ranks; the launcher divides the
cores among the ranks: 2 OpenMP threads for one rank, 1 each for two on this 2-core machine),
and one process without mpiexec (plain Python), with OpenMP threads = cores and with 1 thread.
Speed-ups are against `mpiexec -n 1`.
"""

import argparse
import csv
import os
import shutil
import statistics
import subprocess
import sys
import tempfile
import time

DISK_MESHES = ("brain_cortex_cut_48k.off", "bust_aphrodite_56k.obj", "chinese_lion_17k.off",
               "face_choi_bff_17k.obj", "face_dense_gpp_5k.obj",
               "face_maxplanck_partial_32k.obj", "hand_choi_53k.off", "hand_stein_810.obj",
               "hemisphere_2k.obj", "ogre_face_20k.obj")


def main():
    here = os.path.dirname(os.path.abspath(__file__))
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("otparam")
    parser.add_argument("meshes", nargs="*", default=DISK_MESHES)
    parser.add_argument("--repeat", type=int, default=3)
    parser.add_argument("--mesh-dir", default=os.path.join(here, "..", "..", "..", "shared",
                                                           "data", "meshes"))
    parser.add_argument("--mpiexec", default=shutil.which("mpiexec") or "mpiexec")
    args = parser.parse_args()

    work = tempfile.mkdtemp(prefix="otparam-cohort-")
    cohort = os.path.join(work, "cohort")
    os.makedirs(cohort)
    for mesh in args.meshes:
        os.symlink(os.path.abspath(os.path.join(args.mesh_dir, mesh)), os.path.join(cohort, mesh))
    mpi = [args.mpiexec, "--allow-run-as-root", "--oversubscribe", "-n"]
    configurations = [
        ("mpiexec -n 1 (OpenMP threads = cores)", mpi + ["1"], {}),
        ("mpiexec -n 2 (1 thread per rank)", mpi + ["2"], {}),
        ("no mpiexec, OpenMP threads = cores", [], {}),
        ("no mpiexec, 1 thread", [], {"OMP_NUM_THREADS": "1"}),
    ]
    seconds = {label: [] for label, _, _ in configurations}
    per_surface = {}
    for run in range(args.repeat):
        for label, prefix, env in configurations:
            out = os.path.join(work, f"out-{run}")
            shutil.rmtree(out, ignore_errors=True)
            start = time.monotonic()
            result = subprocess.run(prefix + [args.otparam, cohort, "-o", out, "-q"],
                                    env=dict(os.environ, **env), capture_output=True, text=True)
            seconds[label].append(time.monotonic() - start)
            if result.returncode != 0:
                print(f"{label}: exit {result.returncode}\n{result.stdout}{result.stderr}")
                return 1
            if label.startswith("no mpiexec, OpenMP"):
                with open(os.path.join(out, "summary.csv"), newline="") as f:
                    for row in csv.DictReader(f):
                        per_surface.setdefault(row["name"], (row, []))[1].append(
                            float(row["seconds"]))
    base = statistics.median(seconds[configurations[0][0]])
    print(f"Cohort of {len(args.meshes)} surfaces, {args.repeat} runs each (wall seconds, "
          f"launch and summary included):\n")
    print("| configuration | min | median | max | speed-up (medians) |")
    print("|---|---|---|---|---|")
    for label, _, _ in configurations:
        s = seconds[label]
        print(f"| {label} | {min(s):.1f} | {statistics.median(s):.1f} | {max(s):.1f} | "
              f"{base / statistics.median(s):.2f} |")
    print("\nPer surface, one process (median seconds in summary.csv):\n")
    print("| surface | vertices | seconds | area | flips |")
    print("|---|---|---|---|---|")
    for name, (row, times) in sorted(per_surface.items(), key=lambda kv: -int(kv[1][0]["vertices"])):
        print(f"| {name} | {row['vertices']} | {statistics.median(times):.2f} | "
              f"{float(row['area']):.4f} | {row['flips']} |")
    shutil.rmtree(work, ignore_errors=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
