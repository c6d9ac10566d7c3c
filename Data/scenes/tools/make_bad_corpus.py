#!/usr/bin/env python3
"""Regenerate the bad-input corpus Testing/Data/bad/ and its expected.json.

    python3 Data/scenes/tools/make_bad_corpus.py

Every corpus file is a small valid input (support/base.scene, or a valid one-patch .bpt) with
exactly ONE thing broken, so the loader's first and only error is the one expected.
expected.json maps each corpus file name to the substrings its error message must contain:
[file base name, location, problem phrase]. The loader prints  <path>: <location>: <problem>
where <location> is "line L, column C" (JSON syntax), "line L" (.bpt) or an RFC 6901 JSON
pointer (scene semantics). See Testing/Data/README.md and Data/scenes/FORMAT.md.

Plain python3, no third-party packages. Files are written byte for byte (LF unless a case says
otherwise), so re-running reproduces the committed corpus exactly.
"""

import copy
import json
import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)

from scenegeom import dumps, png_chunk, png_file  # noqa: E402

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(HERE)))
BAD = os.path.join(ROOT, "Testing", "Data", "bad")
SUPPORT = os.path.join(BAD, "support")

# A valid scene every bad scene is derived from (also written as support/base.scene, so a test
# can check that the base itself loads).
BASE = {
    "version": 1,
    "materials": {
        "white": {"type": "diffuse", "reflectance": [0.5, 0.5, 0.5]},
        "lamp": {"type": "diffuse", "reflectance": [0.5, 0.5, 0.5], "emission": [1, 1, 1]},
        "glossy": {"type": "phong", "diffuse": [0.4, 0.4, 0.4], "specular": [0.3, 0.3, 0.3], "exponent": 20},
    },
    "surfaces": [
        {"name": "floor", "type": "bilinear", "material": "white",
         "points": [[0, 0, 0], [0, 0, 1], [1, 0, 1], [1, 0, 0]]},
        {"name": "light", "type": "bilinear", "material": "lamp", "two_sided": False,
         "points": [[0, 1, 0], [1, 1, 0], [1, 1, 1], [0, 1, 1]],
         "transform": {"scale": 1, "rotate": [0, 0, 0], "translate": [0, 0.5, 0]}},
        {"name": "cap", "type": "bezier", "degree": [2, 1], "material": "glossy",
         "points": [[0, 0.2, 0], [0.5, 0.6, 0], [1, 0.2, 0], [0, 0.2, 1], [0.5, 0.6, 1], [1, 0.2, 1]]},
    ],
    "cameras": [{"name": "main", "position": [0.5, 0.5, -2], "focal_point": [0.5, 0.5, 0.5],
                 "view_up": [0, 1, 0], "view_angle": 40, "width": 64, "height": 48}],
    "settings": {"theta_bins": 8, "phi_bins": 16, "max_level": 2, "tolerance": 0.05},
}

BASE_TEXT = dumps(BASE) + "\n"

# One valid bicubic patch (a gently curved square), 16 lines "x y z", u fastest.
PATCH_LINES = ["%g %g %g" % (i, j, 0.25 * ((i - 1.5) ** 2 + (j - 1.5) ** 2) / 2.25)
               for j in range(4) for i in range(4)]
VALID_BPT = "1\n3 3\n" + "\n".join(PATCH_LINES) + "\n"

CASES = []  # (file name, bytes, [substrings])


def scene_case(name, mutate, location, phrase):
    s = copy.deepcopy(BASE)
    mutate(s)
    CASES.append((name, (dumps(s) + "\n").encode(), [name, location, phrase]))


def raw_case(name, text, location, phrase, basename=None):
    data = text.encode() if isinstance(text, str) else text
    CASES.append((name, data, [basename or name, location, phrase]))


def line_of(text, needle, occurrence=1):
    """1-based line number of the line containing the given occurrence of needle."""
    pos = -1
    for _ in range(occurrence):
        pos = text.index(needle, pos + 1)
    return text.count("\n", 0, pos) + 1


# --------------------------------------------------------------------------- JSON syntax


