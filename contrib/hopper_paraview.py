"""Render the hopper scene's marched field (hopper-field.pvd) with ParaView:
the hopper in physical coordinates (x = r sin theta, z = r cos theta; above
the arc Gamma_0 the upper hopper's radial field, below it the marched lower
hopper), coloured by an array, with contour lines of the Sokolovskii angle.

  xvfb-run -a pvpython --no-mpi contrib/hopper_paraview.py \
      $PWD/output/hopper_cone_30_25/hopper-field.pvd doc/figures/hopper_paraview_cone_30_25.png [ARRAY [TITLE]]

ARRAY defaults to T_rr_over_r (Pa/m). Paths of the .pvd must be absolute.
"""
import sys

from paraview.simple import (ColorBy, Contour, GetColorTransferFunction, OpenDataFile, ResetCamera,
                             SaveScreenshot, Show)

from granular_dg.paraview import scalar_bar, title, white_view

pvd, png = sys.argv[1], sys.argv[2]
array = sys.argv[3] if len(sys.argv) > 3 else 'T_rr_over_r'
reader = OpenDataFile(pvd)
view = white_view([1100, 1100])
display = Show(reader, view)
ColorBy(display, ('POINTS', array))
display.RescaleTransferFunctionToDataRange(True, False)
lut = GetColorTransferFunction(array)
lut.ApplyPreset('Viridis (matplotlib)', True)
display.SetScalarBarVisibility(view, True)
scalar_bar(lut, view, array.replace('_over_r', '/r') + (' (Pa/m)' if 'over_r' in array else ''),
           TitleFontSize=18, LabelFontSize=16, ScalarBarLength=0.4, Position=[0.85, 0.1])
contour = Contour(Input=reader)
contour.ContourBy = ['POINTS', 'psi_deg']
contour.Isosurfaces = [-25, -20, -15, -10, -5, 0, 5, 10, 15, 20, 25]
lines = Show(contour, view)
ColorBy(lines, None)
lines.AmbientColor = lines.DiffuseColor = [1, 1, 1]
lines.LineWidth = 1.5
title(view, sys.argv[4] if len(sys.argv) > 4 else 'hopper stress field; white: psi contours every 5 deg', 20)
view.InteractionMode = '2D'
ResetCamera(view)
view.CameraParallelProjection = 1
SaveScreenshot(png, view, ImageResolution=[1100, 1100])
print('wrote ' + png)
