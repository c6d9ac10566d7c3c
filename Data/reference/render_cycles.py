"""Independent path-traced reference of a SphericalCover scene with Blender Cycles.

Run inside Blender (tested with Debian's blender 3.4.1):

    blender -b --factory-startup --python Data/reference/render_cycles.py -- \
        --scene Data/scenes/cornell_box.scene --out Data/reference/cornell_box_cycles.exr \
        --samples 2048 --passes 4 --seed 0 --threads 2 --png Data/reference/cornell_box_cycles.png

The scene file is parsed here (geometry through Data/scenes/tools/scenegeom.py, the same
helpers that verify the scenes), so nothing of the Cornell box is hard-coded. What the
script sets up, and why (see README.md in this folder for the unit checks):

- Geometry: every patch is a mesh whose faces keep the patch's front side (dP/du x dP/dv,
  FORMAT.md "Orientation"). A planar bilinear quad is one exact quad; twisted bilinear and
  Bezier patches are tessellated on a --tessellation x --tessellation grid in (u, v).
- Materials: `diffuse` (Lambertian, BRDF = reflectance / pi): Cycles' Diffuse BSDF with
  roughness 0 (Lambert) and the reflectance as colour. A `tabulated` material whose table names
  the Cycles closure it was made from (a comment line `# origin: cycles-glossy-ggx
  roughness=R color=R,G,B`, written by Data/brdf/tools/make_ggx_table.py) is rendered with that
  closure itself, the Glossy BSDF (distribution GGX, the roughness and colour of the line), not
  with the table: the table is checked to be that lobe first (every row within 1e-5), so the
  two renderers are given the same BRDF, each in its own form. Any other type (mirror, phong,
  a table without an origin) is refused: Cycles' sharp glossy as a mirror came out 14 % dark
  in a lit room against the room unfolded across the mirror (issue 39), so mirror scenes are
  compared with their unfolded, all-diffuse twin instead. A `texture` (paper §5.4) multiplies that
  colour: an Image Texture node (bilinear, "Linear"; edge texels extended, "EXTEND"; the PNG
  decoded to linear floats first, see linear_texture) read at the mesh's UV map, which
  holds every vertex's (u, v) in its patch (FORMAT.md: u across the image's columns from the
  left, v up its rows from the bottom, Blender's UV convention too). A `transmittance` (a thin
  pane) adds a Transparent BSDF of that colour, which lets rays through unbent and scaled, on
  both sides (a pane is two-sided). `emission` becomes an Emission shader of
  strength 1 whose colour is the radiance (a Cycles emission of strength 1 shows its colour
  as the pixel value: measured, README.md). One-sided surfaces (the default) are black and
  non-emitting from behind: a Mix shader driven by Geometry > Backfacing switches to an empty
  closure (no reflection, no emission) on the back; the back still blocks light, as in the
  scene format.
- Camera: the scene camera (VTK's convention: vertical view angle), sensor fit vertical,
  width x height at 100 %, box pixel filter of --filter-width pixels (1 = the pixel's own
  area, nothing leaks into neighbours, so block means are area means of radiance).
- Light transport: path tracing, no clamping, no denoising, no adaptive sampling, no light
  threshold, no caustics filter, --bounces diffuse and glossy bounces (Russian roulette keeps it
  unbiased; 128 bounces of albedo <= 0.89 leave < 1e-6 of the light), black world.
- Output: linear scene radiance, OpenEXR 32-bit float RGB (view transform Standard, look None,
  exposure 0, gamma 1; the EXR is written before any display transform), written to a
  temporary file and renamed. Optionally an sRGB PNG preview (--png, --png-exposure).
"""

import argparse
import json
import math
import os
import sys
import time

import bpy
import mathutils
import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(os.path.dirname(HERE), "scenes", "tools"))

import scenegeom  # noqa: E402


def fail(msg):
    print("render_cycles.py: error: " + msg, file=sys.stderr)
    sys.exit(1)


