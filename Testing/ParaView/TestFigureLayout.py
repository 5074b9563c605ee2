"""Runs Examples/paraview_figure_layout.py (the paper's figure layout in ParaView) on a shared
face and checks the pictures it saves: the four views and the bar chart are drawn.

Usage: pvpython TestFigureLayout.py <OTParam.so> <surface> <work dir>   (under xvfb-run)"""

import os
import runpy
import sys

plugin, surface, work_dir = sys.argv[1:4]
os.makedirs(work_dir, exist_ok=True)
layout_png = os.path.join(work_dir, "paper_layout.png")
example = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "Examples",
                       "paraview_figure_layout.py")
sys.argv = [example, plugin, surface, layout_png]
runpy.run_path(example, run_name="__main__")

import numpy  # noqa: E402
from vtkmodules.util.numpy_support import vtk_to_numpy  # noqa: E402
from vtkmodules.vtkIOImage import vtkPNGReader  # noqa: E402

failures = []
for png, columns, least_colors in ((layout_png, 4, 200),
                                   (layout_png.replace(".png", "_histogram.png"), 1, 3)):
    reader = vtkPNGReader()
    reader.SetFileName(png)
    reader.Update()
    image = reader.GetOutput()
    width, height, _ = image.GetDimensions()
    pixels = vtk_to_numpy(image.GetPointData().GetScalars())[:, :3].reshape(height, width, 3)
    # Every view (a quarter of the width each) must show something besides the background.
    for k in range(columns):
        part = pixels[:, k * width // columns:(k + 1) * width // columns].reshape(-1, 3)
        colors = len(numpy.unique(part, axis=0))
        if colors < least_colors:
            failures.append(f"{png}, view {k}: only {colors} colours")
print("\n".join(failures) or "all checks passed", flush=True)
# os._exit: pvpython's teardown of its render windows under Xvfb can end in "GLXBadContext"
# and a failing exit code after everything passed.
os._exit(1 if failures else 0)
