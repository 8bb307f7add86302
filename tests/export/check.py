#!/usr/bin/python3
"""check.py DIR CASE...: read back what export_all (lib.lua) wrote and
compare it with the values tds reported in CASE.json. Prints a line
"PASS export/..." or "FAIL export/...: why" per check.

Readers: meshio for every format and variant (its PLY reader in 5.0 cannot
read binary files with per-face properties, so those are read by the
small structured-array reader here, which follows the PLY specification),
VTK 9's own readers for VTU and legacy VTK, and a NumPy reader of binary
STL for the watertightness checks.

Tolerances: coordinates and fields written as doubles (binary, or ASCII
with 17 significant digits) must come back bit for bit, so they are
compared exactly. Binary STL holds float32: its coordinates must equal the
float32 rounding of tds's values exactly. The vertex normal and the
curvatures recomputed here independently (same formulas, different
summation order) agree to 1e-9 relative; volumes of float32 STL shells
agree with tds's body volumes to 1e-5 relative (each coordinate is off by
at most 2^-24 relative, and the signed-volume sum over facets adds at most
a few times that per unit of volume).
"""
import contextlib
import io
import json
import math
import struct
import sys
import warnings

import numpy as np

warnings.filterwarnings("ignore")
import meshio  # noqa: E402
import vtk  # noqa: E402
from vtk.util.numpy_support import vtk_to_numpy  # noqa: E402



def mread(*args, **kw):
    """meshio.read without the blank lines its Gmsh reader prints."""
    with contextlib.redirect_stdout(io.StringIO()):
        return meshio.read(*args, **kw)


VF = ["position", "normal", "mean_curvature", "gauss_curvature", "displacement", "id"]
FF = ["min_angle", "area", "tension", "color", "frontbody", "backbody", "id"]
# Evolver's colour names, -1 CLEAR .. 15 WHITE, as the PC text-mode palette
PALETTE = {0: (0, 0, 0), 1: (0, 0, 170), 2: (0, 170, 0), 3: (0, 170, 170),
           4: (170, 0, 0), 5: (170, 0, 170), 6: (170, 85, 0), 7: (170, 170, 170),
           8: (85, 85, 85), 9: (85, 85, 255), 10: (85, 255, 85), 11: (85, 255, 255),
           12: (255, 85, 85), 13: (255, 85, 255), 14: (255, 255, 85), 15: (255, 255, 255)}

failures = 0


def report(name, ok, why=""):
    global failures
    if ok:
        print(f"PASS export/{name}")
    else:
        failures += 1
        print(f"FAIL export/{name}: {why}")


def nan(x):
    return math.nan if x is None else x