def parse_args():
    argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    ap = argparse.ArgumentParser(prog="render_cycles.py",
                                 description="Render a .scene with Blender Cycles to a linear EXR.")
    ap.add_argument("--scene", required=True, help="the .scene file")
    ap.add_argument("--out", required=True, help="output .exr (32-bit float RGB, linear)")
    ap.add_argument("--camera", help="camera name (default: the first camera)")
    ap.add_argument("--samples", type=int, default=1024, help="samples per pixel")
    ap.add_argument("--seed", type=int, default=0, help="Cycles sampling seed of the first pass")
    ap.add_argument("--passes", type=int, default=1,
                    help="render SAMPLES/PASSES spp PASSES times with seeds SEED, SEED+1, ... and "
                         "average (the spread of the passes measures the noise of the result)")
    ap.add_argument("--bounces", type=int, default=128,
                    help="maximum diffuse (and glossy) bounces after the first hit (0: emission and "
                         "direct light only)")
    ap.add_argument("--width", type=int, help="override the camera width (pixels)")
    ap.add_argument("--height", type=int, help="override the camera height (pixels)")
    ap.add_argument("--filter-width", type=float, default=1.0,
                    help="box pixel filter width in pixels (default 1: the pixel area)")
    ap.add_argument("--tessellation", type=int, default=64,
                    help="grid per curved/twisted patch (planar quads stay one quad)")
    ap.add_argument("--threads", type=int, default=0, help="render threads (0: all cores)")
    ap.add_argument("--png", help="also write a tone-mapped sRGB PNG preview")
    ap.add_argument("--png-exposure", type=float, default=0.0, help="exposure (stops) of the PNG")
    a = ap.parse_args(argv)
    if a.samples < 1:
        fail("--samples must be >= 1")
    if a.passes < 1 or a.samples % a.passes:
        fail("--passes must be >= 1 and divide --samples")
    if a.bounces < 0:
        fail("--bounces must be >= 0")
    if a.tessellation < 1:
        fail("--tessellation must be >= 1")
    if not a.out.lower().endswith(".exr"):
        fail("--out must end in .exr")
    return a


# --------------------------------------------------------------------------- geometry


def mirroring(transform):
    """True if the transform's scale has an odd number of negative factors (FORMAT.md
    "Transform": the reader then reverses u so that the front stays where it was meant)."""
    if not transform or "scale" not in transform:
        return False
    s = transform["scale"]
    s = s if isinstance(s, list) else [s, s, s]
    return sum(1 for x in s if x < 0) % 2 == 1


def reverse_u(p):
    pts = [p.P(p.m - i, j) for j in range(p.n + 1) for i in range(p.m + 1)]
    return scenegeom.Patch(p.m, p.n, pts, p.name)


def is_planar_quad(p):
    if p.m != 1 or p.n != 1:
        return False
    pts = [p.P(0, 0), p.P(1, 0), p.P(1, 1), p.P(0, 1)]
    size = max(scenegeom.dist(a, b) for a in pts for b in pts)
    return scenegeom.quad_nonplanarity(pts) <= 1e-9 * size


def patch_faces(p, grid, verts, faces, uvs):
    """Append the patch's tessellation; every face is counter-clockwise seen from the front.
    `uvs` gets every vertex's (u, v) in the patch, for textures."""
    if is_planar_quad(p):
        grid = 1
    base = len(verts)
    for j in range(grid + 1):
        for i in range(grid + 1):
            verts.append(p.eval(i / grid, j / grid))
            uvs.append((i / grid, j / grid))

    def vid(i, j):
        return base + j * (grid + 1) + i

    for j in range(grid):
        for i in range(grid):
            # (u, v) corners in the order (0,0) (1,0) (1,1) (0,1): the face normal is then
            # along dP/du x dP/dv, the patch's front (collapsed edges give triangles).
            ring = [vid(i, j), vid(i + 1, j), vid(i + 1, j + 1), vid(i, j + 1)]
            uniq = []
            for k in ring:
                if all(scenegeom.dist(verts[k], verts[q]) > 0 for q in uniq):
                    uniq.append(k)
            if len(uniq) >= 3:
                faces.append(uniq)


# --------------------------------------------------------------------------- materials


def linear_texture(path, srgb):
    """The PNG as a float image of linear reflectance factors. Cycles keeps an 8-bit sRGB image
    in sRGB and decodes it after its bilinear interpolation, which darkens every blend between
    texels (the sRGB curve is convex: an 8 x 8 checker of codes 235 and 120 renders about 10 %
    darker); SphericalCover interpolates the decoded values (FORMAT.md), so the image is decoded
    here, once, and handed to Cycles as linear floats ("Non-Color": used as is)."""
    raw = bpy.data.images.load(path)
    raw.colorspace_settings.name = "Non-Color"  # the file's codes / (2^bits - 1)
    width, height = raw.size
    pixels = np.array(raw.pixels[:], dtype=np.float64).reshape(height, width, 4)
    if srgb:
        c = pixels[..., :3]
        pixels[..., :3] = np.where(c <= 0.04045, c / 12.92, ((c + 0.055) / 1.055) ** 2.4)
    image = bpy.data.images.new(os.path.basename(path) + "__linear", width, height, alpha=False,
                                float_buffer=True)
    image.colorspace_settings.name = "Non-Color"
    image.pixels = pixels.ravel().tolist()
    bpy.data.images.remove(raw)
    return image


