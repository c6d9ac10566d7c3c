"""pvbatch: every proxy of the plug-in, enumerated from its server-manager XML files, so that a
proxy added later without a check here makes this test fail.
- every proxy is documented; filters are in the "Spherical Cover" menu category, readers and
  writers have a factory (files open and save by extension);
- every property (enumerated from the XML too) is documented, has a domain if it is a number,
  has an XML default equal to the C++ constructor's value, can be set to a non-default value
  that reaches the VTK object (its getter returns it), and set back to the default;
- multi-output proxies label their ports (ParaView shows the names);
- on the Cornell box at small settings, every output port has the data type and the named
  arrays (with their component counts) of Documentation/Pipeline.md, and the stages' counts agree (one
  characteristic point and one cover point per patch, ThetaBins x PhiBins hemisphere cells);
- the OpenEXR writer writes a hemisphere image that the OpenEXR reader reads back;
- the long stages (reader, subdivision, cover, propagation) report progress to ParaView;
- the View-Dependent Radiance representation of the Illumination Field renders.

usage: pvbatch TestPluginAllProxies.py PLUGIN DATA_DIR PLUGIN_XML_DIR"""
import glob
import os
import sys
import tempfile
import xml.etree.ElementTree as ElementTree

from paraview import servermanager
from paraview.simple import (Calculator, CellDatatoPointData, CreateRenderView, Delete,
                             LoadPlugin, OutputPort, Render, Show)

plugin, data, xml_folder = sys.argv[1:4]
LoadPlugin(plugin, remote=False, ns=globals())
import sphericalcover  # noqa: E402

failures = []


def proxies_in_xml():
    """(group, name, element) of every proxy declared by the plug-in's XML files."""
    found = []
    for path in sorted(glob.glob(os.path.join(xml_folder, "*.xml"))):
        for group in ElementTree.parse(path).getroot().iter("ProxyGroup"):
            for element in group:
                if element.tag.endswith("Proxy"):
                    found.append((group.get("name"), element.get("name"), element))
    return found


# ---------------------------------------------------------------------------------------------
# Properties: default == C++, set to another value and back, both reaching the VTK object.

def other_value(element, default):
    """A valid value different from the default, chosen from the property's domain."""
    enum = element.find("EnumerationDomain")
    if enum is not None:
        return next(int(e.get("value")) for e in enum if int(e.get("value")) != default)
    if element.find("BooleanDomain") is not None:
        return 1 - default
    if element.tag == "StringVectorProperty":
        return os.path.join(data, "scenes", "cornell_box.scene") \
            if element.find("FileListDomain") is not None else default + "Other"
    bounds = element.find("IntRangeDomain")
    if bounds is None:
        bounds = element.find("DoubleRangeDomain")
    upper = float(bounds.get("max")) if bounds is not None and bounds.get("max") else None
    if element.tag == "DoubleVectorProperty":
        value = default * 2 if default else 0.5
        return value if upper is None or value <= upper else default / 2
    return default + 1 if upper is None or default + 1 <= upper else default - 1


def getter_value(vtk_object, element):
    """What the VTK object holds for the property: GetX for SetX, GetNumberOfXs for AddX."""
    command = element.get("command")
    if command.startswith("Add"):
        return getattr(vtk_object, "GetNumberOf" + command[3:] + "s")()
    value = getattr(vtk_object, "Get" + command[3:])()
    return "" if value is None and element.tag == "StringVectorProperty" else value


def same(a, b):
    if isinstance(a, (list, tuple)) or isinstance(b, (list, tuple)):
        return (isinstance(a, (list, tuple)) and isinstance(b, (list, tuple))
                and len(a) == len(b) and all(same(x, y) for x, y in zip(a, b)))
    return a == b if isinstance(a, str) or isinstance(b, str) else float(a) == float(b)


