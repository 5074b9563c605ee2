"""Regression images of the area-preserving pipeline on the main job's built-in hand-like
surface, drawn by the example's own functions (Examples/area_preserving_demo.py):
- _circles: the surface textured with circles through the conformal coordinates (left) and
  through the area-preserving ones (right: ellipses of equal area);
- _histograms: the four distortion histograms (port 2, the paper's Fig. 5) as bar charts;
- _power_diagram: the transport's power diagram coloured by DiracId over the weighted Delaunay
  triangulation;
- _brenier: the Brenier potential and its Legendre dual in 3D.

    TestAreaPreservingParamImage.py BASELINE_DIR TEMP_DIR

A missing baseline makes the test write the rendered image into TEMP_DIR and fail: look at it
before committing it as the baseline. Needs an X display (CMake runs it under xvfb-run)."""

import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "..", "Examples"))

from area_preserving_demo import (make_hand_like_surface, render_brenier_legendre,  # noqa: E402
                                  render_circle_texture, render_density_and_samples,
                                  render_histograms, run_stages)
from ot_solver_demo import render_png as render_power_diagram  # noqa: E402
from otparam import vtkAreaPreservingParam  # noqa: E402
from otparam_test_utils import check, check_image, field_value, finish, image_test_arguments  # noqa: E402,E501

baseline_dir, _ = image_test_arguments()

surface = make_hand_like_surface()
param = vtkAreaPreservingParam()
param.SetInputData(surface)
param.Update()
out = param.GetOutput()
check(field_value(out, "Converged") == 1, "the transport converges")
check(field_value(out, "FlippedTriangles") == 0, "no flipped triangle")
check(field_value(out, "MeanAbsLogAreaRatio") <= 0.03, "mean |log area ratio| <= 0.03")
conformal, sampler, transport = run_stages(surface, 5000, 0)

# Under Xvfb, Debian's VTK 9.2 renders the first picture of a process black: draw one to waste.
render_density_and_samples(conformal.GetOutput(), sampler.GetOutput(), None, 200)
pictures = {
    "circles": render_circle_texture(out, None, 800),
    "histograms": render_histograms(param.GetOutputDataObject(2), None, 800),
    "power_diagram": render_power_diagram(transport, None, 600),
    "brenier": render_brenier_legendre(transport, None, 800),
}
for name, window in pictures.items():
    check_image(window, os.path.join(baseline_dir, f"TestAreaPreservingParamImage_{name}.png"),
                f"{name}: ")
finish()
