"""What the pvbatch tests of the view-dependent radiance share (ParaView.ViewDependentRadiance,
ParaView.ViewDependentRadianceRepresentation): the mixed box's Illumination Field through the
plug-in's proxies, two cameras that each see the white wall (diffuse), the mirror wall and the
glossy cube, black render views, screenshots as arrays, and the pixels of the white wall and the
mirror in each camera's view."""
import os
import shutil
import tempfile

import numpy as np
import paraview.simple as simple
from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.vtkIOImage import vtkPNGReader

WIDTH, HEIGHT = 320, 240
# The mixed box's surfaces in the scene's order: x_max the mirror, z_min white (diffuse).
MIRROR, WHITE = 1, 4
CAMERAS = [([0.3, 0.45, 0.9], [0.75, 0.5, 0.0]), ([0.5, 0.6, 0.95], [0.9, 0.4, 0.1])]


def mixed_box_field(plugin, data):
    """Loads the plug-in; (subdivision, propagation, field) of Data/scenes/mixed_box.scene at
    test settings (max_level 2, a 16 x 64 grid, field resolution 4)."""
    simple.LoadPlugin(plugin, remote=False)
    scene = simple.OpenDataFile(f"{data}/scenes/mixed_box.scene")
    subdivision = simple.IntervalSubdivision(Input=scene)
    subdivision.MaxLevel = 2
    subdivision.ThetaBins = 16
    subdivision.PhiBins = 64
    cover = simple.SphericalCover(Input=simple.OutputPort(subdivision, 0))
    cover.ThetaBins = 16
    cover.PhiBins = 64
    propagation = simple.LightPropagation(Input=simple.OutputPort(cover, 0))
    field = simple.IlluminationField(Input=simple.OutputPort(propagation, 0),
                                     Patches=simple.OutputPort(subdivision, 0))
    field.Resolution = 4
    return subdivision, propagation, field


def black_view():
    created = simple.CreateRenderView()
    created.ViewSize = [WIDTH, HEIGHT]
    created.OrientationAxesVisibility = 0
    created.UseColorPaletteForBackground = 0
    created.Background = [0, 0, 0]
    return created


def unlit(display):
    """Colours shown as they are: the bytes, no lighting."""
    display.MapScalars = 0
    display.Ambient = 1.0
    display.Diffuse = 0.0


def evaluator_of(subdivision, propagation, display, failures):
    """A vtkViewDependentRadiance with the solution, and the polydata `display` renders (its copy
    of the field, whose arrays are the field's own: rewriting them changes the field's output)."""
    from sphericalcover import vtkViewDependentRadiance
    evaluator = vtkViewDependentRadiance()
    if not evaluator.SetSolution(propagation.GetClientSideObject().GetOutputDataObject(0),
                                 subdivision.GetClientSideObject().GetOutputDataObject(0)):
        failures.append("the solution was refused")
    iterator = display.GetClientSideObject().GetRenderedDataObject(0).NewIterator()
    iterator.InitTraversal()
    return evaluator, iterator.GetCurrentDataObject()


def check_views(view_shots, field_shots, masks, failures, white_tolerance):
    """The checks of a view-dependent view against the field's, per camera: the white wall's
    pixels within `white_tolerance` of the field's; 90 % of the mirror's pixels differ from the
    field's (its zero diffuse part; the view shows its reflection of the room, paper §5.3.1);
    and the mirror's mean colour differs between the cameras."""
    for k in range(len(CAMERAS)):
        white = masks[k]["white"]
        difference = np.abs(view_shots[k] - field_shots[k]).max(axis=2)
        print(f"camera {k}, white wall: {white.sum()} pixels, largest difference from the field "
              f"{difference[white].max() if white.any() else '-'}")
        if white.sum() < 0.02 * WIDTH * HEIGHT:
            failures.append(f"camera {k}: the white wall is hardly in view; the test is wrong")
        elif difference[white].max() > white_tolerance:
            failures.append(f"camera {k}: {(difference[white] > white_tolerance).sum()} pixels of "
                            f"the white wall differ from the Illumination Field's by more than "
                            f"{white_tolerance}")
        mirror = masks[k]["mirror"]
        changed = (difference > 0) & mirror
        print(f"camera {k}, mirror: {mirror.sum()} pixels, {changed.sum()} differ from the field")
        if mirror.sum() < 0.02 * WIDTH * HEIGHT:
            failures.append(f"camera {k}: the mirror is hardly in view; the test is wrong")
        elif changed.sum() < 0.9 * mirror.sum():
            failures.append(f"camera {k}: only {changed.sum()} of {mirror.sum()} mirror pixels "
                            "show more than the field's diffuse part")
    means = [view_shots[k][masks[k]["mirror"]].mean(axis=0) for k in range(len(CAMERAS))]
    print(f"the mirror's mean colour: {means[0]} and {means[1]}")
    if not np.abs(means[0] - means[1]).max() > 2:
        failures.append(f"the mirror looks the same from both cameras ({means[0]}, {means[1]})")


