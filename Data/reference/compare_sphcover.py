"""SphericalCover vs the Cycles reference: block-wise comparison of a render with an EXR.

Runs under /usr/bin/python3 (ParaView's vtkmodules) with the build's package on the path:

    PYTHONPATH=build/lib/python3.11/site-packages /usr/bin/python3 \\
        Data/reference/compare_sphcover.py --size 128x128 --spp 64

renders Data/scenes/cornell_box.scene through its first camera with the whole pipeline
(reader, subdivision, spherical cover, light propagation, vtkRadianceImageFilter) at the
scene's settings (`--set key=value` overrides them as `sphcover --set` does), or renders a
saved solution (`--solution cornell.vtm`, from `sphcover solve -o`), or takes a finished
image (`--image mine.exr`), and compares its linear `Radiance` with
cornell_box_cycles.exr, both read with vtkOpenEXRReader.

The comparison (README.md, "How to compare" and "SphericalCover vs Cycles"): the reference is
cut into square blocks of `--block` pixels (16 by default: 32 x 32 blocks at 512 x 512) and the
image into the same regions (at 128 x 128, blocks of 4 pixels). A pixel is the mean radiance
over its own area in both renderers, so a block mean is the mean over the block's area,
whatever the resolution. With A_bc, B_bc the block means of the image and the reference
(block b, channel c),

    e   = sqrt( mean over (b, c) with B_bc > 1e-3 * mean_c(B) of ((A_bc - B_bc) / B_bc)^2 )
    e_c = the same over the blocks of channel c only

and, per channel, the largest block error, the normalised RMS difference
sqrt(mean_b (A_bc - B_bc)^2) / mean_b B_bc and the image means. `--map` prints the block
error map (the RMS over the three channels of each block's relative error, in percent, the
image's top row first) and `--map-exr map.exr` writes the signed per-channel block errors
as an EXR (one pixel per block, VTK's row order, readable in ParaView).

The functions are used by Testing/Python/TestCyclesReference.py and (read_exr, block_means,
DARK_FRACTION) by Testing/Benchmarks/time_to_accuracy.py.
"""
import argparse
import math
import os
import sys
import time

import numpy as np
from vtkmodules.util.numpy_support import numpy_to_vtk, vtk_to_numpy
from vtkmodules.vtkCommonDataModel import vtkImageData

HERE = os.path.dirname(os.path.abspath(__file__))
DATA = os.path.dirname(HERE)
REFERENCE = os.path.join(HERE, "cornell_box_cycles.exr")
SCENE = os.path.join(DATA, "scenes", "cornell_box.scene")

# Blocks whose reference mean is below this fraction of the channel's image mean see next to
# nothing; their relative error is noise over noise (exr_stats.py compare uses the same cut).
DARK_FRACTION = 1e-3


def radiance_array(image):
    """The `Radiance` of a vtkImageData as a float64 array [row, column, channel], row 0 at the
    bottom (VTK's order)."""
    nx, ny, _ = image.GetDimensions()
    array = image.GetPointData().GetArray("Radiance")
    if array is None or array.GetNumberOfComponents() != 3:
        raise RuntimeError("the image has no 3-component Radiance array")
    return vtk_to_numpy(array).astype(np.float64).reshape(ny, nx, 3)


def read_exr(path):
    """An EXR's R, G, B with vtkOpenEXRReader: [row, column, channel], row 0 at the bottom."""
    from sphericalcover import vtkOpenEXRReader
    if not os.path.isfile(path):
        raise RuntimeError(f"{path}: no such file")
    reader = vtkOpenEXRReader()
    reader.SetFileName(path)
    reader.Update()
    if reader.GetErrorCode() or reader.GetOutput().GetNumberOfPoints() == 0:
        raise RuntimeError(f"{path}: vtkOpenEXRReader could not read it")
    return radiance_array(reader.GetOutput())


