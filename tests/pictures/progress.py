"""progress.py: the live progress line, driven through a pseudo-terminal.

Usage: /usr/bin/python3 tests/pictures/progress.py TDS (from the project
root). On a terminal a long `g` or `pg` redraws one line ending in '\\r'
(iteration, energy, scale or r, rate, time left) at most four times a
second and leaves Evolver's last line; through a pipe every iteration
prints its line; -q prints none; verbose(true) brings the lines back on
the terminal."""
import os
import pty
import re
import subprocess
import sys
import time

TDS = sys.argv[1]  # (argv[2], the build folder, is not needed here)
N = 300
SETUP = "for i = 1, 4 do r() end; "


def on_tty(args):
    """Run tds with stdout and stderr on a new pseudo-terminal; returns
    (output, seconds)."""
    master, slave = pty.openpty()
    t0 = time.monotonic()
    p = subprocess.Popen([TDS] + args, stdout=slave, stderr=slave,
                         stdin=subprocess.DEVNULL)
    os.close(slave)
    chunks = []
    while True:
        try:
            data = os.read(master, 65536)
        except OSError:  # EIO: the child closed the terminal
            break
        if not data:
            break
        chunks.append(data)
    p.wait()
    os.close(master)
    return b"".join(chunks).decode().replace("\r\n", "\n"), time.monotonic() - t0


def report(name, ok, why):
    print(f"PASS progress/{name}" if ok else f"FAIL progress/{name}: {why}")


LIVE_G = re.compile(r"g (\d+)/(\d+)  energy (\S+)  scale (\S+)  (\S+) it/s  (\S+) left")
LIVE_PG = re.compile(r"pg (\d+)/(\d+)  energy (\S+)  r (\S+)  (\S+) it/s")
EVOLVER = re.compile(r"^ *(\d+)\. area: +(\S+) energy: +(\S+)  scale: (\S+)$", re.M)


def live_lines(out, pattern):
    """The redrawn lines: text after each '\\r', matched by pattern."""
    return [m for m in (pattern.match(seg.strip()) for seg in out.split("\r")[1:]) if m]


def test_g():
    out, secs = on_tty(["scripts/cube.tds", "-e", SETUP + f"g({N}); print('E', total_energy)"])
    draws = live_lines(out, LIVE_G)
    final = float(re.search(r"^E\s+(\S+)$", out, re.M).group(1))
    why = []
    if not draws:
        why.append(f"no live line in {out[-300:]!r}")
    # at most four redraws a second (plus one), each with a sane content
    if len(draws) > 4 * secs + 1:
        why.append(f"{len(draws)} redraws in {secs:.1f} s")
    last_k = 0
    for m in draws:
        k, n, e = int(m.group(1)), int(m.group(2)), float(m.group(3))
        if n != N or not (last_k < k <= N) or not (final - 1e-9 <= e <= 6.0):
            why.append(f"bad live line {m.group(0)!r}")
            break
        last_k = k
    shown = "\n".join(l.split("\r")[-1] for l in out.split("\n"))  # as on screen
    lines = EVOLVER.findall(shown)
    # only Evolver's last line (countdown 1) remains, with the final energy
    if len(lines) != 1 or lines[0][0] != "1" or abs(float(lines[0][2]) - final) > 1e-9 * final:
        why.append(f"expected one final iteration line, got {lines[:3]}")
    report("g_live_line", not why, "; ".join(why))


def test_pg():
    # long enough for a redraw (every 0.25 s) on a fast, idle machine
    out, secs = on_tty(["scripts/cube.tds", "-e", SETUP + "pg(3000)"])
    draws = live_lines(out, LIVE_PG)
    why = []
    if not draws:
        why.append(f"no live line in {out[-300:]!r}")
    for m in draws:
        if int(m.group(2)) != 3000 or not (0 < int(m.group(1)) <= 3000) or float(m.group(4)) <= 0:
            why.append(f"bad live line {m.group(0)!r}")
            break
    if re.search(r"^pg +\d+  r ", out, re.M):
        why.append("per-iteration pg lines printed on the terminal")
    if not re.search(r"pg: \d+ iterations", out):
        why.append("no pg summary line")
    report("pg_live_line", not why, "; ".join(why))


def test_pipe_quiet_verbose():
    code = SETUP + "g(20)"
    piped = subprocess.run([TDS, "scripts/cube.tds", "-e", code], capture_output=True,
                           text=True).stdout
    n = len(EVOLVER.findall(piped))
    report("g_pipe_lines", n == 20 and "\r" not in piped,
           f"{n} iteration lines through a pipe (want 20, no \\r)")
    quiet, _ = on_tty(["-q", "scripts/cube.tds", "-e", code])
    report("g_quiet_terminal", EVOLVER.search(quiet) is None and "\r" not in quiet.replace("\n", ""),
           f"-q printed {quiet[-200:]!r}")
    verb, _ = on_tty(["scripts/cube.tds", "-e", "verbose(true); " + code])
    n = len(EVOLVER.findall(verb))
    report("g_verbose_terminal", n == 20 and not live_lines(verb, LIVE_G),
           f"{n} iteration lines with verbose(true) on a terminal (want 20)")


for t in (test_g, test_pg, test_pipe_quiet_verbose):
    try:
        t()
    except Exception as e:
        print(f"FAIL progress/{t.__name__}: {e}")