def look(view, camera):
    view.CameraPosition, view.CameraFocalPoint = camera
    view.CameraViewUp = [0, 1, 0]
    view.CameraViewAngle = 60


class Screenshots:
    """Screenshots of views as (HEIGHT, WIDTH, 3) integer arrays, through a temporary folder."""

    def __init__(self):
        self.folder = tempfile.mkdtemp()

    def shot(self, name, view):
        path = os.path.join(self.folder, f"{name}.png")
        simple.SaveScreenshot(path, view, ImageResolution=[WIDTH, HEIGHT])
        reader = vtkPNGReader()
        reader.SetFileName(path)
        reader.Update()
        pixels = vtk_to_numpy(reader.GetOutput().GetPointData().GetScalars())
        return pixels.reshape(HEIGHT, WIDTH, -1)[:, :, :3].astype(int)

    def regions(self, field):
        """Per camera, the pixels of the white wall and of the mirror ({"white": mask, "mirror":
        mask}), 2 pixels in from their edges (an edge pixel may show either surface): the field
        in a view of its own, each vertex coloured (SurfaceId + 1) x 16 in red (a patch's
        vertices are its own, so every patch is one flat colour)."""
        view = black_view()
        ids = simple.Calculator(Input=field, ResultArrayName="SurfaceColour",
                                ResultArrayType="Float", Function="(SurfaceId+1)*16/255*iHat")
        display = simple.Show(ids, view)
        simple.ColorBy(display, ("POINTS", "SurfaceColour"))
        unlit(display)
        # paraview.simple resets the camera on a view's first render: render before placing it.
        simple.Render(view)
        masks = []
        for k, camera in enumerate(CAMERAS):
            look(view, camera)
            surface = np.rint(self.shot(f"surfaces_{k}", view)[:, :, 0] / 16.0).astype(int) - 1
            found = {}
            for name, index in [("white", WHITE), ("mirror", MIRROR)]:
                mask = surface == index
                for _ in range(2):
                    mask[1:-1, 1:-1] &= (mask[:-2, 1:-1] & mask[2:, 1:-1] & mask[1:-1, :-2]
                                         & mask[1:-1, 2:])
                    mask[[0, -1], :] = False
                    mask[:, [0, -1]] = False
                found[name] = mask
            masks.append(found)
        return masks

    def field_views(self, field):
        """The Illumination Field as the Surface representation shows it (DisplayRGB, unlit) in
        a black view: (view, display, regions of each camera, screenshot of each camera)."""
        view = black_view()
        display = simple.Show(field, view)
        simple.ColorBy(display, ("POINTS", "DisplayRGB"))
        unlit(display)
        # paraview.simple resets the camera on a view's first render: render before placing it.
        simple.Render(view)
        masks = self.regions(field)
        shots = []
        for k, camera in enumerate(CAMERAS):
            look(view, camera)
            simple.Render(view)
            shots.append(self.shot(f"field_{k}", view))
        return view, display, masks, shots

    def close(self):
        """Deletes the views (tearing one down at interpreter exit crashes in X) and the folder."""
        for created in simple.GetViews():
            simple.Delete(created)
        shutil.rmtree(self.folder)