def write_exr(path, array):
    """Writes [row, column, channel] (row 0 at the bottom) as the Radiance of an EXR."""
    from sphericalcover import vtkOpenEXRWriter
    ny, nx, _ = array.shape
    image = vtkImageData()
    image.SetDimensions(nx, ny, 1)
    values = numpy_to_vtk(np.ascontiguousarray(array.reshape(-1, 3), dtype=np.float32), deep=1)
    values.SetName("Radiance")
    image.GetPointData().SetScalars(values)
    writer = vtkOpenEXRWriter()
    writer.SetFileName(path)
    writer.SetInputData(image)
    if not writer.Write():
        raise RuntimeError(f"{path}: could not write the EXR")


def scene_settings(reader_output):
    """theta_bins, phi_bins, max_level, tolerance, min_patch_size from the reader's
    `SceneSettings` field."""
    values = reader_output.GetFieldData().GetArray("SceneSettings")
    if values is None or values.GetNumberOfComponents() != 5:
        raise RuntimeError("the scene reader gave no SceneSettings")
    return {"theta_bins": int(values.GetComponent(0, 0)),
            "phi_bins": int(values.GetComponent(0, 1)),
            "max_level": int(values.GetComponent(0, 2)),
            "tolerance": values.GetComponent(0, 3),
            "min_patch_size": values.GetComponent(0, 4)}


def render(scene=SCENE, solution=None, camera="", size=None, spp=16, overrides=None,
           verbose=False):
    """Radiance of `scene` through `camera` (default: the first), [row, column, channel] with
    row 0 at the bottom, from the whole pipeline at the scene's settings updated by
    `overrides`, or from a solution file of `sphcover solve -o`. `size` (width, height)
    defaults to the camera's. Returns (radiance, facts) with the settings and timings."""
    from sphericalcover import (vtkIntervalSubdivisionFilter, vtkLightPropagationFilter,
                                vtkPatchSceneReader, vtkRadianceImageFilter,
                                vtkSphericalCoverFilter)
    from vtkmodules.vtkCommonExecutionModel import vtkTrivialProducer
    from vtkmodules.vtkIOXML import vtkXMLMultiBlockDataReader

    facts = {}
    reader = vtkPatchSceneReader()
    reader.SetFileName(scene)
    reader.Update()
    if reader.GetErrorCode() or reader.GetOutput().GetNumberOfCells() == 0:
        raise RuntimeError(f"{scene}: the scene could not be read")
    names = reader.GetOutput().GetFieldData().GetAbstractArray("CameraNames")
    cameras = [names.GetValue(k) for k in range(names.GetNumberOfValues())] if names else []
    camera = camera or (cameras[0] if cameras else "")
    if camera not in cameras:
        raise RuntimeError(f"{scene}: no camera '{camera}' (cameras: {cameras})")
    if size is None:
        # CameraParameters: position, focal point, view up, view angle, width, height.
        parameters = reader.GetOutput().GetFieldData().GetArray("CameraParameters")
        k = cameras.index(camera)
        size = (int(parameters.GetComponent(k, 10)), int(parameters.GetComponent(k, 11)))

    start = time.perf_counter()
    if solution is None:
        settings = scene_settings(reader.GetOutput())
        settings.update(overrides or {})
        facts["settings"] = settings
        subdivision = vtkIntervalSubdivisionFilter()
        subdivision.SetInputConnection(reader.GetOutputPort())
        subdivision.SetThetaBins(settings["theta_bins"])
        subdivision.SetPhiBins(settings["phi_bins"])
        subdivision.SetMaxLevel(settings["max_level"])
        subdivision.SetTolerance(settings["tolerance"])
        subdivision.SetMinPatchSize(settings["min_patch_size"])
        cover = vtkSphericalCoverFilter()
        cover.SetInputConnection(subdivision.GetOutputPort(0))
        cover.SetThetaBins(settings["theta_bins"])
        cover.SetPhiBins(settings["phi_bins"])
        propagation = vtkLightPropagationFilter()
        propagation.SetInputConnection(cover.GetOutputPort(0))
        propagation.Update()
        if propagation.GetErrorCode() or propagation.GetOutput().GetNumberOfPoints() == 0:
            raise RuntimeError(f"{scene}: the pipeline failed before rendering")
        facts["characteristic_points"] = propagation.GetOutput().GetNumberOfPoints()
        facts["shots"] = propagation.GetShots()
        illumination_port = propagation.GetOutputPort(0)
        patches_port = subdivision.GetOutputPort(0)
        keep = (subdivision, cover, propagation)
    else:
        saved = vtkXMLMultiBlockDataReader()
        saved.SetFileName(solution)
        saved.Update()
        blocks = saved.GetOutputDataObject(0)
        if blocks is None or blocks.GetNumberOfBlocks() != 2:
            raise RuntimeError(f"{solution}: not a solution of sphcover solve -o")
        patches, illumination = vtkTrivialProducer(), vtkTrivialProducer()
        patches.SetOutput(blocks.GetBlock(0))
        illumination.SetOutput(blocks.GetBlock(1))
        facts["characteristic_points"] = blocks.GetBlock(1).GetNumberOfPoints()
        illumination_port = illumination.GetOutputPort()
        patches_port = patches.GetOutputPort()
        keep = (saved, patches, illumination)
    facts["solve_s"] = time.perf_counter() - start

    start = time.perf_counter()
    image_filter = vtkRadianceImageFilter()
    image_filter.SetInputConnection(0, illumination_port)
    image_filter.SetPatchesConnection(patches_port)
    image_filter.SetCameraName(camera)
    image_filter.SetWidth(size[0])
    image_filter.SetHeight(size[1])
    image_filter.SetSamplesPerPixel(spp)
    image_filter.Update()
    if image_filter.GetErrorCode() or image_filter.GetOutput().GetNumberOfPoints() == 0:
        raise RuntimeError(f"{scene}: the render failed")
    facts["render_s"] = time.perf_counter() - start
    facts.update({"camera": camera, "size": tuple(size), "spp": spp})
    del keep
    return radiance_array(image_filter.GetOutput()), facts