def check_properties(group, name, element):
    created = servermanager.CreateProxy(group, name)
    if created is None:
        failures.append(f"{group}/{name}: ParaView cannot create the proxy")
        return
    proxy = servermanager._getPyProxy(created)
    vtk_object = proxy.GetClientSideObject()
    native = getattr(sphericalcover, element.get("class"))()
    for prop in element:
        if not prop.tag.endswith("VectorProperty") or prop.get("command") is None or \
                prop.get("information_only") == "1":
            # Information properties (the Radiance Image's CameraNamesInfo) are read, not set:
            # ParaView.GuiCornellBox checks the domain they feed.
            continue
        label = f"{name}.{prop.get('name')}"
        sm = proxy.SMProxy.GetProperty(prop.get("name"))
        if prop.get("repeat_command") == "1":
            # A list property (the writer's ChannelArrays): empty by default, two names and back.
            if sm.GetNumberOfElements() != getter_value(native, prop):
                failures.append(f"{label}: XML default has {sm.GetNumberOfElements()} elements, "
                                f"C++ {getter_value(native, prop)}")
            for values in (["Depth", "SurfaceId"], []):
                proxy.SetPropertyWithName(prop.get("name"), values)
                proxy.UpdateVTKObjects()
                if getter_value(vtk_object, prop) != len(values):
                    failures.append(f"{label}: set to {values}, the VTK object holds "
                                    f"{getter_value(vtk_object, prop)}")
            continue
        # Vector properties (a camera's Position, ...) compare whole; the first element varies.
        count = sm.GetNumberOfElements()
        defaults = [sm.GetElement(k) for k in range(count)] if count else [""]
        default = defaults[0]
        if not same(defaults if count > 1 else default, getter_value(native, prop)):
            failures.append(f"{label}: XML default {defaults if count > 1 else default!r} != "
                            f"C++ {getter_value(native, prop)!r}")
        for value in (other_value(prop, default), default):
            sm.SetElement(0, value)
            proxy.UpdateVTKObjects()
            expected = [value] + defaults[1:] if count > 1 else value
            if not same(getter_value(vtk_object, prop), expected):
                failures.append(f"{label}: set to {expected!r}, the VTK object holds "
                                f"{getter_value(vtk_object, prop)!r}")
        if not prop.findall("Documentation"):
            failures.append(f"{label}: no <Documentation>")
        # Numbers need a domain; 3-D points and directions (a camera's Position, FocalPoint,
        # ViewUp) are free vectors without one.
        is_vector3 = prop.tag == "DoubleVectorProperty" and count == 3
        if prop.tag in ("IntVectorProperty", "DoubleVectorProperty") and not is_vector3 and not any(
                child.tag.endswith("Domain") for child in prop):
            failures.append(f"{label}: no domain (enumeration, boolean or range)")
    Delete(proxy)


def check_declaration(group, name, element):
    """Documented; filters in the "Spherical Cover" menu, readers and writers by extension."""
    if element.find("Documentation") is None:
        failures.append(f"{name}: no <Documentation>")
    hints = element.find("Hints")
    if group == "filters":
        menu = hints.find("ShowInMenu") if hints is not None else None
        if menu is None or menu.get("category") != "Spherical Cover":
            failures.append(f"{name}: not in the Spherical Cover menu category")
    reader = group == "sources" and any(p.get("name") == "FileName" for p in element)
    factory = "ReaderFactory" if reader else "WriterFactory" if group == "writers" else None
    if factory and (hints is None or hints.find(factory) is None):
        failures.append(f"{name}: no {factory} (files do not open or save by extension)")


# ---------------------------------------------------------------------------------------------
# Outputs on the Cornell box: type and named arrays (components) per Documentation/Pipeline.md.

MATERIAL_CELLS = {"SurfaceId": 1, "MaterialId": 1, "Emission": 3, "Diffuse": 3, "Specular": 3,
                  "PhongExponent": 1}
SCENE_FIELDS = {"MaterialNames": 1, "CameraNames": 1, "CameraParameters": 12}


def arrays(attributes):
    """{name: components} of a vtkDataSetAttributes / vtkFieldData."""
    found = {}
    for k in range(attributes.GetNumberOfArrays()):
        array = attributes.GetAbstractArray(k)
        found[array.GetName()] = array.GetNumberOfComponents()
    return found