def cycles_origin(name, path):
    """(roughness, colour) of a BRDF table that names its Cycles origin (see the docstring),
    after checking every row against that lobe; fails for a table without an origin or one
    that is not (or no longer) the lobe it names."""
    sys.path.insert(0, os.path.join(os.path.dirname(HERE), "brdf", "tools"))
    import make_ggx_table  # noqa: E402
    origin, rows = None, 0
    try:
        with open(path) as table:
            for number, line in enumerate(table, 1):
                line = line.strip()
                if line.startswith("#"):
                    origin = make_ggx_table.parse_origin(line) or origin
                    continue
                if not line or line.replace(" ", "").startswith("theta_in,"):
                    continue
                if origin is None:
                    fail("material '%s': %s names no Cycles origin (a '%s ...' comment before "
                         "its rows), so Cycles cannot render it" % (name, path,
                                                                    make_ggx_table.ORIGIN_PREFIX))
                ti, to, dp, *rgb = (float(x) for x in line.split(","))
                lobe = make_ggx_table.ggx(math.radians(ti), math.radians(to), math.radians(dp),
                                          origin[0])
                for value, c in zip(rgb, origin[1]):
                    if abs(value - c * lobe) > 1e-5 * c * lobe + 1e-9:
                        fail("material '%s': %s line %d: %g is not the GGX lobe of its origin "
                             "(%g)" % (name, path, number, value, c * lobe))
                rows += 1
    except (OSError, ValueError) as e:
        fail("material '%s': %s: %s" % (name, path, e))
    if origin is None or rows == 0:
        fail("material '%s': %s names no Cycles origin or has no rows" % (name, path))
    return origin


def make_material(name, mat, two_sided, folder):
    if mat["type"] not in ("diffuse", "tabulated"):
        fail("material '%s': type '%s' is not supported by this reference script (diffuse, and "
             "tabulated tables that name their Cycles origin)" % (name, mat["type"]))
    two_sided = two_sided or any(t > 0 for t in mat.get("transmittance", [0, 0, 0]))
    m = bpy.data.materials.new(name + ("__two_sided" if two_sided else ""))
    m.use_nodes = True
    nt = m.node_tree
    for n in list(nt.nodes):
        nt.nodes.remove(n)
    out = nt.nodes.new("ShaderNodeOutputMaterial")
    out.target = "CYCLES"
    if mat["type"] == "tabulated":
        path = mat["file"] if os.path.isabs(mat["file"]) else os.path.join(folder, mat["file"])
        roughness, colour = cycles_origin(name, path)
        # Cycles squares the node's Roughness (svm/closure.h), as make_ggx_table.ggx does.
        bsdf = nt.nodes.new("ShaderNodeBsdfGlossy")
        bsdf.distribution = "GGX"  # single scattering, not "MULTI_GGX"
        bsdf.inputs["Color"].default_value = (*colour, 1.0)
        bsdf.inputs["Roughness"].default_value = roughness
    else:
        bsdf = nt.nodes.new("ShaderNodeBsdfDiffuse")
        bsdf.inputs["Color"].default_value = (*mat["reflectance"], 1.0)
        bsdf.inputs["Roughness"].default_value = 0.0  # Lambert, not Oren-Nayar
    if "texture" in mat:
        path = mat["texture"] if os.path.isabs(mat["texture"]) else os.path.join(folder, mat["texture"])
        image = nt.nodes.new("ShaderNodeTexImage")
        image.image = linear_texture(path, mat.get("texture_encoding") != "linear")
        image.interpolation = "Linear"
        image.extension = "EXTEND"
        uv = nt.nodes.new("ShaderNodeUVMap")
        uv.uv_map = "UVMap"
        nt.links.new(uv.outputs["UV"], image.inputs["Vector"])
        multiply = nt.nodes.new("ShaderNodeMixRGB")
        multiply.blend_type = "MULTIPLY"
        multiply.inputs["Fac"].default_value = 1.0
        multiply.inputs["Color1"].default_value = (*mat["reflectance"], 1.0)
        nt.links.new(image.outputs["Color"], multiply.inputs["Color2"])
        nt.links.new(multiply.outputs["Color"], bsdf.inputs["Color"])
    front = bsdf.outputs["BSDF"]
    transmittance = mat.get("transmittance", [0.0, 0.0, 0.0])
    if any(t > 0 for t in transmittance):
        transparent = nt.nodes.new("ShaderNodeBsdfTransparent")
        transparent.inputs["Color"].default_value = (*transmittance, 1.0)
        both = nt.nodes.new("ShaderNodeAddShader")
        nt.links.new(front, both.inputs[0])
        nt.links.new(transparent.outputs["BSDF"], both.inputs[1])
        front = both.outputs["Shader"]
    emission = mat.get("emission", [0.0, 0.0, 0.0])
    if any(e > 0 for e in emission):
        em = nt.nodes.new("ShaderNodeEmission")
        em.inputs["Color"].default_value = (*emission, 1.0)
        em.inputs["Strength"].default_value = 1.0
        add = nt.nodes.new("ShaderNodeAddShader")
        nt.links.new(front, add.inputs[0])
        nt.links.new(em.outputs["Emission"], add.inputs[1])
        front = add.outputs["Shader"]
        m.cycles.sample_as_light = True
    if two_sided:
        nt.links.new(front, out.inputs["Surface"])
    else:
        # Back side: the Mix shader's second input is left unconnected, an empty closure,
        # so the back neither reflects nor emits (and still blocks rays).
        geo = nt.nodes.new("ShaderNodeNewGeometry")
        mix = nt.nodes.new("ShaderNodeMixShader")
        nt.links.new(geo.outputs["Backfacing"], mix.inputs["Fac"])
        nt.links.new(front, mix.inputs[1])
        nt.links.new(mix.outputs["Shader"], out.inputs["Surface"])
    return m


