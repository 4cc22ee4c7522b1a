# Render one .vti snapshot of `geomint maxwell run` with ParaView (pvbatch): Ez (component 2 of
# the cell vector "E") in the "Cool to Warm" map, the outlines of the cells with epsilon > 1.5,
# a title. Used by scripts/maxwell-figures:
#   xvfb-run -a pvbatch scripts/render-snapshot.py FILE.vti OUT.png RANGE [TITLE]
import sys
from paraview.simple import *  # noqa: F401,F403 (ParaView's own API)
src = XMLImageDataReader(FileName=[sys.argv[1]])
src.CellArrayStatus = ['E', 'H', 'epsilon', 'mu', 'sigma']
view = CreateView('RenderView')
view.ViewSize = [1000, 760]
view.OrientationAxesVisibility = 0
view.Background = [1, 1, 1]
try:
    view.UseColorPaletteForBackground = 0
except Exception:
    pass
disp = Show(src, view)
disp.Representation = 'Surface'
ColorBy(disp, ('CELLS', 'E', 'Z'))
lut = GetColorTransferFunction('E')
lut.ApplyPreset('Cool to Warm', True)
lut.VectorMode = 'Component'
lut.VectorComponent = 2
lut.RescaleTransferFunction(-float(sys.argv[3]), float(sys.argv[3]))
bar = GetScalarBar(lut, view)
bar.Title = 'Ez'
bar.ComponentTitle = ''
bar.TitleColor = [0, 0, 0]
bar.LabelColor = [0, 0, 0]
disp.SetScalarBarVisibility(view, True)
thr = Threshold(Input=src, Scalars=['CELLS', 'epsilon'])
try:
    thr.LowerThreshold = 1.5
    thr.UpperThreshold = 1e9
    thr.ThresholdMethod = 'Between'
except Exception:
    thr.ThresholdRange = [1.5, 1e9]
edges = FeatureEdges(Input=ExtractSurface(Input=thr))
edges.BoundaryEdges = 1
edges.FeatureEdges = 0
edges.NonManifoldEdges = 0
edges.ManifoldEdges = 0
ed = Show(edges, view)
ed.ColorArrayName = ['POINTS', '']
ed.AmbientColor = [0, 0, 0]
ed.DiffuseColor = [0, 0, 0]
ed.LineWidth = 2.0
text = Text(Text=sys.argv[4] if len(sys.argv) > 4 else '')
td = Show(text, view)
td.Color = [0, 0, 0]
td.FontSize = 14
td.WindowLocation = 'Upper Center'
view.CameraPosition = [2, 1.5, 10]
view.CameraFocalPoint = [2, 1.5, 0]
view.CameraViewUp = [0, 1, 0]
view.CameraParallelProjection = 1
view.CameraParallelScale = 1.6
Render(view)
SaveScreenshot(sys.argv[2], view, ImageResolution=[1000, 760])
