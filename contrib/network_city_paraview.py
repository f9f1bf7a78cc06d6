"""Renders the city-grid network run (prm/network_city_grid.prm) with ParaView
as a row of snapshots of the grid seen from above: one panel per time, the
roads as tubes coloured by the traffic density u and the junctions as small
spheres coloured by their own u, all panels on ONE colour scale (0 to the
largest u over the chosen times), the colour bar ("density u") in a narrow
panel at the right. Run with ParaView's python under a virtual X server (this
ParaView build has no offscreen rendering):

  xvfb-run -a pvpython --no-mpi contrib/network_city_paraview.py OUTPUT_DIR PNG [TIMES]

OUTPUT_DIR is the run's Output/directory (absolute or relative), PNG the
picture to write, TIMES a comma list of snapshot times (default 2,3,4,5; each
is snapped to the nearest time in solution.pvd). For doc/network.md:

  build/granular_dg prm/network_city_grid.prm --set Output/directory=/tmp/city_pv
  xvfb-run -a pvpython --no-mpi contrib/network_city_paraview.py /tmp/city_pv \\
      doc/figures/network_city_grid.png
"""
import os
import sys

from paraview.simple import (AssignViewToLayout, ColorBy, CreateLayout, ExtractSurface, GetColorTransferFunction,
                             Glyph, OpenDataFile, Render, SaveScreenshot, Show, Tube)

from granular_dg.paraview import scalar_bar, threshold_edge, title, white_view

directory = os.path.abspath(sys.argv[1])
png = os.path.abspath(sys.argv[2])
wanted = [float(s) for s in sys.argv[3].split(',')] if len(sys.argv) > 3 else [2, 3, 4, 5]

reader = OpenDataFile(os.path.join(directory, 'solution.pvd'))
available = list(reader.TimestepValues)
times = [min(available, key=lambda a: abs(a - t)) for t in wanted]

# the shared colour range: 0 to the max of u over the chosen times. Note
# UpdatePipeline(time=0) takes 0 as "no time" and gives the last step, so pass
# the time positionally to the proxy's own UpdatePipeline.
u_max = 0.0
for t in times:
    reader.UpdatePipeline(t)
    u_max = max(u_max, reader.PointData['u'].GetRange()[1])


roads = Tube(Input=ExtractSurface(Input=threshold_edge(reader, 0.5, 1e9)),  # Tube needs polydata
             Radius=0.04, NumberofSides=16)
junctions = Glyph(Input=threshold_edge(reader, -0.5, 0.5), GlyphType='Sphere',
                  ScaleArray=['POINTS', 'No scale array'], ScaleFactor=0.16)

lut = GetColorTransferFunction('u')
lut.ApplyPreset('Turbo', True)
lut.AutomaticRescaleRangeMode = 'Never'
lut.RescaleTransferFunction(0.0, u_max)

panel_size = [420, 470]
bar_width = 120
layout = CreateLayout('city grid')
try:
    layout.SeparatorWidth = 0
except AttributeError:
    pass


# a row of cells: split the remaining right part of the layout each time
views = []
cell = 0
remaining = len(times) * panel_size[0] + bar_width
for time in times:
    cell_left = layout.SplitHorizontal(cell, float(panel_size[0]) / remaining)
    remaining -= panel_size[0]
    view = white_view([panel_size[0], panel_size[1]])
    AssignViewToLayout(view=view, layout=layout, hint=cell_left)
    cell = cell_left + 1
    view.ViewTime = time
    for source in (roads, junctions):
        shown = Show(source, view)
        ColorBy(shown, ('POINTS', 'u'))
        shown.LookupTable = lut
        shown.SetScalarBarVisibility(view, False)
    title(view, 't = %g' % time, 22)
    Render(view)  # the first render resets the camera: set ours after it
    # top view of the square [-1, 6]^2, a margin for the tubes and the title
    view.CameraPosition = [2.5, 2.5, 20]
    view.CameraFocalPoint = [2.5, 2.75, 0]
    view.CameraViewUp = [0, 1, 0]
    view.CameraParallelProjection = 1
    view.CameraParallelScale = 3.85 * panel_size[1] / panel_size[0]
    views.append(view)

# the colour bar alone in a narrow panel on the right
bar_view = white_view([bar_width, panel_size[1]])
AssignViewToLayout(view=bar_view, layout=layout, hint=cell)
scalar_bar(lut, bar_view, 'density u', TitleFontSize=18, LabelFontSize=16, Position=[0.12, 0.12],
           ScalarBarLength=0.72, RangeLabelFormat='%.2f', ScalarBarThickness=20, Visibility=1)
views.append(bar_view)

lut.RescaleTransferFunction(0.0, u_max)  # showing can rescale; fix it again
for view in views:
    Render(view)
SaveScreenshot(png, layout,
               ImageResolution=[len(times) * panel_size[0] + bar_width, panel_size[1]])
print('wrote %s (times %s, u in [0, %.3g])' % (png, ', '.join('%g' % t for t in times), u_max))
