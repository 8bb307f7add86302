"""pictures.py: tests that look at the pictures tds draws.

Usage: /usr/bin/python3 tests/pictures/pictures.py TDS BUILD (from the
project root). Runs the .tds scripts of this folder, reads their PNGs back
with BUILD/png2ppm (cairo) and prints PASS/FAIL lines."""
import math
import os
import subprocess
import sys
import tempfile

import numpy as np

TDS, BUILD = sys.argv[1], sys.argv[2]
HERE = os.path.dirname(os.path.abspath(__file__))


def read_png(path):
    ppm = subprocess.run([os.path.join(BUILD, "png2ppm"), path], check=True,
                         capture_output=True).stdout
    head = ppm.split(b"\n", 3)
    w, h = map(int, head[1].split())
    return np.frombuffer(head[3], dtype=np.uint8).reshape(h, w, 3).astype(float)


def run(script, out, seed=None):
    env = dict(os.environ, OUT=out)
    if seed is not None:
        env["SEED"] = str(seed)
    p = subprocess.run([TDS, "-q", os.path.join(HERE, script)], env=env,
                       capture_output=True, text=True)
    if p.returncode:
        raise RuntimeError(f"{script}: {p.stderr.strip() or p.stdout.strip()}")
    info = {}
    for line in p.stdout.splitlines():
        if line.startswith("INFO "):
            parts = line.split()
            key = " ".join(parts[1:-1]) if len(parts) == 3 else " ".join(parts[1:3])
            vals = [float(x) for x in parts[2:]] if len(parts) == 3 else \
                [float(x) for x in parts[3:]]
            info[key] = vals if len(vals) > 1 else vals[0]
        elif line.startswith(("HIST ", "COUNTS ")):
            word, rest = line.split(" ", 1)
            info.setdefault(word, []).append([float(x) for x in rest.split()])
    return info


def report(name, ok, why):
    print(f"PASS picture/{name}" if ok else f"FAIL picture/{name}: {why}")


def sphere(out, seed):
    """The silhouette of a sphere drawn orthographically is a disc of radius
    R * scale about the projected centre. The mesh is inscribed in the
    sphere, so its outline lies between the circle and the circle shrunk by
    the chord depth of the longest edge (sag); anti-aliasing moves each
    boundary pixel's coverage by under half a pixel."""
    info = run("sphere.tds", out, seed)
    for pic, pre, tag in (("sphere.png", "", ""), ("sphere_smooth.png", "", "_smooth"),
                          ("sphere_persp.png", "p", "_perspective")):
        disc(out, pic, info[pre + "cx"], info[pre + "cy"], info[pre + "R"],
             info[pre + "sag"], f"{tag}_seed{seed}")


def disc(out, pic, cx, cy, R, sag, tag):
    img = read_png(os.path.join(out, pic))
    surface = np.array([0.80, 0.82, 0.88]) * 255  # the neutral colour, unlit
    cov = np.clip((255 - img).sum(axis=2) / (765 - surface.sum()), 0, 1)
    ys, xs = np.mgrid[0:img.shape[0], 0:img.shape[1]] + 0.5
    area = cov.sum()
    mx, my = (cov * xs).sum() / area, (cov * ys).sum() / area
    lo = math.pi * (R - sag) ** 2 - math.pi * R
    hi = math.pi * R ** 2 + math.pi * R
    report(f"sphere_area{tag}", lo <= area <= hi,
           f"silhouette area {area:.1f} px not in [{lo:.1f}, {hi:.1f}]")
    dc = math.hypot(mx - cx, my - cy)
    report(f"sphere_centroid{tag}", dc <= sag + 0.5,
           f"centroid ({mx:.2f}, {my:.2f}) is {dc:.2f} px from the projected "
           f"centre ({cx:.2f}, {cy:.2f}), tolerance {sag + 0.5:.2f}")
    # round, not an ellipse: equal second moments about the centroid
    ixx = (cov * (xs - mx) ** 2).sum()
    iyy = (cov * (ys - my) ** 2).sum()
    ixy = (cov * (xs - mx) * (ys - my)).sum()
    tol = 4 * sag / R + 4 / R
    report(f"sphere_round{tag}",
           abs(ixx / iyy - 1) <= tol and abs(ixy) / iyy <= tol,
           f"moments xx {ixx:.4g} yy {iyy:.4g} xy {ixy:.4g}, tolerance {tol:.3g}")