def block_means(image, block):
    """Means over square blocks of `block` pixels: [block row, block column, channel]."""
    ny, nx, nc = image.shape
    if ny % block or nx % block:
        raise ValueError(f"{nx} x {ny} pixels do not divide into blocks of {block}")
    return image.reshape(ny // block, block, nx // block, block, nc).mean(axis=(1, 3))


def compare(image, reference, block=16):
    """The figures of the module docstring for `image` against `reference` (arrays of
    [row, column, channel]); the image may have another resolution of the same aspect, its
    blocks then cover the same regions as the reference's `block`-pixel blocks."""
    ry, rx, _ = reference.shape
    iy, ix, _ = image.shape
    if rx * iy != ry * ix or (rx // block) == 0 or ix % (rx // block) or iy % (ry // block):
        raise ValueError(f"a {ix} x {iy} image does not divide into the {rx // block} x "
                         f"{ry // block} blocks of the {rx} x {ry} reference")
    a = block_means(image, ix // (rx // block))
    b = block_means(reference, block)
    lit = b > DARK_FRACTION * reference.mean(axis=(0, 1))
    relative = np.where(lit, (a - b) / np.where(lit, b, 1.0), 0.0)
    result = {
        "blocks": a.shape[0] * a.shape[1],
        "lit_block_channels": int(lit.sum()),
        "block_rms": math.sqrt((relative[lit] ** 2).mean()),
        "block_rms_channel": [math.sqrt((relative[..., c][lit[..., c]] ** 2).mean())
                              for c in range(3)],
        "max_block_error_channel": [float(np.abs(relative[..., c]).max()) for c in range(3)],
        "normalised_rms_channel": [math.sqrt(((a[..., c] - b[..., c]) ** 2).mean())
                                   / b[..., c].mean() for c in range(3)],
        "mean_image": image.mean(axis=(0, 1)).tolist(),
        "mean_reference": reference.mean(axis=(0, 1)).tolist(),
        "relative": relative,
        "lit": lit,
    }
    result["mean_error_channel"] = [result["mean_image"][c] / result["mean_reference"][c] - 1.0
                                    for c in range(3)]
    return result


def error_map_text(result):
    """The block error map as text: per block the RMS over the lit channels of the relative
    error in percent (rounded; '.' below 0.5 %, ' ' for a dark block), the top row first."""
    relative, lit = result["relative"], result["lit"]
    count = lit.sum(axis=2)
    rms = np.sqrt((relative ** 2).sum(axis=2) / np.maximum(count, 1)) * 100.0
    lines = []
    for row in range(rms.shape[0] - 1, -1, -1):
        cells = []
        for column in range(rms.shape[1]):
            if count[row, column] == 0:
                cells.append("   ")
            elif rms[row, column] < 0.5:
                cells.append("  .")
            else:
                cells.append(f"{min(rms[row, column], 99.0):3.0f}")
        lines.append("".join(cells))
    return "\n".join(lines)


def report(result, facts=None):
    """The figures as text."""
    lines = []
    if facts:
        lines.append("render: " + ", ".join(f"{k} {v}" for k, v in facts.items()))
    lines.append(f"blocks: {result['blocks']}, lit block-channels: {result['lit_block_channels']}"
                 f" of {3 * result['blocks']}")
    lines.append(f"block-RMS relative error e = {result['block_rms']:.5f}")
    for name, c in zip("RGB", range(3)):
        lines.append(f"  {name}: e_c {result['block_rms_channel'][c]:.5f}, "
                     f"max block {result['max_block_error_channel'][c]:.4f}, "
                     f"normalised RMS {result['normalised_rms_channel'][c]:.5f}, "
                     f"mean {result['mean_image'][c]:.6f} vs {result['mean_reference'][c]:.6f}"
                     f" ({100.0 * result['mean_error_channel'][c]:+.3f} %)")
    return "\n".join(lines)


def parse_size(text):
    try:
        width, height = (int(part) for part in text.lower().split("x"))
    except ValueError:
        raise argparse.ArgumentTypeError(f"'{text}' is not WIDTHxHEIGHT") from None
    return width, height


def parse_set(text):
    key, _, value = text.partition("=")
    if key not in ("theta_bins", "phi_bins", "max_level", "tolerance") or not value:
        raise argparse.ArgumentTypeError(f"'{text}' is not theta_bins|phi_bins|max_level|"
                                         "tolerance=VALUE")
    return key, (float(value) if key == "tolerance" else int(value))


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    source = parser.add_mutually_exclusive_group()
    source.add_argument("--solution", help="render a solution of `sphcover solve -o` (.vtm)")
    source.add_argument("--image", help="compare this EXR instead of rendering")
    parser.add_argument("--scene", default=SCENE, help="scene file (default: the Cornell box)")
    parser.add_argument("--camera", default="", help="camera (default: the scene's first)")
    parser.add_argument("--size", type=parse_size, help="WIDTHxHEIGHT (default: the camera's)")
    parser.add_argument("--spp", type=int, default=16, help="samples per pixel (default 16)")
    parser.add_argument("--set", type=parse_set, action="append", default=[],
                        help="override a scene setting, e.g. --set max_level=3")
    parser.add_argument("--reference", default=REFERENCE, help="reference EXR")
    parser.add_argument("--block", type=int, default=16, help="block size in reference pixels")
    parser.add_argument("--map", action="store_true", help="print the block error map")
    parser.add_argument("--map-exr", help="write the signed block errors to this EXR")
    parser.add_argument("--save", help="write the rendered Radiance to this EXR")
    args = parser.parse_args()

    try:
        reference = read_exr(args.reference)
        facts = None
        if args.image:
            image = read_exr(args.image)
        else:
            image, facts = render(args.scene, args.solution, args.camera, args.size, args.spp,
                                  dict(args.set))
            if args.save:
                write_exr(args.save, image)
        result = compare(image, reference, args.block)
    except (RuntimeError, ValueError) as error:
        print(f"compare_sphcover.py: {error}", file=sys.stderr)
        return 1
    print(report(result, facts))
    if args.map:
        print("block error map (RMS over channels, %, top row first):")
        print(error_map_text(result))
    if args.map_exr:
        write_exr(args.map_exr, result["relative"])
    return 0


if __name__ == "__main__":
    sys.exit(main())
