# ParaView view of a FEM-DEM result (last VTK pair): silicone by von Mises stress, grains by force.
#   xvfb-run -a pvbatch bench/dem/paraview_view.py RESULTS_DIR   (needs python3-paraview, xvfb)
from paraview.simple import *
import sys
d = sys.argv[1].rstrip('/') + '/'  # a results folder of cases/granular_bending_dem.ini
fem = LegacyVTKReader(FileNames=[d + 'fem_0001.vtk'])
gr = LegacyVTKReader(FileNames=[d + 'grains_0001.vtk'])
v = GetActiveViewOrCreate('RenderView')
v.ViewSize = [700, 1100]
fd = Show(fem, v)
ColorBy(fd, ('CELLS', 'von_mises'))
fd.Opacity = 0.35
g = Glyph(Input=gr, GlyphType='Sphere')
g.ScaleArray = ['POINTS', 'radius']
g.ScaleFactor = 2.0
g.GlyphMode = 'All Points'
gd = Show(g, v)
ColorBy(gd, ('POINTS', 'force', 'Magnitude'))
v.CameraPosition = [0.25, -0.05, -0.02]
v.CameraFocalPoint = [0, 0, -0.02]
v.CameraViewUp = [0, 0, 1]
v.ResetCamera()
SaveScreenshot(d + 'paraview.png', v, ImageResolution=[700, 1100])
print('ok')
