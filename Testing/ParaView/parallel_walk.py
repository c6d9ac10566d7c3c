"""pvbatch script of ParaView.ParallelWalk (TestParallelWalk.py runs it serially and under
`mpiexec -n 2 pvbatch --symmetric`): the mixed box solved through the plug-in's proxies (on two
ranks the cover's rows, its refinement and the direct light are built on both), its Illumination
Field shown with the "View-Dependent Radiance" representation, and a walk of five cameras
rendered by ParaView's render view (on two ranks: each rank renders its piece and ParaView
composites them; rank 0 holds the whole solution). Each frame is saved as OUT/frame_K.png by
rank 0.

usage: parallel_walk.py PLUGIN DATA OUT"""
import os
import sys

import paraview.simple as simple
from vtkmodules.vtkParallelCore import vtkMultiProcessController

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from mixed_box_views import CAMERAS, HEIGHT, WIDTH, black_view, look, mixed_box_field  # noqa: E402

plugin, data, out = sys.argv[1:4]
controller = vtkMultiProcessController.GetGlobalController()
rank = controller.GetLocalProcessId() if controller else 0
ranks = controller.GetNumberOfProcesses() if controller else 1

subdivision, propagation, field = mixed_box_field(plugin, data)
view = black_view()
display = simple.Show(field, view)
display.SetRepresentationType("View-Dependent Radiance")
# A walk: from the first camera to the second and on, the eye moving, the focus fixed between.
(eye0, focus0), (eye1, focus1) = CAMERAS
for k in range(5):
    t = k / 4.0
    eye = [a + t * (b - a) for a, b in zip(eye0, eye1)]
    focus = [a + t * (b - a) for a, b in zip(focus0, focus1)]
    look(view, (eye, focus))
    simple.Render(view)
    path = os.path.join(out, f"frame_{k}.png" if rank == 0 else f"frame_{k}_rank{rank}.png")
    simple.SaveScreenshot(path, view, ImageResolution=[WIDTH, HEIGHT])
print(f"rank {rank} of {ranks}: pipeline completed")
