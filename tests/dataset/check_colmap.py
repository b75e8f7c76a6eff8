#!/usr/bin/env python3
"""ctest dataset_colmap: COLMAP itself (Debian's `colmap` 3.8, on the CPU)
reads what `mvr render --colmap` writes and triangulates with its poses.

  check_colmap.py MVR WORK [--views N] [--size WxH]

1. A held textured model: a cube whose faces carry a seeded multi-scale
   noise texture (SIFT needs texture; a flat-coloured model gives no
   matches), written as glTF by this script (tests/dataset/scene_cube.py).
2. `mvr render cube.gltf --layout ring --views N --colmap --out WORK/out`.
3. `colmap model_converter` TXT -> BIN -> TXT: the poses and cameras read
   back are mvr's, to the 17 digits mvr writes.
4. COLMAP's own SIFT features and exhaustive matches on mvr's images, then
   `colmap point_triangulator` with mvr's poses held fixed (it sets every
   image's pose constant) and mvr's intrinsics not refined: COLMAP's
   `model_analyzer` must report over MIN_POINTS points with a mean
   reprojection error under 1 pixel (0.25 px here). Poses that are a
   little wrong fail: every camera moved 0.05 units sideways (about 6 px
   at the cube) gave 1.01 px in a trial.
Prints COLMAP's figures (docs/benchmarks.md quotes them). Exit 77 (skipped)
where colmap is missing, except under CI=true."""
import argparse
import os
import pathlib
import re
import shutil
import subprocess
import sys

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parent))
import scene_cube  # noqa: E402

MIN_POINTS = 300
MAX_ERROR_PX = 1.0


def run(cmd, log):
    with open(log, "w") as f:
        p = subprocess.run([str(c) for c in cmd], stdout=f, stderr=subprocess.STDOUT)
    if p.returncode != 0:
        print(pathlib.Path(log).read_text()[-4000:])
        raise SystemExit("dataset_colmap: failed (exit %d): %s" % (p.returncode, " ".join(map(str, cmd))))
    return pathlib.Path(log).read_text()


