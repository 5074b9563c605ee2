"""Helpers shared by the example scripts: an X display for rendering, PNG output."""

import os
import shutil
import sys


def ensure_display(args):
    """Re-runs the calling script under xvfb-run when there is no X display to render into
    (Debian's VTK renders through X only: no EGL, no OSMesa)."""
    if args.no_picture or os.environ.get("DISPLAY") or os.environ.get("OTPARAM_UNDER_XVFB"):
        return
    xvfb = shutil.which("xvfb-run")
    if xvfb is None:
        sys.exit("No X display and no xvfb-run: install xvfb or pass --no-picture.")
    os.environ["OTPARAM_UNDER_XVFB"] = "1"
    os.execv(xvfb, [xvfb, "-a", "-s", "-screen 0 1600x1600x24", sys.executable] + sys.argv)


def save_png(window, path):
    """Writes what a vtkRenderWindow shows (back buffer) as a PNG."""
    from vtkmodules.vtkIOImage import vtkPNGWriter
    from vtkmodules.vtkRenderingCore import vtkWindowToImageFilter
    grab = vtkWindowToImageFilter()
    grab.SetInput(window)
    grab.ReadFrontBufferOff()
    grab.Update()
    writer = vtkPNGWriter()
    writer.SetFileName(path)
    writer.SetInputConnection(grab.GetOutputPort())
    writer.Write()