class Ref:
    """The surface as tds reported it, and what the files must hold."""

    def __init__(self, path):
        d = json.load(open(path))
        v = d["vertices"]
        self.vid = np.array([r[0] for r in v])
        row = {r[0]: i for i, r in enumerate(v)}
        X = np.array([[r[1], r[2], r[3]] for r in v], float)
        H = np.array([nan(r[4]) for r in v], float)
        K = np.array([nan(r[5]) for r in v], float)
        M = np.array([[nan(r[6]), nan(r[7]), nan(r[8])] for r in v], float)
        fixed = np.array([r[9] for r in v]) == 1
        f = d["facets"]
        self.fid = np.array([r[0] for r in f])
        fv = np.array([[r[1], r[2], r[3]] for r in f])
        self.farea = np.array([r[4] for r in f], float)
        self.fmin = np.array([r[5] for r in f], float)
        self.ften = np.array([r[6] for r in f], float)
        self.fcol = np.array([r[7] for r in f])
        self.ffb = np.array([r[8] for r in f])
        self.fbb = np.array([r[9] for r in f])
        self.fsel = np.array([r[10] for r in f]) == 1
        self.bodies = {r[0]: r[1] for r in d["bodies"]}
        # exported vertices: those of the facets, in id order
        used = np.unique(fv)
        rows = np.array([row[i] for i in used])
        self.X, self.H, self.K, self.M = X[rows], H[rows], K[rows], M[rows]
        self.fixed = fixed[rows]
        self.ids = used
        compact = {vid: i for i, vid in enumerate(used)}
        self.tri = np.vectorize(compact.get)(fv)
        self.normal = self.vertex_normals()
        self.Hind, self.Kind = self.curvatures()

    def vertex_normals(self):
        n = np.zeros_like(self.X)
        for t in self.tri:
            a, b, c = self.X[t]
            N = np.cross(b - a, c - a)  # |N| = 2 area: area-weighted
            n[t] += N
        return n / np.linalg.norm(n, axis=1)[:, None]

    def curvatures(self):
        """Meyer et al. k1+k2 and angle defect / mixed area, at vertices
        whose every edge has two facets; NaN elsewhere."""
        nv = len(self.X)
        val = {}
        for t in self.tri:
            for k in range(3):
                e = tuple(sorted((t[k], t[(k + 1) % 3])))
                val[e] = val.get(e, 0) + 1
        ok = ~self.fixed
        for (a, b), c in val.items():
            if c != 2:
                ok[a] = ok[b] = False
        Kv = np.zeros((nv, 3))
        S = np.zeros((nv, 3))
        amix = np.zeros(nv)
        ang = np.zeros(nv)
        for t in self.tri:
            for k in range(3):
                i, j, l = t[k], t[(k + 1) % 3], t[(k + 2) % 3]
                xi, xj, xl = self.X[i], self.X[j], self.X[l]
                N = np.cross(xj - xi, xl - xi)
                A = np.linalg.norm(N) / 2
                S[i] += N
                ai = math.atan2(np.linalg.norm(N), np.dot(xj - xi, xl - xi))
                aj = math.atan2(np.linalg.norm(N), np.dot(xi - xj, xl - xj))
                al = math.atan2(np.linalg.norm(N), np.dot(xi - xl, xj - xl))
                cj, cl = 1 / math.tan(aj), 1 / math.tan(al)
                Kv[i] += cl * (xi - xj) + cj * (xi - xl)
                ang[i] += ai
                if ai > math.pi / 2:
                    amix[i] += A / 2
                elif aj > math.pi / 2 or al > math.pi / 2:
                    amix[i] += A / 4
                else:
                    amix[i] += (np.dot(xj - xi, xj - xi) * cl + np.dot(xl - xi, xl - xi) * cj) / 8
        H = np.full(nv, math.nan)
        G = np.full(nv, math.nan)
        for i in range(nv):
            if ok[i] and amix[i] > 0:
                H[i] = np.dot(Kv[i], S[i]) / (np.linalg.norm(S[i]) * 2 * amix[i])
                G[i] = (2 * math.pi - ang[i]) / amix[i]
        return H, G

    def vfield(self, name):
        return {"position": self.X, "normal": self.normal, "mean_curvature": self.H,
                "gauss_curvature": self.K, "displacement": self.X - self.M,
                "id": self.ids}[name]

    def ffield(self, name):
        return {"min_angle": self.fmin, "area": self.farea, "tension": self.ften,
                "color": self.fcol, "frontbody": self.ffb, "backbody": self.fbb,
                "id": self.fid}[name]


def same(a, b, tol=0.0):
    """Equal element by element, NaN matching NaN; tol relative to max(1,|b|)."""
    a = np.asarray(a, float).reshape(-1)
    b = np.asarray(b, float).reshape(-1)
    if a.shape != b.shape:
        return False, f"shape {a.shape} != {b.shape}"
    na, nb = np.isnan(a), np.isnan(b)
    if (na != nb).any():
        i = int(np.nonzero(na != nb)[0][0])
        return False, f"NaN at {i}: {a[i]} vs {b[i]}"
    d = np.abs(a[~na] - b[~nb])
    lim = tol * np.maximum(1, np.abs(b[~nb]))
    if (d > lim).any():
        i = int(np.argmax(d - lim))
        return False, f"differs at {i}: {a[~na][i]!r} vs {b[~nb][i]!r}"
    return True, ""


def check_mesh(name, ref, points, tris):
    ok, why = same(points, ref.X)
    if ok:
        ok, why = same(tris, ref.tri)
    report(f"{name}/mesh", ok and len(points) == len(ref.X),
           why or f"{len(points)} points, expected {len(ref.X)}")


def check_fields(name, ref, pdata, cdata, vnames=VF, fnames=FF):
    bad = []
    for f in vnames:
        tol = 1e-12 if f == "normal" else 0.0
        ok, why = same(pdata[f], ref.vfield(f), tol)
        if not ok:
            bad.append(f"vertex {f}: {why}")
    for f in fnames:
        ok, why = same(cdata[f], ref.ffield(f))
        if not ok:
            bad.append(f"facet {f}: {why}")
    if fnames and "color" in fnames:
        rgba = np.array([(255, 255, 255, 0) if c == -1 else PALETTE[c % 16] + (255,)
                         for c in ref.fcol], float)
        ok, why = same(cdata["rgba"], rgba)
        if not ok:
            bad.append(f"rgba: {why}")
    report(f"{name}/fields", not bad, "; ".join(bad))