def bubbles(out, seed):
    """Colour by body: each bubble's outer wall shows its body's colour
    (unlit, so exactly that colour away from the outline), the two colours
    differ clearly, and together they cover the surface."""
    info = run("bubbles.tds", out, seed)
    for name in ("bubbles", "bubbles_perturbed"):
        img = read_png(os.path.join(out, name + ".png"))
        c1, c2 = np.array(info[f"{name} body1"]), np.array(info[f"{name} body2"])
        surf = (img < 250).any(axis=2)
        d1 = np.abs(img - c1).max(axis=2)
        d2 = np.abs(img - c2).max(axis=2)
        n = surf.sum()
        f1, f2 = ((d1 <= 2) & surf).sum() / n, ((d2 <= 2) & surf).sum() / n
        why = []
        if np.abs(c1 - c2).max() < 60:
            why.append(f"body colours {c1} and {c2} are too close")
        if not (f1 > 0.3 and f2 > 0.3 and f1 + f2 > 0.95):
            why.append(f"body 1 covers {f1:.3f}, body 2 {f2:.3f} of the surface")
        # 12 px inside each bubble's extreme point along the x axis
        for key, c, step in (("left", c1, 12), ("right", c2, -12)):
            x, y = info[f"{name} {key}"]
            p = img[int(y), int(x + step)]
            if np.abs(p - c).max() > 2:
                why.append(f"{key} bubble pixel {p} is not its body colour {c}")
        report(f"{name}_seed{seed}", not why, "; ".join(why))


def ramp(t):
    """The colour map of tds pictures (render.c): blue, grey at 0.5, red."""
    c = np.array([[0.230, 0.299, 0.754], [0.865, 0.865, 0.865], [0.706, 0.016, 0.150]])
    t = np.clip(t, 0, 1)
    i = (t >= 0.5).astype(int)
    u = np.where(t < 0.5, 2 * t, 2 * t - 1)
    return 255 * (c[i] + u[..., None] * (c[i + 1] - c[i]))


