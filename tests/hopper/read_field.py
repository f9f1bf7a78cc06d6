"""Opens the hopper scene's hopper-field.pvd (absolute path) with ParaView's
reader and prints what a user sees: the point arrays, the number of points
and cells, the bounding box of the hopper in physical coordinates (x = r sin
theta, z = r cos theta, apex of the lower hopper at the origin), the range
of T_rr/r and of the region marker, and the count of non-finite values.
Run under `pvpython --no-mpi` by run_test.py."""
import math
import sys

from paraview import servermanager
from paraview.simple import OpenDataFile, UpdatePipeline

path = sys.argv[1]
reader = OpenDataFile(path)
if reader is None:
    sys.exit('cannot open ' + path)
UpdatePipeline(proxy=reader)
data = servermanager.Fetch(reader)
if data.IsA('vtkMultiBlockDataSet'):
    data = data.GetBlock(0)
pd = data.GetPointData()
print('arrays ' + ' '.join(sorted(pd.GetArrayName(i) for i in range(pd.GetNumberOfArrays()))))
print('points %d cells %d' % (data.GetNumberOfPoints(), data.GetNumberOfCells()))
b = data.GetBounds()
print('x %.6f %.6f z %.6f %.6f' % (b[0], b[1], b[2], b[3]))
for name in ('T_rr_over_r', 'region'):
    r = pd.GetArray(name).GetRange()
    print('%s %.6g %.6g' % (name, r[0], r[1]))
bad = 0
for i in range(pd.GetNumberOfArrays()):
    a = pd.GetArray(i)
    for j in range(a.GetNumberOfTuples()):
        for k in range(a.GetNumberOfComponents()):
            if not math.isfinite(a.GetComponent(j, k)):
                bad += 1
print('non_finite_values %d' % bad)
