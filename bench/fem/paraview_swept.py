# ParaView view of a pressure-scene result on a swept mesh ([mesh] kind = swept), opened as a
# user would (fem.vtk.series): left, the reference mesh near the clamp cut at y = 0 with its
# edges, coloured by region (silicone, band, rings), to show the grid through the ring faces
# and the band; right, the deformed actuator at the last time, coloured by von Mises stress.
#   xvfb-run -a -s "-screen 0 1600x1000x24 +extension GLX" pvbatch bench/fem/paraview_swept.py RESULTS_DIR OUT.png
from paraview.simple import *
import sys
d = sys.argv[1].rstrip('/') + '/'
out = sys.argv[2]
src = OpenDataFile(d + 'fem.vtk.series')
times = list(src.TimestepValues)
print('time values [kPa]:', times)
layout = CreateLayout('swept')
v1 = CreateView('RenderView'); AssignViewToLayout(v1, layout, 0)
layout.SplitHorizontal(0, 0.5)
v2 = CreateView('RenderView'); AssignViewToLayout(v2, layout, 2)
layout.SetSize(1600, 1000)
# left: reference configuration (time 0): the half y < 0, its top 20 mm, seen on the cut
v1.ViewTime = times[0]
clip = Clip(Input=src); clip.ClipType = 'Plane'; clip.ClipType.Normal = [0, 1, 0]; clip.Crinkleclip = 1
box = Clip(Input=clip); box.ClipType = 'Plane'; box.ClipType.Origin = [0, 0, -0.02]; box.ClipType.Normal = [0, 0, 1]; box.Crinkleclip = 1; box.Invert = 0  # keep z > -20 mm
d1 = Show(box, v1); ColorBy(d1, ('CELLS', 'region')); d1.SetRepresentationType('Surface With Edges')
d1.LookupTable = GetColorTransferFunction('region'); d1.LookupTable.ApplyPreset('Rainbow Uniform', True)
v1.CameraPosition = [0, 0.06, -0.01]; v1.CameraFocalPoint = [0, 0, -0.01]  # looking at the cut y = 0; v1.CameraViewUp = [0, 0, 1]
v1.OrientationAxesVisibility = 1
v1.ResetCamera(); v1.CameraParallelProjection = 1
# right: deformed at the last time
v2.ViewTime = times[-1]
warp = WarpByVector(Input=src); warp.Vectors = ['POINTS', 'displacement']
d2 = Show(warp, v2); ColorBy(d2, ('CELLS', 'von_mises')); d2.SetScalarBarVisibility(v2, True)
v2.CameraPosition = [0, -0.3, -0.04]; v2.CameraFocalPoint = [0, 0, -0.04]; v2.CameraViewUp = [0, 0, 1]
v2.ResetCamera()
SaveScreenshot(out, layout, ImageResolution=[1600, 1000])
print('wrote', out)
