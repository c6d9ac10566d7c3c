"""Small geometry helpers shared by the scene tools (plain python3, no third-party packages).

This is NOT a scene loader: it does no validation and reports no errors the way the
C++ loader (Core/SceneLoader) does. It only reads well-formed files far enough to check
orientation, closedness and form factors of the reference scenes in Data/scenes/.
"""

import json
import math
import os

# --------------------------------------------------------------------------- vectors


def add(a, b):
    return [a[0] + b[0], a[1] + b[1], a[2] + b[2]]


def sub(a, b):
    return [a[0] - b[0], a[1] - b[1], a[2] - b[2]]


def mul(a, s):
    return [a[0] * s, a[1] * s, a[2] * s]


def dot(a, b):
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]


def cross(a, b):
    return [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]


def norm(a):
    return math.sqrt(dot(a, a))


def unit(a):
    n = norm(a)
    return [a[0] / n, a[1] / n, a[2] / n] if n > 0 else [0.0, 0.0, 0.0]


def dist(a, b):
    return norm(sub(a, b))


# --------------------------------------------------------------------------- Bezier patches


class Patch:
    """Tensor-product Bezier patch of degree (m, n); points[j*(m+1)+i] is P_ij (u fastest)."""

    def __init__(self, m, n, points, name=""):
        assert len(points) == (m + 1) * (n + 1)
        self.m, self.n, self.points, self.name = m, n, [list(p) for p in points], name

    def P(self, i, j):
        return self.points[j * (self.m + 1) + i]

    def _bern(self, deg, t):
        return [math.comb(deg, k) * t ** k * (1 - t) ** (deg - k) for k in range(deg + 1)]

    def _dbern(self, deg, t):
        # derivative of the Bernstein basis
        if deg == 0:
            return [0.0]
        low = [math.comb(deg - 1, k) * t ** k * (1 - t) ** (deg - 1 - k) for k in range(deg)]
        return [deg * ((low[k - 1] if k > 0 else 0.0) - (low[k] if k < deg else 0.0))
                for k in range(deg + 1)]

    def _combine(self, bu, bv):
        r = [0.0, 0.0, 0.0]
        for j in range(self.n + 1):
            for i in range(self.m + 1):
                w = bu[i] * bv[j]
                if w:
                    p = self.P(i, j)
                    r[0] += w * p[0]
                    r[1] += w * p[1]
                    r[2] += w * p[2]
        return r

    def eval(self, u, v):
        return self._combine(self._bern(self.m, u), self._bern(self.n, v))

    def du(self, u, v):
        return self._combine(self._dbern(self.m, u), self._bern(self.n, v))

    def dv(self, u, v):
        return self._combine(self._bern(self.m, u), self._dbern(self.n, v))

    def normal(self, u, v):
        """dP/du x dP/dv (not normalised); the front side of the patch."""
        return cross(self.du(u, v), self.dv(u, v))

    def area(self, k=24):
        """Area by Gauss-Legendre-free midpoint rule on a k x k grid (good enough for checks)."""
        a = 0.0
        h = 1.0 / k
        for jj in range(k):
            for ii in range(k):
                a += norm(self.normal((ii + 0.5) * h, (jj + 0.5) * h)) * h * h
        return a

    def boundary(self, side):
        """Control points of a boundary curve: 'v0' (v=0, u increasing), 'u1', 'v1', 'u0'."""
        m, n = self.m, self.n
        if side == "v0":
            return [self.P(i, 0) for i in range(m + 1)]
        if side == "u1":
            return [self.P(m, j) for j in range(n + 1)]
        if side == "v1":
            return [self.P(i, n) for i in range(m + 1)]
        if side == "u0":
            return [self.P(0, j) for j in range(n + 1)]
        raise ValueError(side)

    def transformed(self, f):
        return Patch(self.m, self.n, [f(p) for p in self.points], self.name)

    def flipped(self):
        """Same surface, opposite front: swap u and v."""
        pts = [self.P(i, j) for i in range(self.m + 1) for j in range(self.n + 1)]
        return Patch(self.n, self.m, pts, self.name)


def bilinear(points, name=""):
    """points = P(0,0), P(1,0), P(1,1), P(0,1) -> degree (1,1) patch."""
    p00, p10, p11, p01 = points
    return Patch(1, 1, [p00, p10, p01, p11], name)


def quad_normal(points):
    """Normal (P10-P00) x (P01-P00) of a planar bilinear quad given as P00, P10, P11, P01."""
    p00, p10, p11, p01 = points
    return cross(sub(p10, p00), sub(p01, p00))


def quad_nonplanarity(points):
    """Distance of P11 from the plane of P00, P10, P01."""
    p00, p10, p11, p01 = points
    n = unit(quad_normal(points))
    return abs(dot(sub(p11, p00), n))


# --------------------------------------------------------------------------- files


def read_bpt(path):
    """Read a .bpt file (whitespace separated; CRLF, tabs and exponents are fine)."""
    with open(path, "rb") as f:
        toks = f.read().decode("ascii").split()
    pos = 0
    count = int(toks[pos])
    pos += 1
    patches = []
    for _ in range(count):
        m, n = int(toks[pos]), int(toks[pos + 1])
        pos += 2
        pts = []
        for _ in range((m + 1) * (n + 1)):
            pts.append([float(toks[pos]), float(toks[pos + 1]), float(toks[pos + 2])])
            pos += 3
        patches.append(Patch(m, n, pts))
    assert pos == len(toks), "trailing data in " + path
    return patches


