"""What several Python tests share: an error collector for VTK algorithms and the Cornell box's
pipeline at its coarsest useful settings (max_level 1, an 8 x 32 hemisphere grid), the stages
connected but not updated."""
from sphericalcover import (vtkIntervalSubdivisionFilter, vtkLightPropagationFilter,
                            vtkPatchSceneReader, vtkPLightPropagationFilter,
                            vtkPSphericalCoverFilter, vtkSphericalCoverFilter)
from vtkmodules.util.misc import calldata_type
from vtkmodules.vtkCommonCore import VTK_STRING, vtkCommand


class ErrorCollector:
    """Collects the error messages of the algorithms it observes (vtkErrorMacro invokes
    ErrorEvent with the text) in `messages`, as 'ClassName: message'."""

    def __init__(self):
        self.messages = []

    def observe(self, algorithm):
        @calldata_type(VTK_STRING)
        def on_error(caller, event, message):
            self.messages.append(f"{caller.GetClassName()}: {message}")
        algorithm.AddObserver(vtkCommand.ErrorEvent, on_error)
        return algorithm


def coarse_cornell_pipeline(data, collector, distributed=False):
    """(reader, subdivision, cover, propagation) of Data/scenes/cornell_box.scene, each observed
    by `collector`; `distributed`: the cover and the propagation are the Parallel module's
    (under MPI every rank holding the whole scene, the ranks sharing the work)."""
    observe = collector.observe
    reader = observe(vtkPatchSceneReader())
    reader.SetFileName(f"{data}/scenes/cornell_box.scene")
    subdivision = observe(vtkIntervalSubdivisionFilter())
    subdivision.SetInputConnection(reader.GetOutputPort())
    subdivision.SetMaxLevel(1)
    cover = observe(vtkPSphericalCoverFilter() if distributed else vtkSphericalCoverFilter())
    cover.SetInputConnection(subdivision.GetOutputPort(0))
    cover.SetThetaBins(8)
    cover.SetPhiBins(32)
    propagation = observe(vtkPLightPropagationFilter() if distributed
                          else vtkLightPropagationFilter())
    propagation.SetInputConnection(cover.GetOutputPort(0))
    return reader, subdivision, cover, propagation
