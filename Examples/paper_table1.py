#!/usr/bin/python3
"""The paper's Table 1 on the shared meshes: for Adaptive and for Uniform sampling, the Newton
iterations of the transport and its final relative cell-mass error, plus the mesh's size and
what the composition reaches; and the paper's figure set for one mesh.

    paper_table1.py [OUTPUT_DIR] [--meshes NAME ...] [--figures NAME] [--samples N]

Meshes are read from ../shared/data/meshes beside the checkout (or OTPARAM_SHARED_DATA_DIR).
Prints a Markdown table and writes it to OUTPUT_DIR/table1.md; with --figures (default
hand_choi_53k.off; "none" to skip) writes that mesh's figure set as PNGs and its outputs as
.vtp into OUTPUT_DIR/<mesh>/ (see area_preserving_demo.py). The uniform runs are limited to
MaximumNumberOfIterations = 200 (the filter's default): the paper's uniform sampling failed to
converge on the hand and the brain.
"""

import argparse
import os
import sys
import time

from area_preserving_demo import (STAGE_OUTPUTS, run_stages, write_figures, write_histograms,
                                  write_vtp)
from otparam_example_utils import ensure_display, read_surface

MESHES = ["hand_stein_810.obj", "hemisphere_2k.obj", "face_dense_gpp_5k.obj",
          "face_choi_bff_17k.obj", "chinese_lion_17k.off", "ogre_face_20k.obj",
          "face_maxplanck_partial_32k.obj", "brain_cortex_cut_48k.off", "hand_choi_53k.off",
          "bust_aphrodite_56k.obj"]


def shared_mesh(name):
    here = os.path.dirname(os.path.abspath(__file__))
    data = os.environ.get("OTPARAM_SHARED_DATA_DIR",
                          os.path.join(here, "..", "..", "shared", "data"))
    return os.path.join(data, "meshes", name)


def edge_count(surface):
    from vtkmodules.vtkCommonCore import vtkIdList
    edges = set()
    ids = vtkIdList()
    polys = surface.GetPolys()
    for c in range(polys.GetNumberOfCells()):
        polys.GetCellAtId(c, ids)
        n = ids.GetNumberOfIds()
        for k in range(n):
            a, b = ids.GetId(k), ids.GetId((k + 1) % n)
            edges.add((min(a, b), max(a, b)))
    return len(edges)


def run(surface, mode, samples):
    from otparam import vtkAreaPreservingParam
    param = vtkAreaPreservingParam()
    param.SetInputData(surface)
    param.SetSamplingMode(mode)
    param.SetNumberOfSamples(samples)
    start = time.perf_counter()
    param.Update()
    seconds = time.perf_counter() - start
    fd = param.GetOutput().GetFieldData()

    def value(name):
        array = fd.GetArray(name)
        return array.GetValue(0) if array is not None else float("nan")

    return param, {k: value(k) for k in (
        "Iterations", "RelativeError", "Converged", "NumberOfSamples", "FlippedTriangles",
        "MeanAbsLogAreaRatio", "MassCoefficientOfVariation")}, seconds


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("output", nargs="?", default="otparam-output", help="output directory")
    parser.add_argument("--meshes", nargs="+", default=MESHES, help="shared mesh file names")
    parser.add_argument("--figures", default="hand_choi_53k.off",
                        help="mesh whose figure set is written ('none': skip)")
    parser.add_argument("--samples", type=int, default=5000, help="NumberOfSamples (5000)")
    parser.add_argument("--size", type=int, default=1200, help="picture width in pixels")
    parser.add_argument("--no-picture", action="store_true", help="skip the PNGs")
    args = parser.parse_args()
    if args.figures == "none":
        args.no_picture = True
    ensure_display(args)
    os.makedirs(args.output, exist_ok=True)

    header = ("| model | vertices | edges | faces | adaptive: samples | mass CV | Newton its | "
              "rel. error | mean abs log area | s | uniform: mass CV | Newton its | rel. error | "
              "converged |\n|---|---|---|---|---|---|---|---|---|---|---|---|---|---|")
    print(header, flush=True)
    rows = [header]
    for name in args.meshes:
        surface = read_surface(shared_mesh(name))
        _, adaptive, seconds = run(surface, 0, args.samples)
        _, uniform, _ = run(surface, 1, args.samples)
        row = (f"| {name.rsplit('.', 1)[0]} | {surface.GetNumberOfPoints()} | "
               f"{edge_count(surface)} | {surface.GetNumberOfCells()} | "
               f"{adaptive['NumberOfSamples']:.0f} | {adaptive['MassCoefficientOfVariation']:.2f} | "
               f"{adaptive['Iterations']:.0f} | {adaptive['RelativeError']:.1e} | "
               f"{adaptive['MeanAbsLogAreaRatio']:.4f} | {seconds:.1f} | "
               f"{uniform['MassCoefficientOfVariation']:.1f} | {uniform['Iterations']:.0f} | "
               f"{uniform['RelativeError']:.1e} | "
               f"{'yes' if uniform['Converged'] == 1 else 'no'} |")
        print(row, flush=True)
        rows.append(row)
    table = os.path.join(args.output, "table1.md")
    with open(table, "w") as f:
        f.write("\n".join(rows) + "\n")
    print("wrote", table)

    if args.figures != "none":
        directory = os.path.join(args.output, args.figures.rsplit(".", 1)[0])
        os.makedirs(directory, exist_ok=True)
        surface = read_surface(shared_mesh(args.figures))
        param, _, _ = run(surface, 0, args.samples)
        write_vtp(param.GetOutput(), os.path.join(directory, "area_preserving_surface.vtp"))
        write_vtp(param.GetOutput(1), os.path.join(directory, "area_preserving_disk.vtp"))
        write_histograms(param.GetOutputDataObject(2),
                         os.path.join(directory, "distortion_histograms.csv"))
        conformal, sampler, transport = run_stages(surface, args.samples, 0)
        for data, stage in zip((conformal.GetOutput(), sampler.GetOutput(),
                                transport.GetOutput(1), transport.GetOutput(2),
                                transport.GetOutput(3)), STAGE_OUTPUTS):
            write_vtp(data, os.path.join(directory, stage + ".vtp"))
        if not args.no_picture:
            write_figures(param, conformal, sampler, transport, directory, args.size)
    return 0


if __name__ == "__main__":
    sys.exit(main())
