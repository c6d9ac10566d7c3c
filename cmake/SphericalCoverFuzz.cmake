# The fuzzing build (SPHCOVER_FUZZ=ON): Core and the Common and Readers VTK modules, instrumented, linked
# against the VTK that Debian's ParaView 5.11 bundles (uninstrumented: VTK is not what is
# fuzzed), and the libFuzzer harnesses of Testing/Fuzz registered as CTest tests (label `fuzz`).
# Filters, the Python wrapping, the plug-in and the command-line program are not built.

find_package(ParaView 5.11 REQUIRED COMPONENTS RemotingCore)
find_package(VTK REQUIRED
  COMPONENTS
    CommonCore
    CommonDataModel
    CommonExecutionModel
    IOCore
    IOGeometry
    IOPLY
    IOXML
  PATHS "${ParaView_DIR}/vtk"
  NO_DEFAULT_PATH)

include(GNUInstallDirs) # vtk_module_build's default destinations
# Static: the harnesses carry the instrumented reader code themselves.
set(BUILD_SHARED_LIBS OFF)
vtk_module_scan(
  MODULE_FILES
    "${PROJECT_SOURCE_DIR}/Common/vtk.module"
    "${PROJECT_SOURCE_DIR}/Readers/vtk.module"
  REQUEST_MODULES SphericalCover::Readers
  PROVIDES_MODULES sphcover_fuzz_modules
  ENABLE_TESTS OFF)
vtk_module_build(
  MODULES ${sphcover_fuzz_modules}
  PACKAGE SphericalCoverFuzz
  INSTALL_HEADERS OFF)

add_subdirectory(Testing/Fuzz)