# --------------------------------------------------------------------------- scene


def build(args):
    try:
        with open(args.scene) as f:
            raw = json.load(f)
        for k, entry in enumerate(raw.get("surfaces", [])):
            if entry.get("type") == "mesh" and not entry.get("file", "").lower().endswith(".obj"):
                fail("%s: /surfaces/%d/file: only OBJ meshes are read by this script"
                     % (args.scene, k))
        scene_json, patches = scenegeom.load_scene(args.scene)
    except (OSError, ValueError, KeyError, TypeError, IndexError, AssertionError) as e:
        fail("%s: cannot read the scene: %s" % (args.scene, e))

    # Start from an empty file (factory startup has a cube, a lamp and a camera).
    for obj in list(bpy.data.objects):
        bpy.data.objects.remove(obj, do_unlink=True)
    scene = bpy.context.scene

    materials = {}
    lo = [math.inf] * 3
    hi = [-math.inf] * 3
    n_faces = 0
    for k, entry in enumerate(scene_json["surfaces"]):
        two_sided = bool(entry.get("two_sided", False))
        key = (entry["material"], two_sided)
        if key not in materials:
            materials[key] = make_material(entry["material"],
                                           scene_json["materials"][entry["material"]], two_sided,
                                           os.path.dirname(os.path.abspath(args.scene)))
        verts, faces, uvs = [], [], []
        for kk, name, p in patches:
            if kk != k:
                continue
            if mirroring(entry.get("transform")):
                p = reverse_u(p)
            patch_faces(p, args.tessellation, verts, faces, uvs)
        for v in verts:
            for c in range(3):
                lo[c] = min(lo[c], v[c])
                hi[c] = max(hi[c], v[c])
        mesh = bpy.data.meshes.new(entry["name"])
        mesh.from_pydata(verts, [], faces)
        mesh.validate()
        uv_layer = mesh.uv_layers.new(name="UVMap")
        for loop in mesh.loops:
            uv_layer.data[loop.index].uv = uvs[loop.vertex_index]
        mesh.materials.append(materials[key])
        for poly in mesh.polygons:
            poly.use_smooth = False  # geometric normals: Backfacing is exact
        obj = bpy.data.objects.new(entry["name"], mesh)
        scene.collection.objects.link(obj)
        n_faces += len(faces)
    size = max(h - l for l, h in zip(lo, hi))

    # Camera (VTK convention: eye, focal point, view up, vertical view angle in degrees).
    cams = scene_json.get("cameras", [])
    if not cams:
        fail("%s: the scene has no camera" % args.scene)
    if args.camera:
        found = [c for c in cams if c["name"] == args.camera]
        if not found:
            fail("%s: no camera named '%s'" % (args.scene, args.camera))
        cam = found[0]
    else:
        cam = cams[0]
    eye = mathutils.Vector(cam["position"])
    d = (mathutils.Vector(cam["focal_point"]) - eye).normalized()
    right = d.cross(mathutils.Vector(cam["view_up"]))
    if right.length < 1e-9:
        fail("camera '%s': view_up is parallel to the view direction" % cam["name"])
    right.normalize()
    up = right.cross(d)
    # Blender cameras look along their local -Z with local +Y up.
    rot = mathutils.Matrix((right, up, -d)).transposed()
    cam_data = bpy.data.cameras.new("camera")
    cam_data.type = "PERSP"
    cam_data.sensor_fit = "VERTICAL"
    cam_data.angle_y = math.radians(cam["view_angle"])
    cam_data.shift_x = cam_data.shift_y = 0.0
    dist_far = (eye - mathutils.Vector([(l + h) / 2 for l, h in zip(lo, hi)])).length + size
    cam_data.clip_start = 1e-5 * size
    cam_data.clip_end = 10 * dist_far
    cam_obj = bpy.data.objects.new("camera", cam_data)
    cam_obj.matrix_world = mathutils.Matrix.Translation(eye) @ rot.to_4x4()
    scene.collection.objects.link(cam_obj)
    scene.camera = cam_obj

    # Black world.
    world = bpy.data.worlds.new("black")
    world.use_nodes = True
    bg = world.node_tree.nodes["Background"]
    bg.inputs["Color"].default_value = (0, 0, 0, 1)
    bg.inputs["Strength"].default_value = 0.0
    scene.world = world

    r = scene.render
    r.engine = "CYCLES"
    r.resolution_x = args.width or cam["width"]
    r.resolution_y = args.height or cam["height"]
    r.resolution_percentage = 100
    r.pixel_aspect_x = r.pixel_aspect_y = 1.0
    r.use_border = False
    r.film_transparent = False
    r.use_persistent_data = False
    if args.threads > 0:
        r.threads_mode = "FIXED"
        r.threads = args.threads
    c = scene.cycles
    c.device = "CPU"
    c.feature_set = "SUPPORTED"
    c.samples = args.samples
    c.seed = args.seed
    c.use_animated_seed = False
    c.use_adaptive_sampling = False
    c.use_denoising = False
    c.use_guiding = False
    c.light_sampling_threshold = 0.0
    c.sample_clamp_direct = 0.0
    c.sample_clamp_indirect = 0.0
    c.blur_glossy = 0.0
    c.caustics_reflective = True
    c.caustics_refractive = True
    c.max_bounces = args.bounces
    c.diffuse_bounces = args.bounces
    # Glossy bounces as many as diffuse ones (a glossy floor reflects the lit room, and the
    # room the floor); a diffuse scene has no glossy closure, so its images do not change.
    c.glossy_bounces = args.bounces
    c.transmission_bounces = 0
    c.volume_bounces = 0
    # Panes (Transparent BSDF): a path goes on through as many as SphericalCover's renderer
    # does (RadianceRenderer::MaxPanesPerSample); with 0 every pane would be opaque to paths
    # and to shadow rays alike.
    c.transparent_max_bounces = 8
    c.min_light_bounces = 0
    c.use_fast_gi = False
    c.pixel_filter_type = "BOX"
    c.filter_width = args.filter_width
    c.film_exposure = 1.0  # a factor: 1 leaves the radiance unscaled
    scene.view_layers[0].cycles.use_denoising = False
    vs = scene.view_settings
    vs.view_transform = "Standard"
    vs.look = "None"
    vs.exposure = 0.0
    vs.gamma = 1.0
    vs.use_curve_mapping = False
    scene.sequencer_colorspace_settings.name = "Linear"
    im = r.image_settings
    im.file_format = "OPEN_EXR"
    im.color_depth = "32"
    im.color_mode = "RGB"
    im.exr_codec = "ZIP"
    r.use_file_extension = False
    r.use_compositing = False
    r.use_sequencer = False
    return cam, n_faces