def json_syntax_cases():
    raw_case("empty.scene", "", "line 1, column 1", "JSON syntax error")
    raw_case("not_json.scene",
             '<scene version="3.0.0">\n    <shape type="obj">\n        <string name="filename" value="cbox.obj"/>\n'
             "    </shape>\n</scene>\n", "line 1, column 1", "JSON syntax error")
    # Cut in the middle of the surfaces array, at the end of a line; no final newline, so the
    # end of the file is unambiguously on the last line, one column past its last character.
    lines = BASE_TEXT.split("\n")
    cut = next(i for i, l in enumerate(lines) if l.strip() == '"name": "light",')
    text = "\n".join(lines[:cut + 1])
    raw_case("truncated.scene", text, "line %d, column %d" % (cut + 1, len(lines[cut]) + 1), "JSON syntax error")
    # A trailing comma after the last surface: the error is at the "]" that follows it.
    t = BASE_TEXT
    i = t.index('  ],\n  "cameras"')
    j = t.rindex("}", 0, i)
    text = t[:j + 1] + "," + t[j + 1:]
    ln = line_of(text, '  ],\n  "cameras"')
    raw_case("trailing_comma.scene", text, "line %d, column 3" % ln, "JSON syntax error")
    # A // comment (JSON has none): the error is at the "/".
    text = BASE_TEXT.replace('  "materials": {', '  // materials follow\n  "materials": {', 1)
    raw_case("comment.scene", text, "line %d, column 3" % line_of(text, "// materials"), "JSON syntax error")
    # NaN is not a JSON literal.
    text = BASE_TEXT.replace('"points": [[0, 0, 0], [0, 0, 1]', '"points": [[0, NaN, 0], [0, 0, 1]', 1)
    ln = line_of(text, "NaN")
    col = text.split("\n")[ln - 1].index("NaN") + 1
    raw_case("nan_literal.scene", text, "line %d, column %d" % (ln, col), "JSON syntax error")


# --------------------------------------------------------------------------- scene semantics


def set_in(path, value):
    def f(s):
        node = s
        for k in path[:-1]:
            node = node[k]
        node[path[-1]] = value
    return f


def del_in(path):
    def f(s):
        node = s
        for k in path[:-1]:
            node = node[k]
        del node[path[-1]]
    return f


