"""The paper's figure layout in ParaView, from one script: the surface textured with circles
through the area-preserving coordinates, the conformal disk coloured by its area distortion,
the transport's power diagram, and the Brenier potential in 3D, side by side in one layout,
plus the distortion histograms in a bar chart. Saves the layout as a PNG.

    pvpython Examples/paraview_figure_layout.py OTParam.so SURFACE.obj [OUTPUT.png]
    paraview --script=Examples/paraview_figure_layout.py    (from the repository's root;
        arguments from the environment: OTPARAM_PLUGIN, OTPARAM_SURFACE, OTPARAM_OUTPUT)

SURFACE is a disk-like triangle surface ParaView reads (.obj, .vtp, .ply, .stl, ...), e.g.
../shared/data/meshes/face_choi_bff_17k.obj. In the GUI the views stay open to explore.
"""

import os
import sys

from paraview.simple import *  # noqa: F401,F403  (LoadPlugin adds the OTParam functions here)

if len(sys.argv) >= 3:
    plugin, surface_file = sys.argv[1], sys.argv[2]
    output = sys.argv[3] if len(sys.argv) >= 4 else "paper_layout.png"
else:
    plugin, surface_file = os.environ["OTPARAM_PLUGIN"], os.environ["OTPARAM_SURFACE"]
    output = os.environ.get("OTPARAM_OUTPUT", "paper_layout.png")
LoadPlugin(plugin, ns=globals())


def circle_texture(path):
    """Writes the examples' circle image (otparam_example_utils.circle_image) as a PNG."""
    # paraview --script may not set __file__: then run it from the repository's root.
    here = (os.path.dirname(os.path.abspath(__file__)) if "__file__" in globals()
            else os.path.join(os.getcwd(), "Examples"))
    sys.path.insert(0, here)
    from otparam_example_utils import circle_image
    from vtkmodules.vtkIOImage import vtkPNGWriter
    writer = vtkPNGWriter()
    writer.SetFileName(path)
    writer.SetInputData(circle_image(512))
    writer.Write()


surface = Triangulate(Input=OpenDataFile(surface_file))
param = AreaPreservingParameterization(Input=surface)
conformal = ConformalDiskMap(Input=surface)
sampler = AdaptiveDensitySampler(Input=conformal)
sampler.Density = ["CELLS", "AreaDensity"]
sampler.NumberOfSamples = 5000
transport = SemiDiscreteOTSolver(Diracs=sampler)

texture_file = os.path.join(os.path.dirname(os.path.abspath(output)), "circles_texture.png")
circle_texture(texture_file)
# One layout, four views side by side (the GUI's initial view and layout are replaced).
for old_view in GetViews():
    Delete(old_view)
layout = CreateLayout("OTParam")
layout.SplitHorizontal(0, 0.5)
layout.SplitHorizontal(1, 0.5)
layout.SplitHorizontal(2, 0.5)
cells = iter([3, 4, 5, 6])  # the four leaves, left to right


def new_view():
    view = CreateView("RenderView")
    AssignViewToLayout(view=view, layout=layout, hint=next(cells))
    view.OrientationAxesVisibility = 0
    view.Background = [1.0, 1.0, 1.0]
    try:
        view.UseColorPaletteForBackground = 0  # ParaView >= 5.10: else the palette wins
    except AttributeError:
        pass
    return view


# 1. The surface with circles through the area-preserving coordinates.
view = new_view()
display = Show(param, view)  # its texture coordinates: the area-preserving (u, v)
display.Texture = CreateTexture(texture_file)
display.RepeatTextures = 1
display.ColorArrayName = [None, ""]
view.ResetCamera()
# 2. The conformal disk, coloured by the area distortion (log scale).
view = new_view()
display = Show(conformal, view)
ColorBy(display, ("CELLS", "AreaDensity"))
lut = GetColorTransferFunction("AreaDensity")
lut.UseLogScale = 1
display.RescaleTransferFunctionToDataRange(True)
view.InteractionMode = "2D"
view.ResetCamera()
# 3. The transport's power diagram over the uniform disk.
view = new_view()
display = Show(OutputPort(transport, 1), view)
ColorBy(display, ("CELLS", "DiracId"))
display.RescaleTransferFunctionToDataRange(True)
view.InteractionMode = "2D"
view.ResetCamera()
# 4. The Brenier potential in 3D.
view = new_view()
height = Elevation(Input=OutputPort(transport, 2))  # colour by u_h
height.LowPoint = [0.0, 0.0, -1.0]
height.HighPoint = [0.0, 0.0, 1.0]
display = Show(height, view)
ColorBy(display, ("POINTS", "Elevation"))
display.RescaleTransferFunctionToDataRange(True)
view.ResetCamera()
view.CameraPosition = [0.0, -4.0, 2.5]
view.CameraFocalPoint = [0.0, 0.0, 0.0]
view.CameraViewUp = [0.0, 0.0, 1.0]
view.ResetCamera()

layout.SetSize(1600, 400)
SaveScreenshot(output, layout, ImageResolution=[1600, 400])
print("wrote", output, flush=True)

# The histograms in a bar chart (the paper's Fig. 5), saved beside the layout.
chart = CreateView("XYBarChartView")
bars = Show(OutputPort(param, 2), chart)
bars.UseIndexForXAxis = 0
bars.XArrayName = "AreaPreservingLogAreaRatioBinCenter"
bars.SeriesVisibility = ["AreaPreservingLogAreaRatio"]
histogram_png = os.path.splitext(output)[0] + "_histogram.png"
SaveScreenshot(histogram_png, chart, ImageResolution=[800, 400])
print("wrote", histogram_png, flush=True)