def check_output(label, data_object, class_name, point=None, cell=None, field=None, rows=None):
    """Type and named arrays of one output port; returns the data object."""
    if data_object is None or data_object.GetClassName() != class_name:
        failures.append(f"{label}: {data_object.GetClassName() if data_object else None}, "
                        f"expected {class_name}")
        return data_object
    expected_sets = [("point", point, lambda d: d.GetPointData()),
                     ("cell", cell, lambda d: d.GetCellData()),
                     ("field", field, lambda d: d.GetFieldData()),
                     ("column", rows, lambda d: d.GetRowData())]
    for kind, expected, attributes in expected_sets:
        if not expected:
            continue
        present = arrays(attributes(data_object))
        for name, components in expected.items():
            if name not in present:
                failures.append(f"{label}: no {kind} array {name}")
            elif present[name] != components:
                failures.append(f"{label}: {kind} array {name} has {present[name]} components, "
                                f"expected {components}")
    size = data_object.GetNumberOfRows() if class_name == "vtkTable" \
        else data_object.GetNumberOfPoints()
    if size == 0:
        failures.append(f"{label}: empty")
    return data_object


def output(proxy, port=0):
    proxy.UpdatePipeline()
    return servermanager.Fetch(proxy, idx=port)


def check_port_names(proxy, names):
    for index, name in enumerate(names):
        shown = proxy.SMProxy.GetOutputPortName(index)
        if shown != name:
            failures.append(f"{proxy.GetXMLName()}: output port {index} is labelled {shown!r}, "
                            f"expected {name!r}")


# Progress as ParaView's progress bar receives it: the ProgressEvents of each stage's VTK object
# (observed before anything updates: the Hemisphere Extractor updates its input on creation).
progress = {}


def observed(proxy):
    values = progress.setdefault(proxy.GetXMLName(), [])
    proxy.GetClientSideObject().AddObserver(
        "ProgressEvent", lambda algorithm, event: values.append(algorithm.GetProgress()))
    return proxy


folder = tempfile.mkdtemp()
cornell = os.path.join(data, "scenes", "cornell_box.scene")
scene = observed(globals()["PatchSceneReader"](FileName=cornell))
subdivision = observed(globals()["IntervalSubdivision"](Input=scene, MaxLevel=1))
cover = observed(globals()["SphericalCover"](Input=OutputPort(subdivision, 0), ThetaBins=8,
                                             PhiBins=32))
propagation = observed(globals()["LightPropagation"](Input=OutputPort(cover, 0)))
hemisphere = globals()["HemisphereExtractor"](Input=OutputPort(cover, 0), PointId=3)


def check_scene_reader():
    check_output("PatchSceneReader", output(scene), "vtkUnstructuredGrid", cell=MATERIAL_CELLS,
                 field=SCENE_FIELDS)


def check_bpt_reader():
    reader = globals()["BPTReader"](FileName=os.path.join(data, "models", "teapot.bpt"))
    teapot = check_output("BPTReader", output(reader), "vtkUnstructuredGrid",
                          cell=dict(MATERIAL_CELLS, HigherOrderDegrees=3))
    if teapot and teapot.GetNumberOfCells() != 32:
        failures.append(f"BPTReader: {teapot.GetNumberOfCells()} patches of the teapot, "
                        "expected 32")
    Delete(reader)


def check_subdivision():
    check_port_names(subdivision, ["Patches", "Characteristic Points"])
    patches = check_output("IntervalSubdivision Patches", output(subdivision, 0),
                           "vtkUnstructuredGrid",
                           cell={"SurfaceId": 1, "PatchId": 1, "Level": 1, "UVRange": 4, "Area": 1,
                                 "SplitReason": 1})
    points = check_output("IntervalSubdivision Characteristic Points", output(subdivision, 1),
                          "vtkPolyData", point={"Normals": 3, "PatchId": 1, "SurfaceId": 1, "UV": 2,
                                                "Area": 1})
    if patches and points and points.GetNumberOfPoints() != patches.GetNumberOfCells():
        failures.append("IntervalSubdivision: not one characteristic point per patch")