def semantic_cases():
    scene_case("version_2.scene", set_in(["version"], 2), "/version", "unsupported version")

    def with_unit(unit):
        # "unit" right after "version", where a scene writes it (the order of dumps' keys).
        def f(s):
            items = list(s.items())
            s.clear()
            s.update([items[0], ("unit", unit)] + items[1:])
        return f
    scene_case("unit_unknown.scene", with_unit("furlong"), "/unit",
               "unknown length unit 'furlong' (expected one of mm, cm, dm, m, km, in, ft, yd)")
    scene_case("unit_not_string.scene", with_unit(1000), "/unit", "expected a string")

    def rename_settings(s):
        s["setings"] = s.pop("settings")
    scene_case("unknown_top_key.scene", rename_settings, "/setings", "unknown key 'setings'")

    def typo_reflectance(s):
        s["materials"]["white"]["reflectence"] = [0.5, 0.5, 0.5]  # next to the correct key
    scene_case("unknown_key.scene", typo_reflectance, "/materials/white/reflectence", "unknown key 'reflectence'")

    def typo_two_sided(s):
        del s["surfaces"][1]["two_sided"]
        s["surfaces"][1]["two_side"] = True
    scene_case("unknown_key_surface.scene", typo_two_sided, "/surfaces/1/two_side", "unknown key 'two_side'")

    scene_case("unknown_surface_type.scene", set_in(["surfaces", 0, "type"], "nurbs"),
               "/surfaces/0/type", "unknown surface type 'nurbs'")
    scene_case("unknown_material_type.scene", set_in(["materials", "white", "type"], "lambert"),
               "/materials/white/type", "unknown material type 'lambert'")
    scene_case("unknown_material.scene", set_in(["surfaces", 1, "material"], "lmap"),
               "/surfaces/1/material", "unknown material 'lmap'")

    scene_case("bilinear_3_points.scene", set_in(["surfaces", 0, "points"], [[0, 0, 0], [0, 0, 1], [1, 0, 1]]),
               "/surfaces/0/points", "expected 4 points, got 3")
    scene_case("bezier_7_points.scene",
               lambda s: s["surfaces"][2]["points"].append([0.5, 0.2, 2]),
               "/surfaces/2/points", "expected 6 points, got 7")

    def degree_16(s):
        s["surfaces"][2]["degree"] = [2, 16]
        s["surfaces"][2]["points"] = [[i * 0.5, 0.2, j / 16.0] for j in range(17) for i in range(3)]
    scene_case("bezier_degree_16.scene", degree_16, "/surfaces/2/degree/1", "degree must be in [1, 15]")

    scene_case("string_for_number.scene", set_in(["materials", "white", "reflectance"], [0.5, "0.5", 0.5]),
               "/materials/white/reflectance/1", "expected a number")
    scene_case("number_for_array.scene", set_in(["materials", "white", "reflectance"], 0.5),
               "/materials/white/reflectance", "expected an array of 3 numbers")
    scene_case("point_two_coordinates.scene", set_in(["surfaces", 1, "points", 1], [1, 1]),
               "/surfaces/1/points/1", "expected an array of 3 numbers")
    scene_case("rotate_two_numbers.scene", set_in(["surfaces", 1, "transform", "rotate"], [0, 90]),
               "/surfaces/1/transform/rotate", "expected an array of 3 numbers")
    scene_case("object_for_string.scene", set_in(["surfaces", 0, "material"], {"name": "white"}),
               "/surfaces/0/material", "expected a string")
    scene_case("string_for_object.scene", set_in(["materials", "white"], "diffuse"),
               "/materials/white", "expected an object")
    scene_case("float_for_integer.scene", set_in(["settings", "theta_bins"], 8.5),
               "/settings/theta_bins", "expected an integer")
    scene_case("string_for_boolean.scene", set_in(["surfaces", 1, "two_sided"], "yes"),
               "/surfaces/1/two_sided", "expected a boolean")

    # 1e999 overflows a double: JSON has no NaN/Inf literal, this is how an infinity gets in.
    s = copy.deepcopy(BASE)
    text = dumps(s) + "\n"
    text = text.replace('"points": [[0, 0, 0], [0, 0, 1], [1, 0, 1], [1, 0, 0]]',
                        '"points": [[0, 0, 0], [0, 0, 1], [1, 1e999, 1], [1, 0, 0]]', 1)
    assert "1e999" in text
    raw_case("inf_coordinate.scene", text, "/surfaces/0/points/2/1", "not a finite number")

    scene_case("negative_reflectance.scene", set_in(["materials", "white", "reflectance"], [-0.1, 0.5, 0.5]),
               "/materials/white/reflectance/0", "must be in [0, 1]")
    scene_case("reflectance_above_one.scene", set_in(["materials", "white", "reflectance"], [0.5, 1.2, 0.5]),
               "/materials/white/reflectance/1", "must be in [0, 1]")

    def escaped_name(s):
        m = s["materials"].pop("white")
        m["reflectance"] = [0.5, 0.5, 1.5]
        s["materials"]["white/matte~2"] = m
        s["surfaces"][0]["material"] = "white/matte~2"
    scene_case("pointer_escaping.scene", escaped_name, "/materials/white~1matte~02/reflectance/2", "must be in [0, 1]")

    scene_case("negative_emission.scene", set_in(["materials", "lamp", "emission"], [1, -1, 1]),
               "/materials/lamp/emission/1", "must be >= 0")
    scene_case("negative_exponent.scene", set_in(["materials", "glossy", "exponent"], -1),
               "/materials/glossy/exponent", "must be >= 0")

    def phong_sum(s):
        s["materials"]["glossy"]["diffuse"] = [0.7, 0.4, 0.4]
        s["materials"]["glossy"]["specular"] = [0.4, 0.3, 0.3]
    scene_case("phong_sum_above_one.scene", phong_sum, "/materials/glossy", "diffuse + specular exceeds 1")

    scene_case("no_surfaces.scene", set_in(["surfaces"], []), "/surfaces", "scene has no surfaces")
    scene_case("degenerate_patch.scene", set_in(["surfaces", 0, "points"], [[0.5, 0, 0.5]] * 4),
               "/surfaces/0/points", "degenerate patch")
    scene_case("missing_points.scene", del_in(["surfaces", 0, "points"]), "/surfaces/0", "missing key 'points'")
    scene_case("missing_camera_key.scene", del_in(["cameras", 0, "view_up"]), "/cameras/0", "missing key 'view_up'")
    scene_case("duplicate_surface_name.scene", set_in(["surfaces", 2, "name"], "floor"),
               "/surfaces/2/name", "duplicate surface name 'floor'")
    scene_case("view_angle_zero.scene", set_in(["cameras", 0, "view_angle"], 0),
               "/cameras/0/view_angle", "must be in (0, 180)")
    scene_case("view_angle_180.scene", set_in(["cameras", 0, "view_angle"], 180),
               "/cameras/0/view_angle", "must be in (0, 180)")
    scene_case("negative_width.scene", set_in(["cameras", 0, "width"], -5),
               "/cameras/0/width", "must be a positive integer")
    scene_case("zero_theta_bins.scene", set_in(["settings", "theta_bins"], 0),
               "/settings/theta_bins", "must be a positive integer")
    scene_case("negative_max_level.scene", set_in(["settings", "max_level"], -1),
               "/settings/max_level", "must be >= 0")

    def add_surface(entry):
        return lambda s: s["surfaces"].append(entry)
    scene_case("missing_bpt.scene",
               add_surface({"name": "pot", "type": "bpt", "material": "white", "file": "no_such_model.bpt"}),
               "/surfaces/3/file", "cannot open file")
    scene_case("missing_mesh.scene",
               add_surface({"name": "part", "type": "mesh", "material": "white", "file": "no_such_mesh.obj"}),
               "/surfaces/3/file", "cannot open file")

    def missing_brdf(s):
        s["materials"]["table"] = {"type": "tabulated", "file": "no_such_brdf.csv"}
        s["surfaces"][2]["material"] = "table"
    scene_case("missing_brdf.scene", missing_brdf, "/materials/table/file", "cannot open file")

    scene_case("mesh_pentagon.scene",
               add_surface({"name": "part", "type": "mesh", "material": "white", "file": "support/pentagon.obj"}),
               "/surfaces/3/file", "only triangles and quads are supported")

    # An error inside a .bpt read through a scene: the message names the .bpt and its line.
    scene_case("bpt_error_in_scene.scene",
               add_surface({"name": "pot", "type": "bpt", "material": "white", "file": "support/nan_patch.bpt"}),
               "line 7", "not a finite number")
    CASES[-1][2][0] = "nan_patch.bpt"

    # Errors inside a BRDF table read through a scene: the message names the table and its line.
    def with_table(file):
        def f(s):
            s["materials"]["table"] = {"type": "tabulated", "file": file}
            s["surfaces"][2]["material"] = "table"
        return f
    scene_case("brdf_negative_value.scene", with_table("support/negative.brdf.csv"),
               "line 4", "BRDF values must be >= 0")
    CASES[-1][2][0] = "negative.brdf.csv"
    scene_case("brdf_missing_point.scene", with_table("support/incomplete.brdf.csv"),
               "line 5", "missing grid point theta_in = 90, theta_out = 90, delta_phi = 0")
    CASES[-1][2][0] = "incomplete.brdf.csv"
    scene_case("brdf_bad_header.scene", with_table("support/bad_header.brdf.csv"),
               "line 2", "expected the header 'theta_in,theta_out,delta_phi,r,g,b'")
    CASES[-1][2][0] = "bad_header.brdf.csv"

    # Panes and textures (paper §5.4; FORMAT.md "materials").
    scene_case("transmittance_negative.scene", set_in(["materials", "white", "transmittance"], [0.2, -0.1, 0.2]),
               "/materials/white/transmittance/1", "must be in [0, 1]")
    scene_case("transmittance_not_array.scene", set_in(["materials", "white", "transmittance"], "clear"),
               "/materials/white/transmittance", "expected an array of 3 numbers")
    scene_case("transmittance_sum_above_one.scene", set_in(["materials", "white", "transmittance"], [0.5, 0.6, 0.5]),
               "/materials/white", "reflectance + transmittance exceeds 1 in band 1")
    scene_case("transmittance_phong_sum_above_one.scene",
               set_in(["materials", "glossy", "transmittance"], [0.2, 0.2, 0.4]),
               "/materials/glossy", "diffuse + specular + transmittance exceeds 1 in band 2")

    def textured(file, encoding=None):
        def f(s):
            s["materials"]["white"]["texture"] = file
            if encoding is not None:
                s["materials"]["white"]["texture_encoding"] = encoding
        return f
    scene_case("texture_missing.scene", textured("no_such_texture.png"),
               "/materials/white/texture", "cannot open file")
    scene_case("texture_not_string.scene", textured(7), "/materials/white/texture", "expected a string")
    scene_case("texture_bad_encoding.scene", textured("support/grey_ramp.png", "gamma"),
               "/materials/white/texture_encoding", "unknown texture encoding 'gamma' (expected srgb or linear)")
    scene_case("texture_encoding_without_texture.scene",
               set_in(["materials", "white", "texture_encoding"], "linear"),
               "/materials/white/texture_encoding", "texture_encoding without a texture")
    scene_case("texture_on_mirror.scene",
               lambda s: s["materials"].update({"chrome": {"type": "mirror", "reflectance": [0.9, 0.9, 0.9],
                                                           "texture": "support/grey_ramp.png"}}),
               "/materials/chrome/texture", "unknown key 'texture'")
    # Errors inside the image: the message names the PNG after the material's texture pointer.
    for case, file, phrase in [
            ("texture_not_png.scene", "not_png.png", "not a PNG file"),
            ("texture_truncated.scene", "truncated.png", "corrupt PNG file"),
            ("texture_bad_crc.scene", "bad_crc.png", "corrupt PNG file"),
            ("texture_palette.scene", "palette.png", "expected an 8- or 16-bit grey or RGB PNG, got a palette image"),
            ("texture_alpha.scene", "rgba.png", "expected an 8- or 16-bit grey or RGB PNG, got an RGB image with alpha"),
            ("texture_4_bit.scene", "grey_4bit.png", "expected an 8- or 16-bit grey or RGB PNG, got 4 bits per sample"),
            ("texture_huge.scene", "huge.png", "image too large: 100000 x 100000")]:
        scene_case(case, textured("support/" + file), "/materials/white/texture", phrase)
        CASES[-1][2][1] = file


