"""What the network's ParaView scripts (network_paraview.py, the star;
network_city_paraview.py, the city grid) share: selecting the edges or the
vertices of a solution.pvd, and a white render view."""
from paraview.simple import CreateRenderView, Threshold


def threshold_edge(reader, lower, upper):
    """Cells whose point field `edge` lies in [lower, upper]: the edges are
    numbered 1, 2, ..., the vertices 0."""
    selected = Threshold(Input=reader, Scalars=['POINTS', 'edge'])
    try:
        selected.LowerThreshold, selected.UpperThreshold = lower, upper
    except AttributeError:  # older ParaView
        selected.ThresholdRange = [lower, upper]
    return selected


def white_view(size):
    """A render view of the given size, white, without the orientation axes."""
    view = CreateRenderView()
    view.ViewSize = size
    view.OrientationAxesVisibility = 0
    view.Background = [1, 1, 1]
    try:
        view.UseColorPaletteForBackground = 0
    except AttributeError:
        pass
    return view