def ply_fields(m):
    """meshio's PLY point/cell data back into tds's field names."""
    p, c = dict(m.point_data), {k: v[0] for k, v in m.cell_data.items()}
    for f in ("position", "displacement"):
        if f + "_x" in p:
            p[f] = np.column_stack([p[f + "_x"], p[f + "_y"], p[f + "_z"]])
    if "nx" in p:
        p["normal"] = np.column_stack([p["nx"], p["ny"], p["nz"]])
    if "red" in c:
        c["rgba"] = np.column_stack([c["red"], c["green"], c["blue"], c["alpha"]])
    return p, c


def read_ply_binary(path):
    """Binary little-endian PLY with fixed-size records (triangles)."""
    raw = open(path, "rb").read()
    end = raw.index(b"end_header\n") + len(b"end_header\n")
    elems = []
    for line in raw[:end].decode().splitlines():
        w = line.split()
        if w[0] == "element":
            elems.append((w[1], int(w[2]), []))
        elif w[0] == "property" and w[1] == "list":
            elems[-1][2].extend([("n", "<u1"), (w[4], "<i4", (3,))])
        elif w[0] == "property":
            t = {"double": "<f8", "int": "<i4", "uchar": "<u1"}[w[1]]
            elems[-1][2].append((w[2], t))
    out, pos = {}, end
    for name, n, fields in elems:
        dt = np.dtype(fields)
        out[name] = np.frombuffer(raw, dt, n, pos)
        pos += n * dt.itemsize
    report(f"{path.split('/')[-1]}/size", pos == len(raw), f"{len(raw) - pos} bytes left")
    return out["vertex"], out["face"]


def vtk_read(path):
    if path.endswith(".vtu"):
        r = vtk.vtkXMLUnstructuredGridReader()
    else:
        r = vtk.vtkUnstructuredGridReader()
        r.ReadAllFieldsOn()
    r.SetFileName(path)
    r.Update()
    o = r.GetOutput()
    pts = vtk_to_numpy(o.GetPoints().GetData())
    conn = vtk_to_numpy(o.GetCells().GetConnectivityArray()).reshape(-1, 3)
    types = {o.GetCellType(i) for i in range(o.GetNumberOfCells())}
    pd = {o.GetPointData().GetArrayName(i): vtk_to_numpy(o.GetPointData().GetArray(i))
          for i in range(o.GetPointData().GetNumberOfArrays())}
    cd = {o.GetCellData().GetArrayName(i): vtk_to_numpy(o.GetCellData().GetArray(i))
          for i in range(o.GetCellData().GetNumberOfArrays())}
    return pts, conn, types, pd, cd


def stl_binary(path):
    raw = open(path, "rb").read()
    n = struct.unpack_from("<I", raw, 80)[0]
    rec = np.frombuffer(raw, np.dtype([("n", "<f4", 3), ("v", "<f4", (3, 3)), ("a", "<u2")]),
                        n, 84)
    report(f"{path.split('/')[-1]}/size", 84 + 50 * n == len(raw), "size mismatch")
    return rec["v"].astype(float)


def watertight(name, tri_pts, volume=None, positive_below=None):
    """Every edge in exactly two facets, once each way; V - E + F = 2;
    the signed volume against the body's."""
    P, inv = np.unique(tri_pts.reshape(-1, 3), axis=0, return_inverse=True)
    T = inv.reshape(-1, 3)
    use = {}
    for t in T:
        for k in range(3):
            a, b = int(t[k]), int(t[(k + 1) % 3])
            use.setdefault((min(a, b), max(a, b)), []).append(a < b)
    bad = [e for e, d in use.items() if len(d) != 2 or d[0] == d[1]]
    chi = len(P) - len(use) + len(T)
    vol = float(np.einsum("ij,ij->i", tri_pts[:, 0], np.cross(tri_pts[:, 1], tri_pts[:, 2])).sum() / 6)
    why = []
    if bad:
        why.append(f"{len(bad)} edges not in exactly two oppositely oriented facets, e.g. "
                   f"{P[bad[0][0]]}-{P[bad[0][1]]}")
    if chi != 2:
        why.append(f"Euler characteristic {chi}, expected 2")
    if volume is not None and abs(vol - volume) > 1e-5 * abs(volume):
        why.append(f"volume {vol!r}, body volume {volume!r}")
    if positive_below is not None and not (0 < vol < positive_below):
        why.append(f"volume {vol!r} not in (0, {positive_below})")
    report(f"{name}/watertight", not why, "; ".join(why))


