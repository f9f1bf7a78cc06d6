"""Opens a granular_dg solution.pvd or solution.xdmf (absolute path) with
ParaView's own reader, as the GUI does, and prints what a user would see: the number of
time steps, their times, the point-array names and, per step, whether any
value is NaN/Inf and how many points it has. With --pieces after the path
it also prints, per step, how many <Piece> elements the step's VTU files
hold (summed over the files of a .pvtu). Run by run_test.py under
`pvpython --no-mpi`; the output is compared with a hand-written file.
Reader errors are only logged by ParaView, so the data is checked, not
exceptions."""
import os
import re
import sys

import numpy
from paraview import servermanager
from paraview.simple import OpenDataFile
from vtkmodules.util.numpy_support import vtk_to_numpy

path = sys.argv[1]
count_pieces = '--pieces' in sys.argv[2:]


def vtu_pieces(pvd):
    """per step of a .pvd, the <Piece> elements of its .vtu or .pvtu files"""
    folder = os.path.dirname(pvd)
    out = []
    for name in re.findall(r'file="([^"]+)"', open(pvd).read()):
        files = [name]
        if name.endswith('.pvtu'):
            files = re.findall(r'<Piece Source="([^"]+)"',
                               open(os.path.join(folder, name)).read())
        out.append(sum(open(os.path.join(folder, f), 'rb').read().count(b'<Piece ')
                       for f in files))
    return out


reader = OpenDataFile(path)
if reader is None:
    sys.exit('cannot open ' + path)
times = list(reader.TimestepValues) if reader.TimestepValues else []
print('time_steps %d' % len(times))
print('times ' + ' '.join('%g' % t for t in times))
names = None
pieces = vtu_pieces(path) if count_pieces else []
for step, t in enumerate(times):
    # the proxy's own UpdatePipeline(t): paraview.simple's UpdatePipeline(time=0)
    # takes 0 for "no time" and returns whatever step the reader holds
    reader.UpdatePipeline(t)
    data = servermanager.Fetch(reader)
    # a .pvd gives a multiblock or a single data set depending on version
    if data.IsA('vtkMultiBlockDataSet'):
        data = data.GetBlock(0)
    pd = data.GetPointData()
    step_names = sorted(pd.GetArrayName(i) for i in range(pd.GetNumberOfArrays()))
    if names is None:
        names = step_names
        print('arrays ' + ' '.join(names))
    elif names != step_names:
        print('arrays differ at t = %g: %s' % (t, step_names))
    bad = sum(int(numpy.count_nonzero(~numpy.isfinite(vtk_to_numpy(pd.GetArray(i)))))
              for i in range(pd.GetNumberOfArrays()))
    print('t %g points %d non_finite_values %d' % (t, data.GetNumberOfPoints(), bad)
          + (' vtu_pieces %d' % pieces[step] if count_pieces else ''))