def read_obj(path):
    """Minimal OBJ reader: returns (vertices, faces) with 0-based vertex indices per face."""
    verts, faces = [], []
    with open(path) as f:
        for line in f:
            t = line.split()
            if not t:
                continue
            if t[0] == "v":
                verts.append([float(x) for x in t[1:4]])
            elif t[0] == "f":
                idx = []
                for w in t[1:]:
                    k = int(w.split("/")[0])
                    idx.append(k - 1 if k > 0 else len(verts) + k)
                faces.append(idx)
    return verts, faces


# --------------------------------------------------------------------------- transforms


def rotation_matrix(rx, ry, rz):
    """Rotation about x by rx, then about y by ry, then about z by rz (degrees, fixed axes,
    right-hand rule): R = Rz * Ry * Rx applied to column vectors."""
    ax, ay, az = (math.radians(a) for a in (rx, ry, rz))
    cx, sx, cy, sy, cz, sz = math.cos(ax), math.sin(ax), math.cos(ay), math.sin(ay), math.cos(az), math.sin(az)
    Rx = [[1, 0, 0], [0, cx, -sx], [0, sx, cx]]
    Ry = [[cy, 0, sy], [0, 1, 0], [-sy, 0, cy]]
    Rz = [[cz, -sz, 0], [sz, cz, 0], [0, 0, 1]]

    def mm(A, B):
        return [[sum(A[i][k] * B[k][j] for k in range(3)) for j in range(3)] for i in range(3)]

    return mm(Rz, mm(Ry, Rx))


def make_transform(t):
    """The scene's "transform": scale, then rotate, then translate."""
    if not t:
        return lambda p: list(p)
    s = t.get("scale", 1.0)
    if not isinstance(s, list):
        s = [s, s, s]
    R = rotation_matrix(*t.get("rotate", [0, 0, 0]))
    tr = t.get("translate", [0, 0, 0])

    def f(p):
        q = [p[0] * s[0], p[1] * s[1], p[2] * s[2]]
        q = [sum(R[i][k] * q[k] for k in range(3)) for i in range(3)]
        return [q[0] + tr[0], q[1] + tr[1], q[2] + tr[2]]

    return f


# --------------------------------------------------------------------------- scenes


def load_scene(path):
    """Read a (well-formed) .scene and return (scene_dict, list of (entry_index, name, Patch)).
    Patches carry the transform and "flip"; two_sided is left to the caller."""
    with open(path) as f:
        scene = json.load(f)
    folder = os.path.dirname(os.path.abspath(path))
    out = []
    for k, s in enumerate(scene["surfaces"]):
        typ = s["type"]
        if typ == "bilinear":
            patches = [bilinear(s["points"])]
        elif typ == "bezier":
            m, n = s["degree"]
            patches = [Patch(m, n, s["points"])]
        elif typ == "bpt":
            patches = read_bpt(os.path.join(folder, s["file"]))
        elif typ == "mesh":
            verts, faces = read_obj(os.path.join(folder, s["file"]))
            patches = []
            for fc in faces:
                if len(fc) == 4:
                    patches.append(bilinear([verts[i] for i in fc]))
                elif len(fc) == 3:
                    a, b, c = (verts[i] for i in fc)
                    patches.append(bilinear([a, b, c, c]))
                else:
                    raise ValueError("face with %d vertices" % len(fc))
        else:
            raise ValueError(typ)
        f = make_transform(s.get("transform"))
        for p in patches:
            q = p.transformed(f)
            if s.get("flip", False):
                q = q.flipped()
            q.name = s["name"]
            out.append((k, s["name"], q))
    return scene, out


# --------------------------------------------------------------------------- JSON output


def _num(x):
    if isinstance(x, bool):
        return "true" if x else "false"
    if isinstance(x, int):
        return str(x)
    if isinstance(x, float):
        if x == int(x) and abs(x) < 1e15:
            s = "%.1f" % x
        else:
            s = "%.10g" % x
            if "e" not in s and "." not in s:
                s += ".0"
        return s
    return json.dumps(x)


def dumps(obj, indent=0, width=100):
    """JSON text with short arrays (points, colours) kept on one line."""
    pad = "  " * indent
    if isinstance(obj, dict):
        if not obj:
            return "{}"
        items = []
        for k, v in obj.items():
            items.append(pad + "  " + json.dumps(k) + ": " + dumps(v, indent + 1, width).lstrip())
        return "{\n" + ",\n".join(items) + "\n" + pad + "}"
    if isinstance(obj, list):
        flat = "[" + ", ".join(dumps(v, 0, width) for v in obj) + "]"
        if "\n" not in flat and len(flat) + len(pad) <= width:
            return flat
        items = [pad + "  " + dumps(v, indent + 1, width).lstrip() for v in obj]
        return "[\n" + ",\n".join(items) + "\n" + pad + "]"
    return _num(obj)


def write_scene(path, scene):
    text = dumps(scene) + "\n"
    json.loads(text)  # round-trip sanity check
    with open(path, "w", newline="\n") as f:
        f.write(text)


def png_chunk(kind, data):
    """One PNG chunk: length, type, data, CRC-32 of type and data (PNG spec, section 5.3)."""
    import struct
    import zlib
    return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data) & 0xffffffff)


def png_file(width, height, bit_depth, colour_type, rows, extra=b""):
    """A PNG of the given rows, top row first (bytes without the filter byte; filter 0 added),
    written by hand (plain python3): signature, IHDR, optional chunks, one IDAT, IEND."""
    import struct
    import zlib
    ihdr = struct.pack(">IIBBBBB", width, height, bit_depth, colour_type, 0, 0, 0)
    raw = b"".join(b"\x00" + r for r in rows)
    return (b"\x89PNG\r\n\x1a\n" + png_chunk(b"IHDR", ihdr) + extra +
            png_chunk(b"IDAT", zlib.compress(raw, 9)) + png_chunk(b"IEND", b""))
