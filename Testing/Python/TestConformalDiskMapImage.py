"""Regression image of vtkConformalDiskMap on the built-in surface of the main job: the 3D
surface with a checkerboard through the conformal coordinates (left; conformal = the squares
stay square) and the disk image coloured by log10 AreaDensity (right).

    TestConformalDiskMapImage.py BASELINE.png TEMP_DIR

A missing baseline makes the test write the rendered image into TEMP_DIR and fail: look at it
before committing it as the baseline. Needs an X display (CMake runs it under xvfb-run)."""

import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "..", "Examples"))

from conformal_map_demo import make_default_surface, render  # noqa: E402
from otparam import vtkConformalDiskMap  # noqa: E402
from otparam_test_utils import check, field_value, finish  # noqa: E402
from vtkmodules.test import Testing  # noqa: E402

baseline, temp_dir = sys.argv[1], sys.argv[2]
Testing.VTK_TEMP_DIR = temp_dir
os.makedirs(temp_dir, exist_ok=True)

surface = make_default_surface()
mapper = vtkConformalDiskMap()
mapper.SetInputData(surface)
mapper.Update()
disk = mapper.GetOutput()
check(field_value(disk, "FlippedTriangles") == 0, "no flipped triangle")
check(field_value(disk, "MeanAngleDistortion") < 0.5, "mean angle distortion below 0.5 degrees")

window = render(surface, disk, size=800)
try:
    Testing.compareImage(window, baseline, threshold=0.15)
except RuntimeError as error:
    check(False, f"image differs from {baseline}: {error}")
finish()