def read_exr(path):
    """Linear RGB of an EXR as float32 (height, width, 3), Blender's bottom-up row order."""
    img = bpy.data.images.load(path, check_existing=False)
    img.colorspace_settings.name = "Non-Color"  # the file's numbers, no conversion
    w, h = img.size
    px = np.empty(w * h * 4, dtype=np.float32)
    img.pixels.foreach_get(px)
    bpy.data.images.remove(img)
    return px.reshape(h, w, 4)[:, :, :3].copy()


def write_exr(path, rgb, scene):
    """Write float RGB (bottom-up rows) as a 32-bit float OpenEXR through a temporary file."""
    h, w, _ = rgb.shape
    img = bpy.data.images.new("mean", w, h, alpha=False, float_buffer=True)
    img.colorspace_settings.name = "Non-Color"
    rgba = np.ones((h, w, 4), dtype=np.float32)
    rgba[:, :, :3] = rgb
    img.pixels.foreach_set(rgba.ravel())
    tmp = path[:-4] + ".partial.exr"
    img.save_render(tmp, scene=scene)
    bpy.data.images.remove(img)
    back = read_exr(tmp)
    if not np.array_equal(back, rgb.astype(np.float32)):
        fail("the EXR written to %s does not read back bit-exact" % tmp)
    os.replace(tmp, path)


