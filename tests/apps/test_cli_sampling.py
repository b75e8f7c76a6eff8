#!/usr/bin/env python3
"""ctest: mvr render's camera sampling options (issue 33) reach the library: the cameras.json a
render writes shows them.

  python3 test_cli_sampling.py MVR FILE OUT

--fov: fl_y is the pinhole of that vertical field of view; --radius: every camera that far from
the centre of the bounds (mvr info --json); --hemisphere upper with --up z: none below the centre
along +Z, each camera's right axis level and its up leaning to +Z; --layout random --seed: the
same seed writes the same cameras, another seed others, no two closer than --min-spacing;
--margin: every bounds corner inside the image less the margin, touching it on one axis;
--elevation DEG (issue 35): stereo and ring views look down that many degrees, 30 by default. Usage
errors name the option. Python's standard library only."""
import json
import math
import os
import subprocess
import sys

MVR, FILE, OUT = sys.argv[1:4]
W, H = 64, 48
failures = []


def expect(ok, what):
    if not ok:
        failures.append(what)
        print("FAIL:", what)


def render(name, *args):
    out = os.path.join(OUT, name)
    run = subprocess.run([MVR, "render", FILE, "--size", "%dx%d" % (W, H), "--out", out, "--quiet"] + list(args),
                         capture_output=True, text=True)
    expect(run.returncode == 0, "%s: mvr render exits %d: %s" % (name, run.returncode, run.stderr))
    if run.returncode != 0:
        return None
    with open(os.path.join(out, "cameras.json")) as f:
        return json.load(f)["frames"]


info = json.loads(subprocess.run([MVR, "info", FILE, "--json"], capture_output=True, text=True, check=True).stdout)
lo, hi = info["bounds_min"], info["bounds_max"]
centre = [0.5 * (a + b) for a, b in zip(lo, hi)]
corners = [[(hi if (k >> a) & 1 else lo)[a] for a in range(3)] for k in range(8)]


def position(frame):
    return [frame["camera_to_world"][r][3] for r in range(3)]


def direction(frame):
    p = position(frame)
    d = [p[k] - centre[k] for k in range(3)]
    n = math.sqrt(sum(x * x for x in d))
    return [x / n for x in d], n


# --fov, --radius, --hemisphere upper, --up z, --layout random --seed --min-spacing
sampled = ["--layout", "random", "--views", "8", "--fov", "40", "--radius", "5", "--hemisphere", "upper", "--up",
           "z", "--seed", "3", "--min-spacing", "25"]
a = render("random_a", *sampled)
b = render("random_b", *sampled)
other = render("random_other", *(sampled[:-3] + ["4"] + sampled[-2:]))
if a and b and other:
    expect(len(a) == 8, "random: %d views" % len(a))
    with open(os.path.join(OUT, "random_a", "transforms.json")) as f:
        t = json.load(f)
    expect(t.get("up") == [0, 0, 1] and "+Z" in t.get("up_axis", ""),
           "transforms.json states up %r (%r), not --up z's" % (t.get("up"), t.get("up_axis")))
    expect([f["camera_to_world"] for f in a] == [f["camera_to_world"] for f in b], "random: seed 3 twice differs")
    expect(all(p["camera_to_world"] != q["camera_to_world"] for p, q in zip(a, other)),
           "random: seeds 3 and 4 share a camera")
    for i, f in enumerate(a):
        expect(abs(f["fl_y"] - 0.5 * H / math.tan(math.radians(20))) < 1e-9 * f["fl_y"],
               "view %d: fy %r is not --fov 40's" % (i, f["fl_y"]))
        d, dist = direction(f)
        expect(abs(dist - 5.0) < 1e-9, "view %d: %r from the centre, not --radius 5" % (i, dist))
        expect(d[2] >= -1e-12, "view %d: below the centre along +Z (--hemisphere upper --up z)" % i)
        right_z, up_z = f["camera_to_world"][2][0], f["camera_to_world"][2][1]
        expect(abs(right_z) < 1e-12 and up_z > 0, "view %d: right z %r, up z %r (--up z)" % (i, right_z, up_z))
        for j in range(i):
            e, _ = direction(a[j])
            angle = math.degrees(math.acos(max(-1.0, min(1.0, sum(x * y for x, y in zip(d, e))))))
            expect(angle >= 25.0 - 1e-9, "views %d and %d: %.3f degrees apart (--min-spacing 25)" % (j, i, angle))

