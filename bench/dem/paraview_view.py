# ParaView view of a FEM-DEM result, opened as a user would: the two VTK time series
# (fem.vtk.series, grains.vtk.series), whose time values are the piston displacement in mm.
# Prints the time values ParaView reads, then renders the last time: the silicone by von Mises
# stress (transparent), the grains by the magnitude of their `force` array: LIGGGHTS' total
# force on each grain (contacts + weight), i.e. its unbalanced force, near zero in a
# quasi-static bed (max 3e-3 N at 2.5 mm against a 39 N piston): not the force chains.
#   xvfb-run -a -s "-screen 0 1280x1024x24 +extension GLX" pvbatch bench/dem/paraview_view.py RESULTS_DIR [OUT.png]
#   (needs python3-paraview and xvfb)
from paraview.simple import *
import sys
d = sys.argv[1].rstrip('/') + '/'  # a results folder of cases/granular_bending_dem.ini
out = sys.argv[2] if len(sys.argv) > 2 else d + 'paraview.png'
fem = OpenDataFile(d + 'fem.vtk.series')
gr = OpenDataFile(d + 'grains.vtk.series')
tf, tg = list(fem.TimestepValues), list(gr.TimestepValues)
print('fem time values [mm]:', tf)
print('grains time values [mm]:', tg)
if tf != tg:
    sys.exit('the two series have different time values')
v = GetActiveViewOrCreate('RenderView')
v.ViewSize = [700, 1100]
v.ViewTime = tf[-1]
fd = Show(fem, v)
ColorBy(fd, ('CELLS', 'von_mises'))
fd.Opacity = 0.35
g = Glyph(Input=gr, GlyphType='Sphere')
g.ScaleArray = ['POINTS', 'radius']
g.ScaleFactor = 2.0
g.GlyphMode = 'All Points'
gd = Show(g, v)
ColorBy(gd, ('POINTS', 'force', 'Magnitude'))
gd.SetScalarBarVisibility(v, True)
fd.SetScalarBarVisibility(v, True)
info = gr.GetDataInformation()
print('grains at the last time:', info.GetNumberOfPoints(), 'points; arrays:',
      [gr.PointData.GetArray(i).GetName() for i in range(gr.PointData.GetNumberOfArrays())])
print('silicone cells:', fem.GetDataInformation().GetNumberOfCells(), 'cell arrays:',
      [fem.CellData.GetArray(i).GetName() for i in range(fem.CellData.GetNumberOfArrays())],
      'point arrays:',
      [fem.PointData.GetArray(i).GetName() for i in range(fem.PointData.GetNumberOfArrays())])
v.CameraPosition = [0.25, -0.05, -0.02]
v.CameraFocalPoint = [0, 0, -0.02]
v.CameraViewUp = [0, 0, 1]
v.ResetCamera()
SaveScreenshot(out, v, ImageResolution=[700, 1100])
print('wrote', out)