def check_cover():
    check_port_names(cover, ["Cover Points", "Strips"])
    points = check_output("SphericalCover Cover Points", output(cover, 0), "vtkPolyData",
                          point={"Normals": 3, "Area": 1, "PatchId": 1, "SurfaceId": 1,
                                 "CoveredProjectedSolidAngle": 1, "VisibleSources": 1,
                                 "InputPatchId": 1})
    check_output("SphericalCover Strips", output(cover, 1), "vtkTable",
                 rows={"Receiver": 1, "Source": 1, "Theta": 1, "PhiBegin": 1, "PhiEnd": 1, "R": 1})
    # The cover's refinement (vtkSphericalCoverFilter::Refinement) splits patches, never merges
    # them: at least one point per patch, and the points' areas add up to the patches' area.
    patches = output(subdivision, 0)
    if points and points.GetNumberOfPoints() < patches.GetNumberOfCells():
        failures.append("SphericalCover: fewer cover points than patches")
    elif points:
        def total(data, cells):
            attributes = data.GetCellData() if cells else data.GetPointData()
            area = attributes.GetArray("Area")
            return sum(area.GetValue(k) for k in range(area.GetNumberOfTuples()))
        covered, subdivided = total(points, False), total(patches, True)
        if abs(covered - subdivided) > 1e-9 * subdivided:
            failures.append(f"SphericalCover: points' area {covered} != patches' {subdivided}")


def check_propagation():
    check_port_names(propagation, ["Illumination", "History"])
    check_output("LightPropagation Illumination", output(propagation, 0), "vtkPolyData",
                 point={"Irradiance": 3, "Radiosity": 3, "Brightness": 3},
                 field={"IncidentRadiance": 3})
    check_output("LightPropagation History", output(propagation, 1), "vtkTable",
                 rows={"Shot": 1, "Shooter": 1, "MaxChange": 1, "UnshotEnergy": 1, "Seconds": 1})


def check_hemisphere():
    check_port_names(hemisphere, ["Hemisphere Image", "Hemisphere Mesh"])
    # Documentation/Pipeline.md#inspection-filters also names Radiance, which comes with the
    # incident radiance per cell (see vtkHemisphereExtractor.h); the geometric arrays are checked
    # here.
    cells = {"Source": 1, "SurfaceId": 1, "R": 1, "ProjectedSolidAngle": 1}
    image = check_output("HemisphereExtractor Hemisphere Image", output(hemisphere, 0),
                         "vtkImageData", cell=cells)
    mesh = check_output("HemisphereExtractor Hemisphere Mesh", output(hemisphere, 1),
                        "vtkPolyData", cell=cells, point={"Normals": 3})
    for label, grid in (("Image", image), ("Mesh", mesh)):
        if grid and grid.GetNumberOfCells() != 8 * 32:
            failures.append(f"HemisphereExtractor {label}: {grid.GetNumberOfCells()} cells, "
                            f"expected ThetaBins x PhiBins = 256")


def check_radiance_image():
    render = globals()["RadianceImage"](Input=OutputPort(propagation, 0),
                                        Patches=OutputPort(subdivision, 0), CameraName="main",
                                        Width=32, Height=24)
    image = check_output("RadianceImage", output(render), "vtkImageData",
                         point={"Radiance": 3, "Depth": 1, "SurfaceId": 1, "RGB": 3})
    if image and image.GetDimensions()[:2] != (32, 24):
        failures.append(f"RadianceImage: dimensions {image.GetDimensions()}, expected 32 x 24")
    Delete(render)


def check_illumination_field():
    field = globals()["IlluminationField"](Input=OutputPort(propagation, 0),
                                           Patches=OutputPort(subdivision, 0))
    lit = check_output("IlluminationField", output(field), "vtkPolyData",
                       point={"Radiance": 3, "Normals": 3, "SurfaceId": 1, "DisplayRGB": 3},
                       cell={"PatchId": 1})
    if lit and lit.GetNumberOfCells() < output(subdivision, 0).GetNumberOfCells():
        failures.append("IlluminationField: fewer quads than patches")
    Delete(field)


