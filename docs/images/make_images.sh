#!/usr/bin/env bash
# Makes README.md's example pictures from this build: each picture is the
# output of the README command written above it in README.md (the same
# command, at the size given here), scaled to 640 pixels wide with oiiotool
# (openimageio-tools) so each PNG stays small. The depth and Python pictures
# turn numpy arrays into images (Debian's python3-numpy). The viewer's
# screenshot needs Xvfb. Run from the source tree's root after the build:
#     docs/images/make_images.sh            (writes docs/images/example_*.png)
# real_files_lit.png, README's first picture, is two mvr render commands'
# output side by side; docs/cli.md ("How a real file is lit") gives them.
set -euo pipefail
cd "$(dirname "$0")/../.."
img=docs/images
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
py=/usr/bin/python3

# 1. stereo: README's `build/mvr render --demo stereo --out out/stereo`
build/mvr render --demo stereo --out "$out/stereo" --quiet
oiiotool "$out/stereo/contact_sheet.png" --resize 640x0 -o "$img/example_stereo.png"

# 2. 50 views on a sphere with depth: README's command at 128x128 per view
build/mvr render tests/data/peers/textured.gltf --layout sphere --views 50 --outputs depth \
    --size 128x128 --out "$out/sphere" --quiet
# the first 16 views' depth as grey (each view's nearest point bright, its
# farthest dark, nothing black), in the contact sheet's order (8 a row)
"$py" - "$out/sphere" <<'EOF'
import sys, numpy as np
d = sys.argv[1]
depth = [np.load("%s/depth_%04d.npy" % (d, k)) for k in range(16)]
rows = []
for r in range(2):
    tiles = []
    for x in depth[r * 8:(r + 1) * 8]:
        lo, hi = x[x > 0].min(), x[x > 0].max()
        g = np.where(x > 0, 255 - (x - lo) / (hi - lo) * 205, 0).astype(np.uint8)
        tiles.append(np.pad(g, 2))
    rows.append(np.hstack(tiles))
pic = np.vstack(rows)
with open(d + "/depth.pgm", "wb") as f:
    f.write(b"P5 %d %d 255\n" % (pic.shape[1], pic.shape[0]) + pic.tobytes())
EOF
oiiotool "$out/sphere/contact_sheet.png" --resize 640x0 -o "$img/example_sphere.png"
oiiotool "$out/sphere/depth.pgm" --resize 640x0 -o "$img/example_sphere_depth.png"

# 3. a dataset with COLMAP's model: README's command; views 0, 6, 12, 18 in a row
build/mvr render tests/data/peers/textured.gltf --layout orbit --views 24 --size 320x240 --outputs depth --split 0.9,0.1 --colmap \
    --out "$out/dataset" --quiet
oiiotool "$out/dataset/view_0000.png" "$out/dataset/view_0006.png" "$out/dataset/view_0012.png" \
    "$out/dataset/view_0018.png" --mosaic 4x1 --resize 640x0 -o "$img/example_dataset.png"

# 4. Python: README's example's arrays of view 0 (colour, depth, node ids)
PYTHONPATH=python "$py" - "$out" <<'EOF'
import sys, numpy as np, mvr
with mvr.Context() as ctx, mvr.Scene.load("tests/data/peers/textured.gltf") as scene, \
        mvr.Views.layout(scene, "orbit", count=12, aspect=4 / 3) as views, mvr.Environment() as env:
    f = ctx.render(scene, views, (320, 240), outputs=("color", "depth", "ids"),
                   environment=env, choose_exposure=True)[0]
color = f.color[..., :3]
hit = f.depth > 0
g = np.where(hit, 255 - (f.depth - f.depth[hit].min()) / np.ptp(f.depth[hit]) * 205, 0).astype(np.uint8)
depth = np.repeat(g[..., None], 3, axis=2)
palette = np.array([[0, 0, 0], [230, 159, 0], [86, 180, 233], [0, 158, 115], [240, 228, 66], [0, 114, 178]],
                   np.uint8)
ids = palette[np.where(hit, f.ids[..., 0] % 5 + 1, 0)]
pic = np.hstack([color, depth, ids])
with open(sys.argv[1] + "/python.ppm", "wb") as out:
    out.write(b"P6 %d %d 255\n" % (pic.shape[1], pic.shape[0]) + pic.tobytes())
EOF
oiiotool "$out/python.ppm" --resize 640x0 -o "$img/example_python.png"

# 5. the viewer: README's `build/mvr-viewer tests/data/peers/spheres.gltf
# --size 1280x640` (two square halves: the file's camera is square), its
# third frame saved
tests/run_with_xvfb.sh build/mvr-viewer tests/data/peers/spheres.gltf --size 1280x640 --frames 3 \
    --screenshot "$out/viewer.png"
oiiotool "$out/viewer.png" --resize 640x0 -o "$img/example_viewer.png"

ls -l "$img"/example_*.png