def check_case(d, case):
    ref = Ref(f"{d}/{case}.json")
    p = f"{d}/{case}"
    # the export's own curvatures against an independent computation
    ok, why = same(ref.H, ref.Hind, 1e-9)
    report(f"{case}/mean_curvature_independent", ok, why)
    ok, why = same(ref.K, ref.Kind, 1e-9)
    report(f"{case}/gauss_curvature_independent", ok, why)
    for suffix in (".obj", ".off", "_22ascii.msh", "_22binary.msh", "_41ascii.msh",
                   "_41binary.msh", "_ascii.ply", "_vonly.ply", "_ascii.vtu",
                   "_base64.vtu", "_b64app.vtu", "_binary.vtu", "_ascii.vtk", "_binary.vtk", "_asply.dat"):
        name = case + suffix
        m = mread(p + suffix, file_format="ply" if suffix.endswith(".dat") else None)
        tris = [c.data for c in m.cells if c.type == "triangle"]
        check_mesh(name + "(meshio)", ref, m.points, np.concatenate(tris))
        if suffix in ("_ascii.ply", "_vonly.ply"):
            pd, cd = ply_fields(m)
            check_fields(name + "(meshio)", ref, pd, cd,
                         fnames=FF if suffix == "_ascii.ply" else [])
        elif suffix.endswith((".vtu", ".vtk")):
            cd = {k: v[0] for k, v in m.cell_data.items()}
            vn = ["position", "normal", "id"] if suffix == "_ascii.vtk" else VF
            check_fields(name + "(meshio)", ref, m.point_data, cd, vnames=vn)
            pts, conn, types, pd, cd = vtk_read(p + suffix)
            check_mesh(name + "(vtk)", ref, pts, conn)
            report(name + "(vtk)/triangles", types == {vtk.VTK_TRIANGLE}, f"cell types {types}")
            check_fields(name + "(vtk)", ref, pd, cd, vnames=vn)
    v, f = read_ply_binary(p + "_binary.ply")
    check_mesh(case + "_binary.ply", ref, np.column_stack([v["x"], v["y"], v["z"]]),
               f["vertex_indices"])
    pd = {n: v[n] for n in v.dtype.names}
    cd = {n: f[n] for n in f.dtype.names}
    pd["position"] = np.column_stack([v["position_x"], v["position_y"], v["position_z"]])
    pd["displacement"] = np.column_stack([v["displacement_x"], v["displacement_y"],
                                          v["displacement_z"]])
    pd["normal"] = np.column_stack([v["nx"], v["ny"], v["nz"]])
    cd["rgba"] = np.column_stack([f["red"], f["green"], f["blue"], f["alpha"]])
    report(case + "_binary.ply/count", np.all(f["n"] == 3), "list counts")
    check_fields(case + "_binary.ply", ref, pd, cd)
    # STL: triangles in facet order, coordinates exact (ASCII) or float32
    want = ref.X[ref.tri]
    m = mread(p + "_ascii.stl")
    ok, why = same(m.points[m.cells[0].data], want)
    report(case + "_ascii.stl(meshio)", ok, why)
    m = mread(p + "_binary.stl")
    ok, why = same(m.points[m.cells[0].data], want.astype(np.float32))
    report(case + "_binary.stl(meshio)", ok, why)
    ok, why = same(stl_binary(p + "_binary.stl"), want.astype(np.float32))
    report(case + "_binary.stl", ok, why)
    # one closed, outward shell per body
    cut = not ref.fsel.all()
    for b, vol in ref.bodies.items():
        name = f"{case}_pb_body{b}.stl"
        inside = ((ref.ffb == b) | (ref.fbb == b)) & ref.fsel
        tri = stl_binary(f"{p}_pb_body{b}.stl")
        # the body's own facets come first, those on its back reversed
        own = ref.X[ref.tri[inside]]
        rev = ref.fbb[inside] == b
        own[rev] = own[rev][:, ::-1]
        ok, why = same(tri[:len(own)], own.astype(np.float32))
        report(name + "/facets", ok, why)
        watertight(name, tri, None if cut else vol, vol if cut else None)
        m = mread(f"{p}_pba_body{b}.stl")
        watertight(f"{case}_pba_body{b}.stl(meshio)", m.points[m.cells[0].data],
                   None if cut else vol, vol if cut else None)
        m = mread(f"{p}_pb_body{b}.ply")
        c = {k: v[0] for k, v in m.cell_data.items()}
        ok = len(c["frontbody"]) == len(tri) and np.all(c["frontbody"] == b) and \
            np.all(c["backbody"] != b)
        ncap = int(np.sum(c["id"] == 0))
        report(f"{case}_pb_body{b}.ply/outward", ok and ncap == len(tri) - len(own),
               f"frontbody {set(c['frontbody'])}, caps {ncap}")


def main():
    d = sys.argv[1]
    for case in sys.argv[2:]:
        try:
            check_case(d, case)
        except Exception as e:  # a reader failing is a failed test
            report(case, False, f"{type(e).__name__}: {e}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
