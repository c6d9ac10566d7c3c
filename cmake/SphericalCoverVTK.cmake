# VTK modules (Common/, Readers/, Filters/, Parallel/), their Python wrapping (package `sphericalcover`), the
# render-view classes of the plug-in (Views/, ParaView's RemotingViews), the
# ParaView plug-in and the command-line program, all built against the VTK that Debian's
# ParaView 5.11 bundles (README.md#layout): a system VTK would conflict with python3-paraview.

# Listing components keeps ParaView from dragging in its Qt client targets.
find_package(ParaView 5.11 REQUIRED COMPONENTS RemotingCore RemotingServerManager RemotingViews)
find_package(VTK REQUIRED
  COMPONENTS
    CommonCore
    CommonDataModel
    CommonExecutionModel
    CommonSystem
    FiltersCore
    FiltersGeometry
    FiltersSources
    IOCore
    IOGeometry
    IOImage
    IOPLY
    IOXML
    IOParallelXML
    IOXMLParser
    IOLegacy
    ImagingCore
    InteractionStyle
    ParallelCore
    ParallelMPI
    RenderingCore
    RenderingOpenGL2
    TestingCore
    TestingRendering
    Python
    WrappingPythonCore
  PATHS "${ParaView_DIR}/vtk"
  NO_DEFAULT_PATH)
find_package(Python3 REQUIRED COMPONENTS Interpreter Development)

include(GNUInstallDirs)
set(CMAKE_RUNTIME_OUTPUT_DIRECTORY "${CMAKE_BINARY_DIR}/${CMAKE_INSTALL_BINDIR}")
set(CMAKE_LIBRARY_OUTPUT_DIRECTORY "${CMAKE_BINARY_DIR}/${CMAKE_INSTALL_LIBDIR}")
set(CMAKE_ARCHIVE_OUTPUT_DIRECTORY "${CMAKE_BINARY_DIR}/${CMAKE_INSTALL_LIBDIR}")
set(BUILD_SHARED_LIBS ON)
# Installed programs and Python modules find our libraries and ParaView's through RPATH.
set(CMAKE_INSTALL_RPATH "$ORIGIN/../${CMAKE_INSTALL_LIBDIR};${CMAKE_INSTALL_PREFIX}/${CMAKE_INSTALL_LIBDIR}")

vtk_module_scan(
  MODULE_FILES
    "${PROJECT_SOURCE_DIR}/Common/vtk.module"
    "${PROJECT_SOURCE_DIR}/Readers/vtk.module"
    "${PROJECT_SOURCE_DIR}/Filters/vtk.module"
    "${PROJECT_SOURCE_DIR}/Parallel/vtk.module"
    "${PROJECT_SOURCE_DIR}/Views/vtk.module"
  REQUEST_MODULES
    SphericalCover::Readers
    SphericalCover::Filters
    SphericalCover::Parallel
    SphericalCover::Views
  PROVIDES_MODULES sphcover_modules
  ENABLE_TESTS OFF)

vtk_module_build(
  MODULES ${sphcover_modules}
  PACKAGE SphericalCover
  INSTALL_HEADERS OFF
  INSTALL_EXPORT SphericalCover)

vtk_module_python_default_destination(SPHCOVER_PYTHON_DESTINATION)
vtk_module_wrap_python(
  MODULES ${sphcover_modules}
  PYTHON_PACKAGE sphericalcover
  MODULE_DESTINATION "${SPHCOVER_PYTHON_DESTINATION}"
  LIBRARY_DESTINATION "${CMAKE_INSTALL_LIBDIR}"
  INSTALL_HEADERS OFF
  BUILD_STATIC OFF
  TARGET SphericalCover::Python)
# The package's __init__.py imports every wrapped module, so users write
# `from sphericalcover import vtkPatchSceneReader`.
configure_file("${PROJECT_SOURCE_DIR}/cmake/sphericalcover__init__.py"
  "${CMAKE_BINARY_DIR}/${SPHCOVER_PYTHON_DESTINATION}/sphericalcover/__init__.py" COPYONLY)
install(FILES "${PROJECT_SOURCE_DIR}/cmake/sphericalcover__init__.py"
  DESTINATION "${SPHCOVER_PYTHON_DESTINATION}/sphericalcover" RENAME "__init__.py")
set(SPHCOVER_PYTHONPATH "${CMAKE_BINARY_DIR}/${SPHCOVER_PYTHON_DESTINATION}")

paraview_plugin_scan(
  PLUGIN_FILES "${PROJECT_SOURCE_DIR}/paraview_plugin/paraview.plugin"
  PROVIDES_PLUGINS sphcover_plugins
  ENABLE_BY_DEFAULT ON)
paraview_plugin_build(
  PLUGINS ${sphcover_plugins}
  RUNTIME_DESTINATION "${CMAKE_INSTALL_BINDIR}"
  LIBRARY_DESTINATION "${CMAKE_INSTALL_LIBDIR}"
  LIBRARY_SUBDIRECTORY "paraview-plugins")
# The plug-in's XML documentation (every proxy's and property's <Documentation>) is compiled
# into a Qt help file that the plug-in carries, so the GUI's "?" shows the filter's own page:
# paraview_add_plugin's XML_DOCUMENTATION (on by default) runs xmlpatterns
# (qtxmlpatterns5-dev-tools) and qhelpgenerator (Qt5Help from qttools5-dev; scripts/setup.sh).
set(SPHCOVER_PLUGIN_PATH "${CMAKE_BINARY_DIR}/${CMAKE_INSTALL_LIBDIR}/paraview-plugins/SphericalCover/SphericalCover.so")

add_subdirectory(Apps/sphcover)