# --------------------------------------------------------------------------- .bpt


def bpt_cases():
    # Truncated after 10 of 16 points, no final newline: the end of the file is on line 12.
    text = "1\n3 3\n" + "\n".join(PATCH_LINES[:10])
    raw_case("bpt_truncated.bpt", text, "line 12", "unexpected end of file")
    # Claims 999999999 patches, holds one: must fail at the end of the data, not allocate.
    text = "999999999\n3 3\n" + "\n".join(PATCH_LINES)
    raw_case("bpt_huge_count.bpt", text, "line 18", "unexpected end of file")
    raw_case("bpt_empty.bpt", "", "line 1", "unexpected end of file")
    # Degree 100 (with all its 101 x 4 points, so nothing else is wrong).
    pts = ["%g %g 0" % (i / 100.0, j / 3.0) for j in range(4) for i in range(101)]
    raw_case("bpt_degree_100.bpt", "1\n100 3\n" + "\n".join(pts) + "\n", "line 2", "degree must be in [1, 15]")
    pts = ["0 %g 0" % (j / 3.0) for j in range(4)]
    raw_case("bpt_degree_0.bpt", "1\n0 3\n" + "\n".join(pts) + "\n", "line 2", "degree must be in [1, 15]")
    raw_case("bpt_float_degree.bpt", VALID_BPT.replace("\n3 3\n", "\n3.0 3\n", 1), "line 2", "expected an integer")
    lines = VALID_BPT.split("\n")
    lines[6] = "1 nan 0"    # file line 7
    raw_case("bpt_nan.bpt", "\n".join(lines), "line 7", "not a finite number")
    lines = VALID_BPT.split("\n")
    lines[10] = "2 1 inf"   # file line 11
    raw_case("bpt_inf.bpt", "\n".join(lines), "line 11", "not a finite number")
    # CRLF line endings (as in the GeoNum files): "\r\n" is one line break.
    lines = VALID_BPT.split("\n")
    lines[4] = "abc 2 0"    # file line 5
    raw_case("bpt_bad_token_crlf.bpt", "\r\n".join(lines), "line 5", "expected a number")
    raw_case("bpt_trailing_garbage.bpt", VALID_BPT + "end of teapot\n", "line 19", "unexpected data after the last patch")


