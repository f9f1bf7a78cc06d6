"""ParaView pictures of runs (this ParaView build renders under a virtual X server only):

  xvfb-run -a pvpython --no-mpi contrib/paraview_figures.py hopper FIELD.pvd PNG [ARRAY [TITLE]]
  xvfb-run -a pvpython --no-mpi contrib/paraview_figures.py layered SOLUTION.pvd PNG TIME [ARRAY]
  xvfb-run -a pvpython --no-mpi contrib/paraview_figures.py network OUTPUT_DIR PNG [TIME]
  xvfb-run -a pvpython --no-mpi contrib/paraview_figures.py city OUTPUT_DIR PNG [TIMES]

hopper: the marched field (hopper-field.pvd) in physical coordinates coloured by ARRAY
(default T_rr_over_r), white contours of the Sokolovskii angle every 5 deg; layered: case
(c) of the layered strip, ARRAY (default stress) at TIME; network: left the edges as tubes
coloured by u (the vertex a sphere), right u as height above the plane, at TIME (default
the last); city: the city grid (prm/network_city_grid.prm) from above at TIMES (default
2,3,4,5, each the nearest output), one colour scale, its bar in a panel at the right.
"""
import os
import sys

from paraview.simple import (AssignViewToLayout, ColorBy, Contour, CreateLayout, CreateRenderView, ExtractSurface,
                             GetColorTransferFunction, GetScalarBar, Glyph, OpenDataFile, Render, ResetCamera,
                             SaveScreenshot, SetProperties, Show, Text, Threshold, Tube, UpdatePipeline, WarpByScalar)

# the titles of doc/figures/hopper_paraview_<case>.png, by the run's directory
HOPPER_TITLES = {'hopper_cone_30_25': 'cone 30 -> 25 deg, r from 1.5 r0 to 0.05 r0: T_rr/r, white: psi every 5 deg',
                 'hopper_wedge_30_35': 'wedge 30 -> 35 deg: T_rr/r, white: psi every 5 deg'}


def white_view(size, layout=None, hint=0, time=None):
    """A white render view of the given size without the orientation axes
    (in a cell of the layout if given; at the time if given)."""
    view = CreateRenderView(ViewSize=size, OrientationAxesVisibility=0, Background=[1, 1, 1],
                            UseColorPaletteForBackground=0)
    if layout is not None:
        AssignViewToLayout(view=view, layout=layout, hint=hint)
    if time is not None:
        view.ViewTime = time
    return view


def coloured(source, view, array, rescale=None):
    """source shown in view coloured by the point array's colour map (for u
    the fixed one of u_scale; with rescale: the Viridis map rescaled to the
    data by RescaleTransferFunctionToDataRange(*rescale), and its bar)."""
    shown = Show(source, view)
    ColorBy(shown, ('POINTS', array))
    if rescale:
        shown.RescaleTransferFunctionToDataRange(*rescale)
        GetColorTransferFunction(array).ApplyPreset('Viridis (matplotlib)', True)
        shown.SetScalarBarVisibility(view, True)
    return shown


def scalar_bar(lut, view, title, **settings):
    """The colour bar of lut in view: black text, the title, placed by the
    settings (Position, ScalarBarLength, ...)."""
    SetProperties(GetScalarBar(lut, view), Title=title, ComponentTitle='', TitleColor=[0, 0, 0], LabelColor=[0, 0, 0],
                  WindowLocation='Any Location', **settings)


def title(view, text, size, location='Upper Center'):
    """Black text in the view."""
    Show(Text(Text=text), view, Color=[0, 0, 0], FontSize=size, WindowLocation=location)


def flat(view, scale=None):
    """A 2D camera on the data (parallel projection, the scale if given)."""
    view.InteractionMode = '2D'
    ResetCamera(view)
    view.CameraParallelProjection = 1
    if scale:
        view.CameraParallelScale = scale


def camera(view, position, focus, up, dolly):
    view.CameraPosition, view.CameraFocalPoint, view.CameraViewUp = position, focus, up
    view.ResetCamera()
    view.GetActiveCamera().Dolly(dolly)


def save(png, what, size, note=''):
    SaveScreenshot(png, what, ImageResolution=size)
    print('wrote ' + png + note)


def edges_and_vertices(reader, size):
    """The network's edges as polydata (Tube needs it) and its vertices as
    spheres of the size: the point field `edge` numbers the edges 1, 2, ...,
    the vertices 0."""
    def cells(lower, upper):
        return Threshold(Input=reader, Scalars=['POINTS', 'edge'], LowerThreshold=lower, UpperThreshold=upper)
    return ExtractSurface(Input=cells(0.5, 1e9)), Glyph(Input=cells(-0.5, 0.5), GlyphType='Sphere',
                                                         ScaleArray=['POINTS', 'No scale array'], ScaleFactor=size)


def u_scale(preset, lo, hi):
    """The colour map of u, fixed to [lo, hi] (one scale for every view)."""
    lut = GetColorTransferFunction('u')
    lut.ApplyPreset(preset, True)
    lut.AutomaticRescaleRangeMode = 'Never'
    lut.RescaleTransferFunction(lo, hi)
    return lut


def hopper(pvd, png, array='T_rr_over_r', text=None):
    reader = OpenDataFile(pvd)
    view = white_view([1100, 1100])
    coloured(reader, view, array, rescale=(True, False))
    scalar_bar(GetColorTransferFunction(array), view,
               array.replace('_over_r', '/r') + (' (Pa/m)' if 'over_r' in array else ''),
               TitleFontSize=18, LabelFontSize=16, ScalarBarLength=0.4, Position=[0.85, 0.1])
    Show(Contour(Input=reader, ContourBy=['POINTS', 'psi_deg'], Isosurfaces=list(range(-25, 30, 5))), view,
         ColorArrayName=[None, ''], AmbientColor=[1, 1, 1], DiffuseColor=[1, 1, 1], LineWidth=1.5)
    title(view, text or HOPPER_TITLES.get(os.path.basename(os.path.dirname(pvd)),
                                          'hopper stress field; white: psi contours every 5 deg'), 20)
    flat(view)
    save(png, view, [1100, 1100])