def catenoid(out):
    """A minimal surface coloured by k1 + k2 over -1..1 shows the colour of
    zero everywhere: every pixel inside the picture (not on the outline) is
    within the colour of |k1 + k2| <= 0.15 (the relaxed mesh's largest
    vertex error is 0.12; a facet shows the mean of its vertices), while
    the unrelaxed start is not."""
    info = run("catenoid.tds", out)
    c = np.array([[0.230, 0.299, 0.754], [0.865, 0.865, 0.865], [0.706, 0.016, 0.150]]) * 255

    def curvature_of(path):
        """k1 + k2 each inner pixel shows (inverting the map by its green
        channel, the side by red against blue) and its distance from the map."""
        img = read_png(path)
        bg = (img >= 254).all(axis=2)
        inner = ~bg
        for dy, dx in ((1, 0), (-1, 0), (0, 1), (0, -1)):
            inner &= ~np.roll(bg, (dy, dx), axis=(0, 1))
        px = img[inner]
        blue = px[:, 2] > px[:, 0]
        u_blue = (px[:, 1] - c[0, 1]) / (c[1, 1] - c[0, 1])
        u_red = (px[:, 1] - c[1, 1]) / (c[2, 1] - c[1, 1])
        t = np.clip(np.where(blue, u_blue / 2, 0.5 + u_red / 2), 0, 1)
        return 2 * t - 1, np.abs(px - ramp(t)).max(axis=1)

    h, dist = curvature_of(os.path.join(out, "catenoid.png"))
    ok = np.abs(h).max() <= 0.15 and dist.max() <= 3 and info["maxH"] <= 0.15
    report("catenoid_zero_curvature", ok,
           f"|k1+k2| shown up to {np.abs(h).max():.3f} (colour off the map by "
           f"{dist.max():.0f}); vertex maximum {info['maxH']:.3f}")
    # Smooth: colours blend linearly between the vertices', so a pixel may
    # sit off the (kinked) map; it must be as close to the colour of zero
    # as the colours of k1 + k2 = -0.15 and 0.15 are.
    img = read_png(os.path.join(out, "catenoid_smooth.png"))
    bg = (img >= 254).all(axis=2)
    inner = ~bg
    for dy, dx in ((1, 0), (-1, 0), (0, 1), (0, -1)):
        inner &= ~np.roll(bg, (dy, dx), axis=(0, 1))
    zero = ramp(np.array(0.5))
    bound = max(np.abs(ramp(np.array(0.5 + d)) - zero).max() for d in (-0.075, 0.075))
    d0 = np.abs(img[inner] - zero).max(axis=1)
    report("catenoid_zero_curvature_smooth", d0.max() <= bound + 2,
           f"a pixel is {d0.max():.0f} from the colour of zero (bound {bound:.0f})")
    h0, _ = curvature_of(os.path.join(out, "catenoid_start.png"))
    far = (np.abs(h0) > 0.3).mean()
    report("catenoid_start_not_zero", far > 0.2,
           f"only {far:.3f} of the unrelaxed surface shows |k1+k2| > 0.3")


def series_rows(img, colour, x0, x1, y0, y1):
    """Mean row of the pixels of a series' colour in each column of a panel."""
    panel = img[int(y0) + 1:int(y1), int(x0) + 1:int(x1)]
    near = np.abs(panel - np.array(colour) * 255).max(axis=2) <= 40
    cols = {}
    for j in range(panel.shape[1]):
        rows = np.nonzero(near[:, j])[0]
        if len(rows):
            cols[int(x0) + 1 + j + 0.5] = int(y0) + 1 + rows.mean() + 0.5
    return cols


def curve(out, pic, layout, it, vals, name):
    """The plotted curve passes through the recorded values, to 1.5 px, in
    every column away from steep segments (where a column's pixels span
    many rows, so its mean row is not the value)."""
    img = read_png(os.path.join(out, pic))
    x0, y0, x1, y1, lo, hi = layout
    cols = series_rows(img, (0.1, 0.3, 0.75), x0, x1, y0, y1)
    rows = y1 - (vals - lo) / (hi - lo) * (y1 - y0)
    bad, checked = [], 0
    for x, row in cols.items():
        i = it[0] + (x - x0) / (x1 - x0) * (it[-1] - it[0])
        k = int(np.searchsorted(it, i))
        if k < 1 or k >= len(it):
            continue
        d = 2 * (it[-1] - it[0]) / (x1 - x0)
        near = (it >= it[k - 1] - d - 1) & (it <= it[k] + d + 1)
        if not np.isfinite(rows[near]).all() or np.ptp(rows[near]) > 1:
            continue
        ya, yb = rows[k - 1], rows[k]
        want = ya + (yb - ya) * (i - it[k - 1]) / (it[k] - it[k - 1])
        checked += 1
        if abs(row - want) > 1.5:
            bad.append(f"iteration {i:.1f}: curve at row {row:.1f}, value at {want:.1f}")
    report(name, checked > 50 and not bad, f"{checked} columns checked; " + "; ".join(bad[:3]))


