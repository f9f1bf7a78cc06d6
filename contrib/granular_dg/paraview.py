"""The ParaView set-up of the pvpython scripts (run as
`xvfb-run -a pvpython --no-mpi contrib/SCRIPT.py ...`): white views, black
colour bars and titles, and the network's edges and vertices."""
from paraview.simple import CreateRenderView, GetScalarBar, Show, Text, Threshold


def white_view(size):
    """A white render view of the given size, without the orientation axes."""
    view = CreateRenderView()
    view.ViewSize = size
    view.OrientationAxesVisibility = 0
    view.Background = [1, 1, 1]
    try:
        view.UseColorPaletteForBackground = 0
    except AttributeError:
        pass
    return view


def scalar_bar(lut, view, title, **settings):
    """The colour bar of lut in view: black text, the title, placed by the
    settings (Position, ScalarBarLength, ...)."""
    bar = GetScalarBar(lut, view)
    bar.Title, bar.ComponentTitle = title, ""
    bar.TitleColor = bar.LabelColor = [0, 0, 0]
    bar.WindowLocation = "Any Location"
    for key, value in settings.items():
        setattr(bar, key, value)
    return bar


def title(view, text, size, location="Upper Center"):
    """Black text in the view."""
    shown = Show(Text(Text=text), view)
    shown.Color = [0, 0, 0]
    shown.FontSize = size
    shown.WindowLocation = location
    return shown


def threshold_edge(reader, lower, upper):
    """Cells whose point field `edge` lies in [lower, upper]: the edges are
    numbered 1, 2, ..., the vertices 0."""
    selected = Threshold(Input=reader, Scalars=["POINTS", "edge"])
    try:
        selected.LowerThreshold, selected.UpperThreshold = lower, upper
    except AttributeError:  # older ParaView
        selected.ThresholdRange = [lower, upper]
    return selected