def check_view_dependent_representation():
    # The Illumination Field shown as "View-Dependent Radiance" renders, the data it shows with
    # the arrays the mapper evaluates from (SurfaceId, UV) and writes (DisplayRGB; its
    # ViewRadiance goes to the copy the view delivers to the mapper, not to this data).
    # ParaView.ViewDependentRadianceRepresentation checks what it shows.
    field = globals()["IlluminationField"](Input=OutputPort(propagation, 0),
                                           Patches=OutputPort(subdivision, 0))
    view = CreateRenderView()
    view.ViewSize = [64, 48]
    display = Show(field, view)
    display.SetRepresentationType("View-Dependent Radiance")
    Render(view)
    rendered = display.GetClientSideObject().GetRenderedDataObject(0)
    leaves = rendered.NewIterator() if rendered else None
    if leaves is None:
        failures.append("ViewDependentRadianceRepresentation: nothing rendered")
    else:
        leaves.InitTraversal()
        check_output("ViewDependentRadianceRepresentation", leaves.GetCurrentDataObject(),
                     "vtkPolyData", point={"DisplayRGB": 3, "SurfaceId": 1, "UV": 2})
    Delete(view)
    Delete(field)


exr_path = os.path.join(folder, "hemisphere.exr")


def check_exr_writer():
    # The hemisphere image as an HDR image: a 3-component point array Radiance and the cells'
    # measure as an extra channel (not R: the channels R, G, B hold Radiance).
    points = CellDatatoPointData(Input=OutputPort(hemisphere, 0))
    radiance = Calculator(Input=points, ResultArrayName="Radiance", ResultArrayType="Float",
                          Function="ProjectedSolidAngle*iHat + R*jHat + SurfaceId*kHat")
    writer = servermanager.writers.OpenEXRWriter(Input=radiance, FileName=exr_path,
                                                 ChannelArrays=["ProjectedSolidAngle"])
    writer.UpdatePipeline()
    if not os.path.isfile(exr_path):
        failures.append("OpenEXRWriter: no file written")
    Delete(writer)


def check_exr_reader():
    reader = globals()["OpenEXRReader"](FileName=exr_path)
    image = check_output("OpenEXRReader", output(reader), "vtkImageData",
                         point={"Radiance": 3, "ProjectedSolidAngle": 1})
    if image and image.GetDimensions() != (33, 9, 1):
        failures.append(f"OpenEXRReader: dimensions {image.GetDimensions()}, expected the "
                        f"hemisphere image's (33, 9, 1)")
    Delete(reader)


# One check per proxy; the writer runs before the reader that reads its file.
CHECKS = {
    "PatchSceneReader": check_scene_reader,
    "BPTReader": check_bpt_reader,
    "IntervalSubdivision": check_subdivision,
    "SphericalCover": check_cover,
    "LightPropagation": check_propagation,
    "HemisphereExtractor": check_hemisphere,
    "RadianceImage": check_radiance_image,
    "IlluminationField": check_illumination_field,
    "ViewDependentRadianceRepresentation": check_view_dependent_representation,
    "OpenEXRWriter": check_exr_writer,
    "OpenEXRReader": check_exr_reader,
}

declared = proxies_in_xml()
if len(declared) < len(CHECKS):
    failures.append(f"only {len(declared)} proxies found in {xml_folder}")
for group, name, element in declared:
    if name not in CHECKS:
        failures.append(f"proxy {group}/{name} has no output check in this test: add one")
    check_declaration(group, name, element)
    check_properties(group, name, element)
for name, check in CHECKS.items():
    if name not in {n for _, n, _ in declared}:
        failures.append(f"{name} is checked here but not declared in the XML")
    check()

# The long stages report progress between 0 and 1 and end at 1.
for name, values in progress.items():
    if not any(0 < v < 1 for v in values) or not values or values[-1] != 1.0:
        failures.append(f"{name}: progress {values[:10]}, expected steps between 0 and 1 "
                        "ending at 1")

for failure in failures:
    print("FAILED:", failure)
print(f"{len(declared)} proxies checked")
sys.exit(1 if failures else 0)
