"""SphericalCover: Mudur & Pattanaik (1990) spherical-cover global illumination as VTK classes.

Usage::

    from sphericalcover import vtkPatchSceneReader
"""
# VTK's own modules first, so the wrapped classes find their base classes' Python types.
import vtkmodules.vtkCommonCore  # noqa: F401
import vtkmodules.vtkCommonDataModel  # noqa: F401
import vtkmodules.vtkCommonExecutionModel  # noqa: F401

from .SphericalCoverReaders import *  # noqa: F401,F403
from .SphericalCoverFilters import *  # noqa: F401,F403
from .SphericalCoverParallel import *  # noqa: F401,F403
# The plug-in's render-view classes derive from ParaView's RemotingViews: importable where
# ParaView's Python modules are (pvpython, pvbatch, python3 with python3-paraview).
try:
    from .SphericalCoverViews import *  # noqa: F401,F403
except ImportError:
    pass