def block_noise(passes, block=16):
    """Relative standard error of the block means of the average of the passes, estimated
    from their spread: RMS over blocks and channels of std_k(block mean) / sqrt(K) / mean."""
    k = len(passes)
    h, w, _ = passes[0].shape
    if k < 2 or h % block or w % block:
        return None
    b = np.stack([p.astype(np.float64).reshape(h // block, block, w // block, block, 3)
                  .mean(axis=(1, 3)) for p in passes])
    mean = b.mean(axis=0)
    se = b.std(axis=0, ddof=1) / math.sqrt(k)
    mask = mean > 1e-3 * mean.reshape(-1, 3).mean(axis=0)
    return float(np.sqrt(np.mean((se[mask] / mean[mask]) ** 2)))


def main():
    args = parse_args()
    cam, n_faces = build(args)
    scene = bpy.context.scene
    r = scene.render
    per_pass = args.samples // args.passes
    print("render_cycles: Blender %s, camera '%s', %dx%d, %d spp as %d passes of %d (seeds %d..%d), "
          "%d bounces, %d faces" % (bpy.app.version_string, cam["name"], r.resolution_x,
                                    r.resolution_y, args.samples, args.passes, per_pass, args.seed,
                                    args.seed + args.passes - 1, args.bounces, n_faces),
          flush=True)
    out = os.path.abspath(args.out)
    scene.cycles.samples = per_pass
    passes = []
    t0 = time.time()
    for k in range(args.passes):
        scene.cycles.seed = args.seed + k
        tmp = out[:-4] + ".pass%d.partial.exr" % k
        r.filepath = tmp
        bpy.ops.render.render(write_still=True)
        if not os.path.isfile(tmp):
            fail("Cycles wrote no image")
        passes.append(read_exr(tmp))
        os.remove(tmp)
        print("render_cycles: pass %d/%d done after %.1f s" % (k + 1, args.passes, time.time() - t0),
              flush=True)
    seconds = time.time() - t0
    mean = passes[0] if args.passes == 1 else \
        (np.sum(np.stack([p.astype(np.float64) for p in passes]), axis=0) / args.passes).astype(np.float32)
    write_exr(out, mean, scene)
    print("render_cycles: wrote %s, render time %.1f s" % (out, seconds), flush=True)
    noise = block_noise(passes)
    if noise is not None:
        print("render_cycles: relative standard error of the 16x16 block means of the result, "
              "from the spread of the %d passes: %.5f" % (args.passes, noise), flush=True)
    if args.png:
        # Display-referred preview only: sRGB transfer (view transform Standard) after exposure.
        h, w, _ = mean.shape
        img = bpy.data.images.new("preview", w, h, alpha=False, float_buffer=True)
        img.colorspace_settings.name = "Linear"
        rgba = np.ones((h, w, 4), dtype=np.float32)
        rgba[:, :, :3] = mean
        img.pixels.foreach_set(rgba.ravel())
        scene.view_settings.exposure = args.png_exposure
        im = scene.render.image_settings
        im.file_format = "PNG"
        im.color_depth = "8"
        im.color_mode = "RGB"
        png = os.path.abspath(args.png)
        tmp_png = png + ".partial.png"
        img.save_render(tmp_png, scene=scene)
        os.replace(tmp_png, png)
        print("render_cycles: wrote %s" % png, flush=True)


if __name__ == "__main__":
    main()