# --------------------------------------------------------------------------- hostile inputs


def support(name, data):
    os.makedirs(SUPPORT, exist_ok=True)
    with open(os.path.join(SUPPORT, name), "wb") as f:
        f.write(data if isinstance(data, bytes) else data.encode())


def hostile_cases():
    """Files that are not what they claim, bytes JSON allows but a scene must not hold, sizes
    that overflow: each fails with one short line (Data/scenes/FORMAT.md, Errors)."""
    def add_surface(entry):
        return lambda s: s["surfaces"].append(entry)

    def with_table(file):
        def f(s):
            s["materials"]["table"] = {"type": "tabulated", "file": file}
            s["surfaces"][2]["material"] = "table"
        return f

    def named(case, base):
        CASES[-1][2][0] = base

    # Files that are not regular files (a directory is the only kind git can hold).
    for kind, entry in [("bpt", {"name": "pot", "type": "bpt", "material": "white"}),
                        ("mesh", {"name": "part", "type": "mesh", "material": "white"})]:
        scene_case("%s_file_is_directory.scene" % kind, add_surface(dict(entry, file="support")),
                   "/surfaces/3/file", "is a directory")
        scene_case("%s_file_is_device.scene" % kind, add_surface(dict(entry, file="/dev/zero")),
                   "/surfaces/3/file", "not a regular file (a device)")
    scene_case("brdf_file_is_directory.scene", with_table("support"), "/materials/table/file", "is a directory")
    scene_case("brdf_file_is_device.scene", with_table("/dev/zero"), "/materials/table/file",
               "not a regular file (a device)")

    # BRDF tables: 450 scattered rows imply a 450^3 grid; duplicates; a NUL byte.
    rows = ["%g,%g,%g,0.1,0.1,0.1" % (i * 0.2, i * 0.19, i * 0.4) for i in range(450)]
    support("scattered.brdf.csv", "theta_in,theta_out,delta_phi,r,g,b\n" + "\n".join(rows) + "\n")
    scene_case("brdf_scattered_rows.scene", with_table("support/scattered.brdf.csv"),
               "line 451", "450 x 450 x 450 values, 450 rows")
    named(None, "scattered.brdf.csv")
    header = "theta_in,theta_out,delta_phi,r,g,b\n"
    support("duplicate.brdf.csv", header + "0,0,0,0.1,0.1,0.1\n0,0,0,0.2,0.1,0.1\n")
    scene_case("brdf_duplicate_point.scene", with_table("support/duplicate.brdf.csv"),
               "line 3", "duplicate grid point (first given on line 2)")
    named(None, "duplicate.brdf.csv")
    support("nul.brdf.csv", header + "0,0,0,0.1\x00,0.1,0.1\n")
    scene_case("brdf_nul_byte.scene", with_table("support/nul.brdf.csv"), "line 2", "NUL byte")
    named(None, "nul.brdf.csv")

    # NUL bytes and control characters.
    raw_case("bpt_nul_byte.bpt", VALID_BPT.replace("\n0 1 ", "\n0\x00 1 ", 1), "line 7", "NUL byte")
    raw_case("bpt_nul_in_count.bpt", "1\x00garbage" + VALID_BPT[1:], "line 1", "NUL byte")

    def rename_material(new):
        def f(s):
            s["materials"][new] = s["materials"].pop("glossy")
            s["surfaces"][2]["material"] = new
        return f
    scene_case("nul_in_key.scene", rename_material("glo\u0000ssy"), "/materials/glo\\x00ssy",
               "NUL character (\\u0000) in a key")
    scene_case("nul_in_string.scene", set_in(["surfaces", 0, "name"], "floor\u0000"),
               "/surfaces/0/name", "NUL character (\\u0000) in a string")
    scene_case("nul_in_file_path.scene",
               add_surface({"name": "pot", "type": "bpt", "material": "white", "file": "support/base.bpt\u0000.txt"}),
               "/surfaces/3/file", "NUL character")
    text = BASE_TEXT.replace('"version": 1', '"version": 1\x00', 1)
    raw_case("raw_nul_byte.scene", text, "line 2, column 15", "JSON syntax error")
    text = BASE_TEXT.replace('"name": "floor"', '"name": "fl\x00oor"', 1)
    ln = line_of(text, "fl\x00oor")
    raw_case("raw_nul_in_string.scene", text, "line %d" % ln, "must be escaped")
    scene_case("newline_in_material_name.scene", set_in(["surfaces", 1, "material"], "la\nmp"),
               "/surfaces/1/material", "unknown material 'la\\nmp'")

    # Duplicate keys: nlohmann would keep the last one silently.
    def duplicate(name, old, new, location, key):
        assert old in BASE_TEXT, old
        raw_case(name, BASE_TEXT.replace(old, new, 1), location, "duplicate key '%s'" % key)
    duplicate("duplicate_top_key.scene", '"version": 1,', '"version": 1,\n  "version": 1,', "/version", "version")
    duplicate("duplicate_material.scene", '"white": {', '"white": {"type": "mirror", "reflectance": [1, 1, 1]},\n    "white": {',
              "/materials/white", "white")
    duplicate("duplicate_surface_key.scene", '"name": "floor",', '"name": "floor",\n      "name": "floor",',
              "/surfaces/0/name", "name")
    duplicate("duplicate_settings_key.scene", '"theta_bins": 8,', '"theta_bins": 8,\n    "theta_bins": 8,',
              "/settings/theta_bins", "theta_bins")
    duplicate("duplicate_camera_key.scene", '"width": 64,', '"width": 64, "width": 64,', "/cameras/0/width", "width")

    # The version is required.
    scene_case("missing_version.scene", del_in(["version"]), "/", "missing key 'version'")

    # Meshes that VTK's readers would crash on or allocate for.
    ply = ("ply\nformat %s 1.0\nelement vertex %s\nproperty float x\nproperty float y\nproperty float z\n"
           "element face 1\nproperty list uchar int vertex_indices\nend_header\n")
    support("huge_vertex_count.ply", ply % ("ascii", "4000000000") + "0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n")
    support("bad_index.ply", ply % ("ascii", "3") + "0 0 0\n1 0 0\n0 1 0\n3 0 1 200000\n")
    support("truncated.ply", (ply % ("binary_little_endian", "3")).encode() + b"\x00\x00")
    support("bad_index.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 7\n")
    support("huge_index.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4000000000\n")
    support("far.obj", "v 0 0 0\nv 1e19 0 0\nv 0 1 0\nf 1 2 3\n")
    vtp = ('<?xml version="1.0"?>\n<VTKFile type="PolyData" version="0.1" byte_order="LittleEndian">\n<PolyData>\n'
           '<Piece NumberOfPoints="%s" NumberOfPolys="1">\n<Points><DataArray type="Float32" NumberOfComponents="3" '
           'format="ascii">0 0 0 1 0 0 0 1 0</DataArray></Points>\n<Polys><DataArray type="Int64" Name="connectivity" '
           'format="ascii">0 1 2</DataArray><DataArray type="Int64" Name="offsets" format="ascii">3</DataArray></Polys>\n'
           '</Piece>\n</PolyData>\n</VTKFile>\n')
    support("huge_count.vtp", vtp % "4000000000")
    support("short_array.vtp", vtp % "10")
    for case, file, location, phrase in [
            ("mesh_ply_huge_vertex_count.scene", "huge_vertex_count.ply", "line 3", "declares 4000000000 entries"),
            ("mesh_ply_bad_index.scene", "bad_index.ply", "face 1", "face refers to vertex 200000"),
            ("mesh_ply_truncated.scene", "truncated.ply", "element 'vertex' 1", "unexpected end of data"),
            ("mesh_obj_bad_index.scene", "bad_index.obj", "line 4", "face refers to vertex 7"),
            ("mesh_obj_huge_index.scene", "huge_index.obj", "line 4", "face refers to vertex 4000000000"),
            ("mesh_obj_far_vertex.scene", "far.obj", "face 1", "coordinate too large"),
            ("mesh_vtp_huge_count.scene", "huge_count.vtp", "line 4", "NumberOfPoints declares 4000000000"),
            ("mesh_vtp_short_array.scene", "short_array.vtp", "cannot read mesh", "Cannot read points array")]:
        scene_case(case, add_surface({"name": "part", "type": "mesh", "material": "white", "file": "support/" + file}),
                   location, phrase)
        named(None, file)

    # Nesting and long excerpts: the message stays short.
    nested = BASE_TEXT.replace('"settings": {', '"extra": ' + "[" * 100 + "]" * 100 + ',\n  "settings": {', 1)
    raw_case("deep_nesting.scene", nested, "/extra/0/0/0/0/0/0/0/0", "nested deeper than 64 levels")
    raw_case("deep_nesting_unterminated.scene", "{\"version\": 1, \"a\": " + "[" * 100000, "/a/0/0/0",
             "nested deeper than 64 levels")
    scene_case("long_unknown_key.scene", set_in(["materials", "white", "x" * 100000], 1),
               "/materials/white/" + "x" * 60, "(100000 bytes)")
    raw_case("bpt_long_token.bpt", VALID_BPT.replace("\n0 1 ", "\n" + "z" * 100000 + " 1 ", 1), "line 7",
             "(100000 bytes)")
    text = BASE_TEXT.replace('"name": "floor"', '"name": "' + "f" * 100000 + '\\q"', 1)
    raw_case("long_string_syntax_error.scene", text, "JSON syntax error", "(100003 bytes)")

    # Magnitudes whose later arithmetic would overflow.
    scene_case("huge_coordinate.scene", set_in(["surfaces", 0, "points", 2, 1], 1e19),
               "/surfaces/0/points/2/1", "coordinate too large")
    scene_case("huge_translate.scene", set_in(["surfaces", 1, "transform", "translate"], [1e16, 0, 0]),
               "/surfaces/1/transform/translate/0", "coordinate too large")
    scene_case("huge_scale.scene", set_in(["surfaces", 1, "transform", "scale"], 1e300),
               "/surfaces/1/transform", "moves patch 1 too far")
    scene_case("huge_camera_position.scene", set_in(["cameras", 0, "position"], [0.5, 0.5, -1e300]),
               "/cameras/0/position/2", "coordinate too large")
    scene_case("huge_emission.scene", set_in(["materials", "lamp", "emission"], [1e308, 1, 1]),
               "/materials/lamp/emission/0", "emission too large")
    scene_case("emission_above_limit.scene", set_in(["materials", "lamp", "emission"], [1, 1, 1e13]),
               "/materials/lamp/emission/2", "emission too large")
    lines = VALID_BPT.split("\n")
    lines[6] = "1 1e19 0"
    raw_case("bpt_huge_coordinate.bpt", "\n".join(lines), "line 7", "control point coordinate too large")


