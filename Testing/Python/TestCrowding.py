"""Conformal crowding: a disk with one finger (a tube of radius rho and length L, capped) is
crowded by the conformal map into a part of the disk whose area density grows like
exp(2 L / rho). Measured with default properties: the pipeline converges with no flip up to
L / rho = 14 (the conformal area density spans e^28.7 = 3e12; the area error grows from 0.003 at
L / rho = 2 to 0.034), and from L / rho = 15 (e^30.6) the transport stops at its start. Past
that point the user gets a warning that names the cause (the crowding, with its range) and
what to do, never only the solver's internal state."""

import math

from otparam import vtkAreaPreservingParam
from otparam_test_utils import MessageRecorder, check, field_value, finish, make_domain
from vtkmodules.vtkCommonCore import vtkCommand


def finger(length_over_radius, rho=0.2, n=24):
    h = 2 * math.pi / n  # spacing relative to the local radius
    rings = []  # (r, z)
    r = 1.0
    while r > rho * (1 + 0.5 * h):
        rings.append((r, 0.0))
        r *= math.exp(-h)
    # A sharp bend from the plane into the tube, as scans have.
    z = 0.0
    length = length_over_radius * rho
    while z < length:
        rings.append((rho, z))
        z += h * rho
    cap = max(2, int(round((math.pi / 2) / h)))
    for k in range(cap):
        a = (k / cap) * math.pi / 2
        rings.append((rho * math.cos(a), length + rho * math.sin(a)))
    points, triangles = [], []
    for k, (r, z) in enumerate(rings):
        off = 0.5 * (k % 2)
        for j in range(n):
            a = 2 * math.pi * (j + off) / n
            points.append((r * math.cos(a), r * math.sin(a), z))
    for k in range(len(rings) - 1):
        a0, b0 = k * n, (k + 1) * n
        for j in range(n):
            j1 = (j + 1) % n
            if k % 2 == 0:
                triangles += [(a0 + j, b0 + j, a0 + j1), (a0 + j1, b0 + j, b0 + j1)]
            else:
                triangles += [(a0 + j, b0 + j, b0 + j1), (a0 + j, b0 + j1, a0 + j1)]
    tip = len(points)
    points.append((0.0, 0.0, length + rho))
    last = (len(rings) - 1) * n
    for j in range(n):
        triangles.append((last + j, tip, last + (j + 1) % n))
    return make_domain(points, triangles)


def run(length_over_radius):
    param = vtkAreaPreservingParam()
    param.SetInputData(finger(length_over_radius))
    errors = MessageRecorder(param)
    warnings = MessageRecorder(param, vtkCommand.WarningEvent)
    param.Update()
    out = param.GetOutput()
    fig = {k: field_value(out, k) for k in ("Converged", "RelativeError", "FlippedTriangles",
                                            "MeanAbsLogAreaRatio", "ConformalMaximumAbsLogAreaRatio")}
    print(f"L/rho {length_over_radius:4.1f}: {fig}", flush=True)
    return fig, errors, warnings


for length in (2, 6, 10, 14):
    fig, errors, warnings = run(length)
    check(not errors.messages and not warnings.messages,
          f"L/rho {length}: no error or warning ({errors.text()}{warnings.text()})")
    check(fig["Converged"] == 1 and fig["FlippedTriangles"] == 0
          and fig["MeanAbsLogAreaRatio"] <= 0.05,
          f"L/rho {length}: converged, no flip, mean |log area ratio| <= 0.05 ({fig})")
check(fig["ConformalMaximumAbsLogAreaRatio"] >= 28.0,
      "the longest finger that converges spans e^28 in conformal area density")

fig, errors, warnings = run(16)
text = warnings.text().lower()
check(not errors.messages and fig["Converged"] == 0 and "crowds part of the surface" in text
      and "area density spans" in text and "cut the surface open" in text,
      f"L/rho 16: a warning names the crowding and what to do ({warnings.text()})")

finish()
