"""pvbatch: the solution's view-dependent radiance in ParaView's render view (issue 18, part b,
partial: the evaluation is called from the script, not yet by a representation on every
camera move). The mixed box's Illumination Field is shown with DisplayRGB (Map Scalars off, no
lighting); vtkViewDependentRadiance rewrites the displayed data's DisplayRGB in place for the
camera's eye (no pipeline execution) and the view is rendered again. Two camera positions, each
seeing the white wall (diffuse), the mirror wall and the glossy cube:
- on the diffuse walls the screenshot is the Illumination Field's, byte for byte;
- on the mirror it is not (the Illumination Field shows the mirror's zero diffuse part, the view
  its reflection of the room toward the eye, paper §5.3.1), and it differs between the cameras.
Regions are the pixels of each surface in a view of the field coloured by SurfaceId, shrunk
by 2 pixels (an edge pixel may show either surface)."""
import os
import sys

from paraview.simple import Render

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from mixed_box_views import (CAMERAS, Screenshots, check_views, evaluator_of,  # noqa: E402
                             look, mixed_box_field)

plugin, data = sys.argv[1:3]
subdivision, propagation, field = mixed_box_field(plugin, data)

failures = []
screenshots = Screenshots()
view, display, masks, field_shots = screenshots.field_views(field)

# The displayed data (the representation's copy of the field), rewritten for each eye.
evaluator, displayed = evaluator_of(subdivision, propagation, display, failures)
view_shots = []
for k, camera in enumerate(CAMERAS):
    look(view, camera)
    if not evaluator.Update(displayed, *camera[0], 0.0):
        failures.append(f"camera {k}: the view-dependent evaluation failed")
    Render(view)
    view_shots.append(screenshots.shot(f"view_{k}", view))
    print(f"camera {k}: evaluation {1000 * evaluator.GetLastUpdateSeconds():.0f} ms for "
          f"{displayed.GetNumberOfPoints()} vertices")

check_views(view_shots, field_shots, masks, failures, white_tolerance=0)

screenshots.close()
for failure in failures:
    print("FAILED:", failure)
sys.exit(1 if failures else 0)