def support_files():
    os.makedirs(SUPPORT, exist_ok=True)
    with open(os.path.join(SUPPORT, "base.scene"), "wb") as f:
        f.write(BASE_TEXT.encode())
    with open(os.path.join(SUPPORT, "base.bpt"), "wb") as f:
        f.write(VALID_BPT.encode())
    # A square with a pentagon face (one face, 5 vertices): not a triangle or quad.
    with open(os.path.join(SUPPORT, "pentagon.obj"), "wb") as f:
        f.write(b"# one pentagon: only triangles and quads are supported\n"
                b"v 0 0 0\nv 1 0 0\nv 1.3 1 0\nv 0.5 1.6 0\nv -0.3 1 0\nf 1 2 3 4 5\n")
    # Used by bpt_error_in_scene.scene: "nan" on line 7.
    lines = VALID_BPT.split("\n")
    lines[6] = "1 nan 0"
    with open(os.path.join(SUPPORT, "nan_patch.bpt"), "wb") as f:
        f.write("\n".join(lines).encode())
    # BRDF tables (Data/scenes/FORMAT.md, "BRDF tables"), each with one thing broken.
    header = "# a constant 0.2 / sr, but ...\ntheta_in,theta_out,delta_phi,r,g,b\n"
    with open(os.path.join(SUPPORT, "negative.brdf.csv"), "wb") as f:
        f.write((header + "0,0,0,0.2,0.2,0.2\n0,0,180,0.2,-0.2,0.2\n").encode())
    with open(os.path.join(SUPPORT, "incomplete.brdf.csv"), "wb") as f:
        f.write((header + "0,0,0,0.2,0.2,0.2\n90,0,0,0.2,0.2,0.2\n0,90,0,0.2,0.2,0.2\n").encode())
    with open(os.path.join(SUPPORT, "bad_header.brdf.csv"), "wb") as f:
        f.write("# the header misspelt\ntheta_in,theta_out,dphi,r,g,b\n0,0,0,0.2,0.2,0.2\n".encode())


