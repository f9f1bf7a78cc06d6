"""Render case (c) of the layered strip (solution.pvd of prm/layered_2d.prm)
with ParaView: the stress field at one output time, the strips visible
through the strain.

  xvfb-run -a pvpython --no-mpi contrib/layered_paraview.py \
      $PWD/output/layered_2d/solution.pvd doc/figures/layered_2d_t75.png 75 [ARRAY]

ARRAY defaults to stress. The path of the .pvd must be absolute.
"""
import sys

from paraview.simple import (ColorBy, GetAnimationScene, GetColorTransferFunction, OpenDataFile, ResetCamera,
                             SaveScreenshot, Show)

from granular_dg.paraview import scalar_bar, title, white_view

pvd, png, time = sys.argv[1], sys.argv[2], float(sys.argv[3])
array = sys.argv[4] if len(sys.argv) > 4 else 'stress'
reader = OpenDataFile(pvd)
times = list(reader.TimestepValues)
if not any(abs(t - time) < 1e-9 * max(1, time) for t in times):
    sys.exit('layered_paraview: no output at t = %g in %s (has %s)' % (time, pvd, times))
scene = GetAnimationScene()
scene.UpdateAnimationUsingDataTimeSteps()
scene.AnimationTime = time
view = white_view([1800, 320])
view.ViewTime = time
display = Show(reader, view)
ColorBy(display, ('POINTS', array))
display.RescaleTransferFunctionToDataRange(False, True)
lut = GetColorTransferFunction(array)
lut.ApplyPreset('Viridis (matplotlib)', True)
display.SetScalarBarVisibility(view, True)
scalar_bar(lut, view, array, Orientation='Vertical', Position=[0.93, 0.08], ScalarBarLength=0.8)
title(view, 'layered strip (c): %s at t = %g' % (array, time), 14, 'Upper Left Corner')
view.InteractionMode = '2D'
ResetCamera(view)
view.CameraParallelProjection = 1
view.CameraParallelScale = 7.5
SaveScreenshot(png, view, ImageResolution=[1800, 320])
print('wrote ' + png)