def layered(pvd, png, time, array='stress'):
    reader, time = OpenDataFile(pvd), float(time)
    times = list(reader.TimestepValues)
    if not any(abs(t - time) < 1e-9 * max(1, time) for t in times):
        sys.exit('paraview_figures: no output at t = %g in %s (has %s)' % (time, pvd, times))
    view = white_view([1800, 320], time=time)
    coloured(reader, view, array, rescale=(False, True))
    scalar_bar(GetColorTransferFunction(array), view, array, Orientation='Vertical', Position=[0.93, 0.08],
               ScalarBarLength=0.8)
    title(view, 'layered strip (c): %s at t = %g' % (array, time), 14, 'Upper Left Corner')
    flat(view, 7.5)
    save(png, view, [1800, 320])


def network(directory, png, time=None):
    reader = OpenDataFile(os.path.join(directory, 'solution.pvd'))
    time = float(time) if time else list(reader.TimestepValues)[-1]
    UpdatePipeline(time=time, proxy=reader)
    u_range = reader.PointData['u'].GetRange()
    layout = CreateLayout('network')
    lut = u_scale('Viridis (matplotlib)', *u_range)
    # left: the network in the plane, tubes coloured by u, the vertex a sphere
    plane = white_view([900, 700], layout, time=time)
    lines, vertices = edges_and_vertices(reader, 0.09)
    tubes = Tube(Input=lines, Radius=0.018, NumberofSides=16)
    coloured(tubes, plane, 'u')
    scalar_bar(lut, plane, 'u', Position=[0.88, 0.08], ScalarBarLength=0.4, Visibility=1)
    coloured(vertices, plane, 'u')
    title(plane, 't = %g' % time, 14, 'Upper Left Corner')
    # right: u as height above the plane, over the network in grey
    height = white_view([900, 700], layout, 2, time=time)
    warped = WarpByScalar(Input=lines, Scalars=['POINTS', 'u'], ScaleFactor=0.35)
    coloured(Tube(Input=warped, Radius=0.012, NumberofSides=12), height, 'u')
    Show(tubes, height, DiffuseColor=[0.75] * 3, AmbientColor=[0.75] * 3, ColorArrayName=[None, ''])
    lut.RescaleTransferFunction(*u_range)  # showing can rescale; fix it again
    Render(plane)  # the first render resets the camera: set ours after it
    Render(height)
    camera(plane, [0, 0, 6], [0, 0, 0], [0, 1, 0], 1.2)
    camera(height, [0.6, -5.0, 1.6], [0, 0, 0.3], [0, 0, 1], 1.3)
    save(png, layout, [1800, 700])


def city(directory, png, wanted='2,3,4,5'):
    reader = OpenDataFile(os.path.join(directory, 'solution.pvd'))
    times = [min(reader.TimestepValues, key=lambda a: abs(a - float(t))) for t in wanted.split(',')]
    # the shared colour range: 0 to the max of u over the times. UpdatePipeline(time=0)
    # takes 0 as "no time" and gives the last step: the time goes positionally to the proxy's own
    u_max = 0.0
    for t in times:
        reader.UpdatePipeline(t)
        u_max = max(u_max, reader.PointData['u'].GetRange()[1])
    lines, junctions = edges_and_vertices(reader, 0.16)
    roads = Tube(Input=lines, Radius=0.04, NumberofSides=16)
    lut = u_scale('Turbo', 0.0, u_max)
    (width, height), bar_width = (420, 470), 120
    layout = CreateLayout('city grid')
    layout.SeparatorWidth = 0
    cell, remaining = 0, len(times) * width + bar_width
    for time in times:  # a row of cells: split the remaining right part of the layout each time
        left = layout.SplitHorizontal(cell, float(width) / remaining)
        remaining -= width
        view = white_view([width, height], layout, left, time=time)
        cell = left + 1
        for source in (roads, junctions):
            coloured(source, view, 'u').SetScalarBarVisibility(view, False)
        title(view, 't = %g' % time, 22)
        Render(view)  # the first render resets the camera: set ours after it
        # top view of the square [-1, 6]^2, a margin for the tubes and the title
        SetProperties(view, CameraPosition=[2.5, 2.5, 20], CameraFocalPoint=[2.5, 2.75, 0], CameraViewUp=[0, 1, 0],
                      CameraParallelProjection=1, CameraParallelScale=3.85 * height / width)
    bar = white_view([bar_width, height], layout, cell)  # the colour bar alone
    scalar_bar(lut, bar, 'density u', TitleFontSize=18, LabelFontSize=16, Position=[0.12, 0.12],
               ScalarBarLength=0.72, RangeLabelFormat='%.2f', ScalarBarThickness=20, Visibility=1)
    lut.RescaleTransferFunction(0.0, u_max)  # showing can rescale; fix it again
    save(png, layout, [len(times) * width + bar_width, height],
         ' (times %s, u in [0, %.3g])' % (', '.join('%g' % t for t in times), u_max))


if __name__ == '__main__':
    figures = {'hopper': hopper, 'layered': layered, 'network': network, 'city': city}
    if len(sys.argv) < 4 or sys.argv[1] not in figures:
        sys.exit(__doc__)
    figures[sys.argv[1]](*map(os.path.abspath, sys.argv[2:4]), *sys.argv[4:])