def texture_support_files():
    """The PNGs of the texture_*.scene cases (a valid grey ramp, and one broken image per case) and a
    valid 16-bit RGB image."""
    ramp = png_file(4, 2, 8, 0, [bytes([0, 85, 170, 255])] * 2)
    files = {
        "grey_ramp.png": ramp,
        # 16-bit RGB, 2 x 2: top row red, green; bottom row blue, 32768 grey
        # (Testing/Core/scene/TestTexture).
        "rgb16.png": png_file(2, 2, 16, 2, [
            bytes([255, 255, 0, 0, 0, 0, 0, 0, 255, 255, 0, 0]),
            bytes([0, 0, 0, 0, 255, 255, 128, 0, 128, 0, 128, 0])]),
        "not_png.png": b"GIF89a: not a PNG at all\n",
        "truncated.png": ramp[:len(ramp) - 20],  # ends inside the IDAT chunk
        "palette.png": png_file(2, 1, 8, 3, [bytes([0, 0])],
                                extra=png_chunk(b"PLTE", bytes([255, 0, 0]))),
        "rgba.png": png_file(1, 1, 8, 6, [bytes([10, 20, 30, 255])]),
        "grey_4bit.png": png_file(2, 1, 4, 0, [bytes([0x0f])]),
        # A valid header of 100000 x 100000 pixels (and a scrap of data): refused from the header
        # before any memory is taken for the pixels.
        "huge.png": png_file(100000, 100000, 8, 2, [b""]),
    }
    bad_crc = bytearray(ramp)
    bad_crc[29] ^= 0xff  # the IHDR chunk's CRC
    files["bad_crc.png"] = bytes(bad_crc)
    for name, data in files.items():
        with open(os.path.join(SUPPORT, name), "wb") as f:
            f.write(data)


def main():
    json_syntax_cases()
    semantic_cases()
    bpt_cases()
    hostile_cases()
    os.makedirs(BAD, exist_ok=True)
    names = [c[0] for c in CASES]
    assert len(names) == len(set(names))
    # remove stale corpus files (never touches support/)
    for f in os.listdir(BAD):
        p = os.path.join(BAD, f)
        if os.path.isfile(p) and f not in names and f not in ("expected.json", "commands.json"):
            os.remove(p)
    for name, data, _ in CASES:
        with open(os.path.join(BAD, name), "wb") as f:
            f.write(data)
    support_files()
    texture_support_files()
    expected = {name: subs for name, _, subs in CASES}
    with open(os.path.join(BAD, "expected.json"), "w", newline="\n") as f:
        f.write("{\n" + ",\n".join("  %s: %s" % (json.dumps(k), json.dumps(v)) for k, v in expected.items()) + "\n}\n")
    print("wrote %d corpus files + expected.json to %s" % (len(CASES), BAD))


if __name__ == "__main__":
    main()
