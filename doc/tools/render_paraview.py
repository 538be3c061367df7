"""Renders a Tribos Exodus result in ParaView, warped by the displacement.

Usage: xvfb-run -a pvbatch doc/tools/render_paraview.py RESULT.exo OUT.png [scale]
(Debian: apt-get install paraview python3-paraview xvfb xauth). Colours by the magnitude of
the displacement and shows the subdomains' outline; a check that ParaView opens our files.
"""
import sys

from paraview.simple import (ColorBy, ExodusIIReader, GetActiveViewOrCreate, GetAnimationScene, SaveScreenshot,
                             Show, UpdatePipeline, WarpByVector)

path, out = sys.argv[1], sys.argv[2]
scale = float(sys.argv[3]) if len(sys.argv) > 3 else 200.0
reader = ExodusIIReader(FileName=[path])
# ParaView groups displ_x, displ_y, displ_z into the vector "displ_".
reader.PointVariables = reader.PointVariables.Available
reader.ApplyDisplacements = 0  # the warp below shows them, scaled
reader.ElementVariables = ["subdomain"]
scene = GetAnimationScene()
scene.UpdateAnimationUsingDataTimeSteps()
scene.AnimationTime = reader.TimestepValues[-1] if reader.TimestepValues else 0.0
UpdatePipeline(scene.AnimationTime, reader)
warp = WarpByVector(Input=reader, Vectors=["POINTS", "displ_"], ScaleFactor=scale)
view = GetActiveViewOrCreate("RenderView")
view.ViewSize = [1200, 800]
display = Show(warp, view)
display.SetRepresentationType("Surface With Edges")
ColorBy(display, ("POINTS", "displ_", "Magnitude"))
display.RescaleTransferFunctionToDataRange(True)
display.SetScalarBarVisibility(view, True)
view.CameraPosition = [55.0, -45.0, 40.0]
view.CameraFocalPoint = [10.0, 5.0, 10.0]
view.CameraViewUp = [0.0, 0.0, 1.0]
SaveScreenshot(out, view)
print(f"wrote {out}: {reader.PointData.keys()}")