def plots(out, seed):
    """The convergence plots' curves (energy, and energy above the lowest on
    a log scale) pass through the recorded history, and each histogram bar
    is as tall as its count says, to a pixel."""
    info = run("plots.tds", out, seed)
    hist = np.array(info["HIST"])
    it, energy = hist[:, 0], hist[:, 1]
    with np.errstate(divide="ignore"):
        excess = np.log10(energy - energy.min())  # -inf at the lowest: no point
    for pic, key, vals, tag in (("plot.png", "plot layout", energy, "energy"),
                                ("plot_excess.png", "excess layout", excess, "excess")):
        curve(out, pic, info[key], it, vals, f"plot_{tag}_seed{seed}")
    img = read_png(os.path.join(out, "angles.png"))
    x0, y0, x1, y1, top = info["hist layout"]  # y0: row of count 0, y1: of `top`
    counts = info["COUNTS"][0]
    bw = (x1 - x0) / len(counts)
    bad = []
    for i, c in enumerate(counts):
        col = img[:, int(x0 + (i + 0.5) * bw)]
        bar = (np.abs(col - np.array([0.25, 0.45, 0.75]) * 255).max(axis=1) <= 2).sum()
        want = c / top * (y0 - y1)
        if abs(bar - want) > 1.5:
            bad.append(f"bin {i}: bar {bar} px, count {c:.0f} wants {want:.1f}")
    report(f"histogram_bars_seed{seed}", not bad and sum(counts) > 0, "; ".join(bad))


def colors(out):
    """Evolver's colours are the PC palette (RED 170,0,0; LIGHTBLUE
    85,85,255; YELLOW 255,255,85): the upper half of a sphere is red and
    the lower light blue, about half each; CLEAR facets are not drawn, so
    with the front half clear the back half's yellow fills the disc."""
    info = run("colors.tds", out)
    cx, cy, R = info["cx"], info["cy"], info["R"]
    red, lblue, yellow = np.array([170, 0, 0]), np.array([85, 85, 255]), np.array([255, 255, 85])
    img = read_png(os.path.join(out, "colors.png"))
    why = []
    for dy, want in ((-0.5, red), (0.5, lblue)):
        p = img[int(cy + dy * R), int(cx)]
        if np.abs(p - want).max() > 1:
            why.append(f"pixel {dy:+} R from the centre is {p}, not {want}")
    surf = (img < 250).any(axis=2)
    fr = (np.abs(img - red).max(axis=2) <= 1).sum() / surf.sum()
    fb = (np.abs(img - lblue).max(axis=2) <= 1).sum() / surf.sum()
    if not (0.4 < fr < 0.6 and 0.4 < fb < 0.6):
        why.append(f"red covers {fr:.3f}, light blue {fb:.3f} of the sphere")
    img = read_png(os.path.join(out, "colors_clear.png"))
    p = img[int(cy), int(cx)]
    if np.abs(p - yellow).max() > 1:
        why.append(f"centre of the clear-fronted sphere is {p}, not yellow")
    fy = (np.abs(img - yellow).max(axis=2) <= 1).sum() / (img < 250).any(axis=2).sum()
    if fy < 0.95:
        why.append(f"yellow covers only {fy:.3f} of the clear-fronted sphere")
    report("evolver_colors_and_clear", not why, "; ".join(why))


def strings_part(out, seed, name):
    """Run PART name of strings.tds: its INFO lines by their first three
    words, its other lines by their first word, as lists of numbers."""
    env = dict(os.environ, OUT=out, SEED=str(seed), PART=name)
    p = subprocess.run([TDS, "-q", os.path.join(HERE, "strings.tds")], env=env,
                       capture_output=True, text=True)
    if p.returncode:
        raise RuntimeError(f"strings.tds {name}: {p.stderr.strip() or p.stdout.strip()}")
    rows = {}
    for line in p.stdout.splitlines():
        w = line.split()
        k = 3 if w[0] == "INFO" else 1
        rows.setdefault(" ".join(w[:k]), []).append([float(x) for x in w[k:]])
    return rows