def read_model_txt(folder):
    """cameras {id: (model, w, h, params)}, images {name: (id, qvec, tvec, camera)} of a text model."""
    cams, imgs = {}, {}
    for line in (folder / "cameras.txt").read_text().splitlines():
        if line and not line.startswith("#"):
            f = line.split()
            cams[int(f[0])] = (f[1], int(f[2]), int(f[3]), [float(x) for x in f[4:]])
    lines = [ln for ln in (folder / "images.txt").read_text().splitlines() if not ln.startswith("#")]
    for k in range(0, len(lines), 2):
        f = lines[k].split()
        if not f:
            continue
        imgs[f[9]] = (int(f[0]), [float(x) for x in f[1:5]], [float(x) for x in f[5:8]], int(f[8]))
    return cams, imgs


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("mvr")
    ap.add_argument("work")
    ap.add_argument("--views", type=int, default=24)
    ap.add_argument("--size", default="640x480")
    a = ap.parse_args()
    if shutil.which("colmap") is None:
        print("dataset_colmap: no colmap on PATH (Debian: colmap, which scripts/setup installs)")
        sys.exit(1 if os.environ.get("CI") == "true" else 77)
    work = pathlib.Path(a.work).resolve()
    shutil.rmtree(work, ignore_errors=True)
    work.mkdir(parents=True)
    scene = scene_cube.write(work / "cube")
    out = work / "out"
    run([a.mvr, "render", scene, "--layout", "ring", "--views", a.views, "--size", a.size, "--colmap", "--outputs",
         "depth", "--quiet", "--out", out], work / "mvr.log")
    model = out / "colmap"
    cams, imgs = read_model_txt(model)
    assert len(imgs) == a.views and len(cams) >= 1, (len(imgs), len(cams))

    # 3. COLMAP reads the text model: to binary and back, the same numbers
    (work / "bin").mkdir()
    (work / "txt").mkdir()
    run(["colmap", "model_converter", "--input_path", model, "--output_path", work / "bin", "--output_type", "BIN"],
        work / "to_bin.log")
    run(["colmap", "model_converter", "--input_path", work / "bin", "--output_path", work / "txt", "--output_type",
         "TXT"], work / "to_txt.log")
    cams2, imgs2 = read_model_txt(work / "txt")
    assert cams2.keys() == cams.keys() and imgs2.keys() == imgs.keys()
    worst = 0.0
    for name, (iid, q, t, cam) in imgs.items():
        iid2, q2, t2, cam2 = imgs2[name]
        assert (iid2, cam2) == (iid, cam), name
        worst = max(worst, max(abs(x - y) for x, y in zip(q + t, q2 + t2)))
    for cid, (m, w, h, params) in cams.items():
        m2, w2, h2, params2 = cams2[cid]
        assert (m2, w2, h2) == (m, w, h) and max(abs(x - y) for x, y in zip(params, params2)) < 1e-9, cid
    assert worst < 1e-12, "poses changed through COLMAP's binary model by %g" % worst
    # mvr's own points (from depth) and their tracks survive COLMAP's reader
    def points(folder):
        rows = [ln.split() for ln in (folder / "points3D.txt").read_text().splitlines() if ln and ln[0] != "#"]
        return {int(r[0]): (tuple(float(x) for x in r[1:4]), len(r[8:]) // 2) for r in rows}
    mine, theirs = points(model), points(work / "txt")
    assert len(mine) > 100, "mvr wrote %d points" % len(mine)
    assert mine.keys() == theirs.keys() and all(
        mine[k][1] == theirs[k][1] and max(abs(x - y) for x, y in zip(mine[k][0], theirs[k][0])) < 1e-9
        for k in mine), "COLMAP read mvr's points3D differently"
    print("model_converter: %d images, %d cameras, %d points read back, poses equal to %.1e" %
          (len(imgs), len(cams), len(mine), worst))

    # 4. COLMAP's features on mvr's images, triangulated with mvr's poses
    params = {tuple(p) for (_, _, _, p) in cams.values()}
    assert len(params) == 1, "the views' intrinsics differ: %s" % params
    names = sorted(imgs)
    assert [imgs[n][0] for n in names] == list(range(1, len(names) + 1)), \
        "image ids do not follow the names' order (COLMAP's database numbers images in the order it reads them)"
    (work / "list.txt").write_text("\n".join(names) + "\n")
    db = work / "database.db"
    run(["colmap", "feature_extractor", "--database_path", db, "--image_path", out, "--image_list_path",
         work / "list.txt", "--ImageReader.camera_model", "PINHOLE", "--ImageReader.camera_params",
         ",".join(repr(x) for x in next(iter(params))), "--SiftExtraction.use_gpu", "0",
         "--SiftExtraction.num_threads", "2"], work / "features.log")
    run(["colmap", "exhaustive_matcher", "--database_path", db, "--SiftMatching.use_gpu", "0",
         "--SiftMatching.num_threads", "2"], work / "matches.log")
    tri = work / "triangulated"
    tri.mkdir()
    run(["colmap", "point_triangulator", "--database_path", db, "--image_path", out, "--input_path", model,
         "--output_path", tri, "--clear_points", "1", "--Mapper.ba_refine_focal_length", "0",
         "--Mapper.ba_refine_principal_point", "0", "--Mapper.ba_refine_extra_params", "0"], work / "triangulate.log")
    report = run(["colmap", "model_analyzer", "--path", tri], work / "analyze.log")
    points = int(re.search(r"Points:\s*(\d+)", report).group(1))
    error = float(re.search(r"Mean reprojection error:\s*([0-9.eE+-]+)", report).group(1))
    track = re.search(r"Mean track length:\s*([0-9.eE+-]+)", report)
    print("point_triangulator on mvr's poses: %d points, mean track length %s, mean reprojection error %.3f px" %
          (points, track.group(1) if track else "?", error))
    # the poses stayed mvr's (constant in COLMAP's bundle adjustment)
    cams3, imgs3 = read_model_txt_bin(tri, work)
    moved = max(max(abs(x - y) for x, y in zip(imgs[n][1] + imgs[n][2], imgs3[n][1] + imgs3[n][2])) for n in imgs3)
    assert moved < 1e-9, "COLMAP moved mvr's poses by %g" % moved
    assert points >= MIN_POINTS, "only %d points triangulated (at least %d expected)" % (points, MIN_POINTS)
    assert error < MAX_ERROR_PX, "mean reprojection error %.3f px (under %.1f expected)" % (error, MAX_ERROR_PX)
    print("dataset_colmap: passed")


def read_model_txt_bin(folder, work):
    """A model COLMAP wrote (binary) as text, read."""
    txt = work / (folder.name + "_txt")
    txt.mkdir(exist_ok=True)
    run(["colmap", "model_converter", "--input_path", folder, "--output_path", txt, "--output_type", "TXT"],
        work / (folder.name + "_txt.log"))
    return read_model_txt(txt)


main()