# --margin: the bounding box fills the view less the margin (mvr info's bounds: 6 digits)
fitted = render("margin", "--layout", "sphere", "--views", "6", "--margin", "0.1")
for i, f in enumerate(fitted or []):
    m = f["world_to_camera"]
    extent = 0.0
    for p in corners:
        q = [sum(m[r][c] * p[c] for c in range(3)) + m[r][3] for r in range(3)]
        z = -q[2]
        u, v = f["fl_x"] * q[0] / z + f["cx"], f["fl_y"] * -q[1] / z + f["cy"]
        extent = max(extent, abs(u - f["cx"]) / (0.5 * W), abs(v - f["cy"]) / (0.5 * H))
    expect(abs(extent - 0.9) < 1e-4, "--margin 0.1 view %d: the box reaches %.6f of the half-image" % (i, extent))

# --elevation DEG (stereo, ring, grid): the views look down that many degrees; 0 is level;
# none given: 30 (issue 35)
for args, want in ((["--elevation", "20"], 20.0), (["--elevation", "0"], 0.0), ([], 30.0)):
    for layout in ("stereo", "ring"):
        frames = render("elevation_%s_%s" % (layout, "_".join(args) or "default"), "--layout", layout, *args)
        for i, f in enumerate(frames or []):
            back_y = f["camera_to_world"][1][2]  # the camera's +Z, from the scene toward it
            got = math.degrees(math.asin(max(-1.0, min(1.0, back_y))))
            expect(abs(got - want) < 1e-9, "--layout %s %s view %d: looks down %.9f degrees, not %g" % (
                layout, " ".join(args), i, got, want))

# usage errors, each naming the option
for args, needle in ((["--layout", "ring", "--seed", "1"], "--seed"),
                     (["--layout", "ring", "--hemisphere", "upper"], "--hemisphere"),
                     (["--fov", "40"], "--fov"),
                     (["--layout", "sphere", "--fov", "0"], "--fov"),
                     (["--layout", "sphere", "--fov", "nan"], "--fov"),
                     (["--layout", "sphere", "--radius", "-2"], "--radius"),
                     (["--layout", "sphere", "--radius", "2", "--margin", "0.1"], "--margin"),
                     (["--layout", "sphere", "--margin", "0.95"], "--margin"),
                     (["--layout", "random", "--min-spacing", "200"], "--min-spacing"),
                     (["--layout", "sphere", "--elevation", "10"], "--elevation"),
                     (["--layout", "ring", "--elevation", "10,20"], "--elevation"),
                     (["--layout", "stereo", "--elevation", "90"], "--elevation"),
                     (["--layout", "cube", "--elevation", "20"], "--elevation"),
                     (["--layout", "sphere", "--elevation", "40,10"], "--elevation"),
                     (["--layout", "sphere", "--up", "x"], "--up"),
                     (["--layout", "cube", "--fov", "40"], "--fov")):
    run = subprocess.run([MVR, "render", FILE, "--out", os.path.join(OUT, "refused"), "--quiet"] + args,
                         capture_output=True, text=True)
    expect(run.returncode == 2 and needle in run.stderr,
           "%s: exit %d, %r (expected 2 naming %s)" % (" ".join(args), run.returncode, run.stderr.strip(), needle))
run = subprocess.run([MVR, "render", "--help"], capture_output=True, text=True)
for option in ("--fov", "--radius", "--margin", "--hemisphere", "--seed", "--min-spacing", "--elevation", "--up"):
    expect(option in run.stdout, "--help does not list %s" % option)

print("%d failures" % len(failures))
sys.exit(1 if failures else 0)