def strings_fixed(out):
    """String-model pictures without a seed (strings.tds). The bubble,
    filled with its body's colour: the pixels showing exactly that colour
    cover the cell's area (A scale^2) less at most the inner half of the
    outline (width 400/300 px) and one anti-aliased pixel along the
    perimeter. The tilted loop in 3-D: a dark pixel (at most 80 on every
    channel; edges are grey 26) within a pixel of every projected corner,
    and white at the corners' mean (no fill without bodies). Every edge is
    drawn; a colouring that needs facets is refused."""
    why = []
    rows = strings_part(out, 7, "bubble")
    img = read_png(os.path.join(out, "bubble.png"))
    area, perim = rows["INFO bubble area"][0][0], rows["INFO bubble perimeter"][0][0]
    drawn, count = rows["INFO bubble edges"][0]
    c = np.array(rows["INFO bubble color"][0])
    n = (np.abs(img - c).max(axis=2) <= 2).sum()
    if not (area - perim * (400 / 300 / 2 + 1) <= n <= area):
        why.append(f"{n} pixels of the body colour for an area of {area:.0f} px")
    if drawn != count:
        why.append(f"{drawn:.0f} of {count:.0f} edges drawn")
    report("strings_bubble_area", not why, "; ".join(why))

    why = []
    rows = strings_part(out, 7, "loop")
    img = read_png(os.path.join(out, "loop.png"))
    for x, y in rows["CORNER"]:
        i, j = int(y), int(x)
        if img[i - 1:i + 2, j - 1:j + 2].max(axis=2).min() > 80:
            why.append(f"no dark pixel at corner ({x:.0f}, {y:.0f})")
    mx, my = np.mean([r[0] for r in rows["CORNER"]]), np.mean([r[1] for r in rows["CORNER"]])
    if img[int(my), int(mx)].min() < 255:
        why.append(f"the loop's middle ({mx:.0f}, {my:.0f}) is {img[int(my), int(mx)]}")
    drawn, count = rows["INFO loop edges"][0]
    if drawn != count:
        why.append(f"{drawn:.0f} of {count:.0f} edges drawn")
    if rows["INFO loop refused"][0][0] != 1:
        why.append("color = mean_curvature was not refused in the string model")
    report("strings_loop", not why, "; ".join(why))


def strings_foam(out, seed):
    """A seeded perturbed honeycomb foam (convex cells) coloured by body:
    each cell's vertex centroid shows its body's colour (within 2 of 255),
    each wall's midpoint is dark (walls are 800/300 px wide, grey 26: at
    most 80 on every channel), every edge is drawn."""
    why = []
    rows = strings_part(out, seed, "foam")
    img = read_png(os.path.join(out, "foam.png"))
    for x, y, *col in rows["CELL"]:
        p = img[int(y), int(x)]
        if np.abs(p - np.array(col)).max() > 2:
            why.append(f"cell centroid pixel ({x:.0f}, {y:.0f}) is {p}, not {col}")
    for x, y in rows["WALL"]:
        p = img[int(y), int(x)]
        if p.max() > 80:
            why.append(f"wall midpoint pixel ({x:.0f}, {y:.0f}) is {p}, not dark")
    drawn, count = rows["INFO foam edges"][0]
    if drawn != count:
        why.append(f"{drawn:.0f} of {count:.0f} edges drawn")
    report(f"strings_foam_seed{seed}", not why, "; ".join(why[:3]))

with tempfile.TemporaryDirectory() as out:
    for name, fn in (("sphere", lambda: [sphere(out, s) for s in (42, 1234)]),
                     ("bubbles", lambda: bubbles(out, 7)),
                     ("catenoid", lambda: catenoid(out)),
                     ("plots", lambda: plots(out, 3)),
                     ("colors", lambda: colors(out)),
                     ("strings", lambda: strings_fixed(out)),
                     ("strings_foam", lambda: [strings_foam(out, s) for s in (7, 31)])):
        try:
            fn()
        except Exception as e:  # a crash of one group is a failure, not the end
            print(f"FAIL picture/{name}: {e}")
