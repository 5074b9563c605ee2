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
from otparam_test_utils import check, check_image, field_value, finish, image_test_arguments  # noqa: E402,E501

baseline, _ = image_test_arguments()

surface = make_default_surface()
mapper = vtkConformalDiskMap()
mapper.SetInputData(surface)
mapper.Update()
disk = mapper.GetOutput()
check(field_value(disk, "FlippedTriangles") == 0, "no flipped triangle")
check(field_value(disk, "MeanAngleDistortion") < 0.5, "mean angle distortion below 0.5 degrees")

check_image(render(surface, disk, size=800), baseline)
finish()
