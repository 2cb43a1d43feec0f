# Opens a crashlink result.xdmf with ParaView (pvpython --force-offscreen-rendering
# tools/check_xdmf_paraview.py out/DIR/result.xdmf) and prints time steps, sizes and arrays.
# Needs Debian's paraview + python3-paraview (about 440 MB), so it is a manual check, not CI.
import sys
from paraview.simple import *
r = Xdmf3ReaderS(FileName=[sys.argv[1]])
r.UpdatePipelineInformation()
times = r.TimestepValues
print("timesteps:", len(times) if hasattr(times, '__len__') else times)
r.UpdatePipeline(times[-1] if hasattr(times, '__len__') and len(times) else 0)
info = r.GetDataInformation()
print("points:", info.GetNumberOfPoints(), "cells:", info.GetNumberOfCells())
pd = r.PointData.keys(); cd = r.CellData.keys()
print("point arrays:", pd, "cell arrays:", cd)
for k in cd:
    print(k, r.CellData[k].GetRange())
