"""Regression images of the complicated-supports figure (the paper's Fig. 13 analogue), drawn
by the example's own function (Examples/complicated_supports.py): for two half-disks, an
annulus and a letter C, the source disk with the power cells coloured by target position and
the singularity set in black, beside the target support with its samples.

    TestComplicatedSupportsImage.py BASELINE_DIR TEMP_DIR

A missing baseline makes the test write the rendered image into TEMP_DIR and fail: look at it
before committing it as the baseline. Needs an X display (CMake runs it under xvfb-run)."""

import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "..", "Examples"))

from complicated_supports import SHAPES, render_support_figure, transport_onto  # noqa: E402
from otparam_test_utils import check, check_image, field_value, finish, image_test_arguments  # noqa: E402,E501

baseline_dir, _ = image_test_arguments()

first = True
for name, make in SHAPES.items():
    sampler, solver = transport_onto(make(), 1500)
    check(field_value(solver.GetOutput(0), "Converged") == 1, f"{name}: the transport converges")
    check(solver.GetOutput(4).GetNumberOfCells() > 0, f"{name}: a singularity set")
    if first:
        # Under Xvfb, Debian's VTK 9.2 renders the first picture of a process black.
        render_support_figure(sampler, solver, None, 100)
        first = False
    check_image(render_support_figure(sampler, solver, None, 300),
                os.path.join(baseline_dir, f"TestComplicatedSupportsImage_{name}.png"), f"{name}: ")
finish()
