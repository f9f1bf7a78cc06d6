"""Renders a network run's solution.pvd with ParaView as a picture of the
star: left, the edges in the plane as tubes coloured by u (the vertex as a
sphere); right, the same network with u as height above the plane (the
profiles of every edge at once). Run with ParaView's python under a virtual
X server (this ParaView build has no offscreen rendering):

  xvfb-run -a pvpython --no-mpi contrib/network_paraview.py OUTPUT_DIR PNG [TIME]

OUTPUT_DIR is a run's Output/directory (absolute or relative); TIME picks
the snapshot (default: the last one).
"""
import os
import sys

from paraview.simple import (AssignViewToLayout, ColorBy, CreateLayout, ExtractSurface, GetColorTransferFunction,
                             Glyph, OpenDataFile, Render, SaveScreenshot, Show, Tube, UpdatePipeline, WarpByScalar)

from granular_dg.paraview import scalar_bar, threshold_edge, title, white_view

directory = os.path.abspath(sys.argv[1])
png = os.path.abspath(sys.argv[2])
reader = OpenDataFile(os.path.join(directory, 'solution.pvd'))
times = list(reader.TimestepValues)
time = float(sys.argv[3]) if len(sys.argv) > 3 else times[-1]
UpdatePipeline(time=time, proxy=reader)
u_range = reader.PointData['u'].GetRange()

layout = CreateLayout('network')


def make_view():
    view = white_view([900, 700])
    AssignViewToLayout(view=view, layout=layout, hint=0)
    view.ViewTime = time
    return view


lut = GetColorTransferFunction('u')
lut.ApplyPreset('Viridis (matplotlib)', True)
lut.RescaleTransferFunction(u_range[0], u_range[1])

# left: the network in the plane, tubes coloured by u, the vertex a sphere
plane = make_view()
lines = ExtractSurface(Input=threshold_edge(reader, 0.5, 1e9))  # Tube needs polydata
tubes = Tube(Input=lines, Radius=0.018, NumberofSides=16)
shown = Show(tubes, plane)
ColorBy(shown, ('POINTS', 'u'))
shown.LookupTable = lut
scalar_bar(lut, plane, 'u', Position=[0.88, 0.08], ScalarBarLength=0.4)
shown.SetScalarBarVisibility(plane, True)
ball = Glyph(Input=threshold_edge(reader, -0.5, 0.5), GlyphType='Sphere', ScaleArray=['POINTS', 'No scale array'],
             ScaleFactor=0.09)
ball_shown = Show(ball, plane)
ColorBy(ball_shown, ('POINTS', 'u'))
ball_shown.LookupTable = lut
title(plane, 't = %g' % time, 14, 'Upper Left Corner')
plane.CameraPosition = [0, 0, 6]
plane.CameraFocalPoint = [0, 0, 0]
plane.CameraViewUp = [0, 1, 0]
plane.ResetCamera()
plane.GetActiveCamera().Dolly(1.2)

# right: u as height above the plane
height = make_view()
AssignViewToLayout(view=height, layout=layout, hint=2)
warped = WarpByScalar(Input=lines, Scalars=['POINTS', 'u'], ScaleFactor=0.35)
warp_tubes = Tube(Input=warped, Radius=0.012, NumberofSides=12)
warp_shown = Show(warp_tubes, height)
ColorBy(warp_shown, ('POINTS', 'u'))
warp_shown.LookupTable = lut
base = Show(tubes, height)
base.DiffuseColor = base.AmbientColor = [0.75, 0.75, 0.75]
base.ColorArrayName = [None, "" ]
height.CameraPosition = [0.6, -5.0, 1.6]
height.CameraFocalPoint = [0, 0, 0.3]
height.CameraViewUp = [0, 0, 1]
height.ResetCamera()
height.GetActiveCamera().Dolly(1.5)
# one colour scale for all, fixed to the data range of this snapshot
lut.AutomaticRescaleRangeMode = 'Never'
lut.RescaleTransferFunction(u_range[0], u_range[1])
Render(plane)
Render(height)
SaveScreenshot(png, layout, ImageResolution=[1800, 700])
print('wrote ' + png)
