"""The Python package against the command line: the same inputs give the same numbers, bit for
bit (points, pictures, raw weights, verdicts), and broken rules the same messages.

The command line is the program at $BENTSTRAW (default: the workspace's release build).
"""

import csv
import json
import math
import os
import pickle
import struct
import subprocess
import sys
import threading
import zlib
from pathlib import Path

import numpy as np
import pytest

import bentstraw

ROOT = Path(__file__).resolve().parents[3]
BENTSTRAW = os.environ.get("BENTSTRAW", str(ROOT / "target" / "release" / "bentstraw"))
REF2 = dict(observer=(0.1, 0, 0.1), straw=(0, 0.02), water_height=0.1)
REF2_FLAGS = ["--observer", "0.1,0,0.1", "--straw", "0,0.02", "--water-height", "0.1"]


def run(*args, ok=True):
    """Runs the command line; its completed process."""
    assert Path(BENTSTRAW).is_file(), f"the command line is needed at {BENTSTRAW}"
    p = subprocess.run([BENTSTRAW, *map(str, args)], capture_output=True, text=True)
    if ok:
        assert p.returncode == 0, p.stderr
    return p


def read_points(path):
    """A points CSV as (header, rows of strings)."""
    with open(path, newline="") as f:
        rows = list(csv.reader(f))
    return rows[0], rows[1:]


def number(text):
    """A CSV number: empty is not defined (nan)."""
    return float(text) if text != "" else math.nan


def same_bits(a, b):
    """Equal to the bit, nan equal to nan."""
    a, b = np.asarray(a, dtype=np.float64), np.asarray(b, dtype=np.float64)
    return a.shape == b.shape and np.array_equal(a.view(np.uint64), b.view(np.uint64))


def simulated(tmp_path, flags, **kwargs):
    """The command line's points for `flags` and the package's for `kwargs`."""
    out = tmp_path / "points.csv"
    run("simulate", *flags, "--output", out)
    return read_points(out), bentstraw.simulate(**kwargs)


def assert_same_points(header, rows, sim):
    xyz = np.array([[number(r[0]), number(r[1]), number(r[2])] for r in rows])
    assert same_bits(sim.xyz, xyz.reshape(-1, 3))
    assert np.array_equal(sim.color, [int(r[3]) for r in rows])
    for k, name in enumerate(header[4:], start=4):
        values = [r[k] for r in rows]
        got = getattr(sim, name)
        if isinstance(got, list):
            assert got == values, name
        else:
            assert same_bits(got, [number(v) for v in values]), name


@pytest.mark.parametrize(
    "flags, kwargs",
    [
        (REF2_FLAGS, REF2),
        (
            REF2_FLAGS + ["--n-water", "1.5", "--max-events", "4", "--points", "5000"],
            dict(REF2, n_water=1.5, max_events=4, points=5000),
        ),
        (REF2_FLAGS + ["--image-model", "eye", "--points", "3000"], dict(REF2, image_model="eye", points=3000)),
        (
            REF2_FLAGS + ["--image-model", "stereo", "--points", "3000"],
            dict(REF2, image_model="stereo", points=3000),
        ),
        (["--scene", "leaning-straw", "--points", "4000"], dict(scene="leaning-straw", points=4000)),
        (
            ["--scene", "reversing-arrow", "--observer", "0,-0.4,0.1", "--image-model", "eye", "--points", "2000"],
            dict(scene="reversing-arrow", observer=(0, -0.4, 0.1), image_model="eye", points=2000),
        ),
    ],
)
def test_points_are_the_command_lines_bit_for_bit(tmp_path, flags, kwargs):
    (header, rows), sim = simulated(tmp_path, flags, **kwargs)
    assert len(rows) == len(sim) > 100
    assert_same_points(header, rows, sim)


def test_a_scene_file_by_path_from_text_and_by_name_gives_the_same_points(tmp_path):
    text = (ROOT / "scenes" / "leaning-straw.toml").read_text()
    mine = tmp_path / "mine.toml"
    mine.write_text(text)
    (header, rows), by_path = simulated(tmp_path, ["--scene", mine, "--points", "3000"], scene=mine, points=3000)
    assert_same_points(header, rows, by_path)
    for scene in [str(mine), bentstraw.Scene.load(mine), bentstraw.Scene.from_toml(text, name="mine.toml"),
                  bentstraw.Scene.gallery("leaning-straw"), "leaning-straw"]:
        assert_same_points(header, rows, bentstraw.simulate(scene, points=3000))


def test_each_point_knows_its_light_path_and_the_ray_traced_alone_agrees():
    sim = bentstraw.simulate(**REF2, points=2000)
    assert set(sim.path) <= set(sim.path_keys) and len(sim.path) == len(sim)
    # Reference 2 sees the straw through the wall directly and after a total reflection.
    assert {"wall", "wall+1"} <= set(sim.path)
    for k in [0, len(sim) // 2, len(sim) - 1]:
        ray = bentstraw.trace(**REF2, direction=sim.direction[k])
        assert ray["path_key"] == sim.path[k]
        assert ray["path_length"] == sim.path_length[k]
        assert ray["image_point"] == list(sim.image_xyz[k])
        assert ray["color"] == sim.color[k]
        assert len(ray["events"]) == sim.events[k]
        # Snell's law at every refraction the ray reports.
        for e in ray["events"]:
            if e["event"] == "refraction":
                a, b = math.radians(e["incidence_deg"]), math.radians(e["outgoing_deg"])
                assert abs(e["n1"] * math.sin(a) - e["n2"] * math.sin(b)) < 1e-12


def decode_png(data):
    """The pixels of an 8-bit RGB PNG (non-interlaced), as an (h, w, 3) array."""
    assert data[:8] == b"\x89PNG\r\n\x1a\n"
    pos, idat, width = 8, b"", None
    while pos < len(data):
        n, kind = struct.unpack(">I4s", data[pos : pos + 8])
        body = data[pos + 8 : pos + 8 + n]
        if kind == b"IHDR":
            width, height, depth, colour, _, _, interlace = struct.unpack(">IIBBBBB", body)
            assert (depth, colour, interlace) == (8, 2, 0)
        elif kind == b"IDAT":
            idat += body
        pos += 12 + n
    raw, stride = zlib.decompress(idat), 3 * width
    out = np.zeros((height, stride), dtype=np.uint8)
    prev = np.zeros(stride, dtype=np.int32)
    for y in range(height):
        f, line = raw[y * (stride + 1)], np.frombuffer(raw, np.uint8, stride, y * (stride + 1) + 1).astype(np.int32)
        cur = np.zeros(stride, dtype=np.int32)
        for x in range(stride):
            a = cur[x - 3] if x >= 3 else 0
            b, c = prev[x], (prev[x - 3] if x >= 3 else 0)
            if f == 0:
                p = 0
            elif f == 1:
                p = a
            elif f == 2:
                p = b
            elif f == 3:
                p = (a + b) // 2
            else:
                pa, pb, pc = abs(b - c), abs(a - c), abs(a + b - 2 * c)
                p = a if pa <= pb and pa <= pc else (b if pb <= pc else c)
            cur[x] = (line[x] + p) & 0xFF
        out[y], prev = cur, cur
    return out.reshape(height, width, 3)


@pytest.mark.parametrize(
    "flags, kwargs",
    [
        (["--observer", "0.3,0,0.22", "--straw", "-0.02,0.02", "--water-height", "0.15"],
         dict(observer=(0.3, 0, 0.22), straw=(-0.02, 0.02), water_height=0.15)),
        (["--scene", "oil-on-water", "--mode", "course", "--backdrop", "none", "--samples", "1", "--fov", "30"],
         dict(scene="oil-on-water", mode="course", backdrop="none", samples=1, fov=30)),
        # A coin and no card: the raw file still gives a weight for every colour code.
        (["--scene", "coin-in-glass", "--samples", "1"], dict(scene="coin-in-glass", samples=1)),
        # Every pixel sampled 3x3.
        (["--scene", "prism", "--sampling", "full"], dict(scene="prism", sampling="full")),
    ],
)
def test_pictures_are_the_pngs_pixel_for_pixel_and_raw_weights_the_csvs(tmp_path, flags, kwargs):
    png, raw = tmp_path / "view.png", tmp_path / "raw.csv"
    run("render", *flags, "--size", "96x72", "--output", png, "--raw", raw)
    picture, weights = bentstraw.render(**kwargs, size=(96, 72), weights=True)
    assert picture.shape == (72, 96, 3) and picture.dtype == np.uint8
    assert np.array_equal(picture, decode_png(png.read_bytes()))
    assert np.array_equal(bentstraw.render(**kwargs, size=(96, 72)), picture)
    with open(raw, newline="") as f:
        rows = list(csv.reader(f))[1:]
    values = np.array([[float(v) for v in r[2:]] for r in rows])
    if weights.ndim == 2:  # course: a colour code per pixel
        assert np.array_equal(weights.reshape(-1), values[:, 0])
    else:
        assert same_bits(weights.reshape(len(rows), -1), values)


def test_a_picture_knows_the_field_of_view_the_command_line_drew_it_with(tmp_path):
    # Framed by default: the command line says the field of view it chose; the picture holds it,
    # and drawing again with that field of view gives the same pixels.
    p = run("render", "--scene", "leaning-straw", "--size", "64x48", "--output", tmp_path / "v.png")
    said = float((p.stdout + p.stderr).split("fov ")[1].split("°")[0])
    picture = bentstraw.render("leaning-straw", size=(64, 48))
    assert isinstance(picture, bentstraw.Picture) and round(picture.fov, 2) == said
    assert np.array_equal(bentstraw.render("leaning-straw", size=(64, 48), fov=picture.fov), picture)
    again = pickle.loads(pickle.dumps(picture))
    assert again.fov == picture.fov and np.array_equal(again, picture)
    # A picture sliced or copied stays a picture of that view.
    assert picture[10:20].fov == picture.fov and picture.copy().fov == picture.fov


def test_a_pixel_maps_to_the_direction_of_its_ray():
    # Course mode with its colour codes: where a pixel and its eight neighbours all show one
    # object's colour, the ray along the picture's direction for that pixel reaches it.
    picture, codes = bentstraw.render("leaning-straw", size=(320, 240), mode="course", weights=True)
    eye = bentstraw.Scene.gallery("leaning-straw")
    inside = [(i, j) for i in range(1, 239) for j in range(1, 319)
              if codes[i, j] > 0 and (codes[i - 1:i + 2, j - 1:j + 2] == codes[i, j]).all()]
    checked = 0
    for i, j in inside[::max(1, len(inside) // 40)]:
        ray = bentstraw.trace(eye, direction=picture.direction(i, j))
        assert ray["outcome"] != "escaped" and ray["color"] == codes[i, j], (i, j, ray)
        checked += 1
    assert checked >= 5
    assert tuple(picture.eye) == tuple(bentstraw.simulate("leaning-straw", points=10).observer)
    # The picture's middle (between its four central pixels) is the direction it looks along.
    assert np.allclose(picture.direction(119.5, 159.5), picture.forward)
    assert np.isclose(np.linalg.norm(picture.direction(0, 0)), 1.0)
    assert "Picture 320x240" in repr(picture)


def test_reports_and_rays_say_what_they_hold_and_pickle():
    sim = bentstraw.simulate(**REF2, points=500)
    report = bentstraw.check(sim.xyz, sim.color, **REF2)
    assert isinstance(report, dict) and report["verdict"] == "pass"
    assert repr(report).startswith("<CheckReport: pass, ") and "points correct" in repr(report)
    ray = bentstraw.trace(**REF2, direction=sim.direction[0])
    assert repr(ray).startswith(f"<Ray: {ray['path']}, {len(ray['events'])} events, reaches ")
    for value in (report, ray):
        again = pickle.loads(pickle.dumps(value))
        assert type(again) is type(value) and again == value


@pytest.mark.parametrize("model, name", [("course", "p.csv"), ("eye", "p.csv"), ("course", "p.json"),
                                         ("stereo", "p.json"), ("course", "p.ply"), ("eye", "p.ply")])
def test_save_writes_the_command_lines_bytes(tmp_path, model, name):
    run("simulate", *REF2_FLAGS, "--points", "1500", "--image-model", model, "--output", tmp_path / ("cli-" + name))
    sim = bentstraw.simulate(**REF2, points=1500, image_model=model)
    sim.save(tmp_path / name)
    assert (tmp_path / name).read_bytes() == (tmp_path / ("cli-" + name)).read_bytes()
    # A bad name is refused, nothing written; a pickled simulation says why it cannot save.
    with pytest.raises(ValueError, match="txt"):
        sim.save(tmp_path / "p.txt")
    assert not (tmp_path / "p.txt").exists()
    with pytest.raises(ValueError, match="pickle"):
        pickle.loads(pickle.dumps(sim)).save(tmp_path / name)


def test_a_sweep_is_each_simulation_alone_with_a_progress_bar_when_asked(capfd):
    values = [1.0, 1.25, 1.333, 1.5]
    sims = bentstraw.sweep("n_water", np.array(values), **REF2, points=1500, progress=False)
    for n, sim in zip(values, sims):
        alone = bentstraw.simulate(**REF2, n_water=n, points=1500)
        assert same_bits(sim.xyz, alone.xyz) and np.array_equal(sim.color, alone.color)
    # Water of index 1 bends nothing: the image is the straw itself; denser water moves it.
    assert np.allclose(sims[0].xyz, sims[0].object_point)
    assert not np.allclose(sims[2].xyz, sims[2].object_point)
    heights = bentstraw.sweep("water_height", [0.05, 0.1], observer=(0.1, 0, 0.1), straw=(0, 0.02), points=500)
    assert [len(s) > 0 for s in heights] == [True, True]
    # The bar (tqdm's) when asked; none for a sweep under a second.
    capfd.readouterr()
    bentstraw.sweep("n_water", [1.2, 1.3], **REF2, points=500, progress=True)
    assert "bentstraw.sweep" in capfd.readouterr().err
    bentstraw.sweep("n_water", [1.2, 1.3], **REF2, points=500)
    assert "bentstraw.sweep" not in capfd.readouterr().err
    with pytest.raises(TypeError, match="radius"):
        bentstraw.sweep("radius", [1, 2], **REF2)
    with pytest.raises(TypeError, match="both swept and shared"):
        bentstraw.sweep("n_water", [1.2], n_water=1.3, observer=(0.1, 0, 0.1), straw=(0, 0.02), water_height=0.1)
    with pytest.raises(TypeError, match="sequence"):
        bentstraw.sweep("n_water", {1.2, 1.3}, **REF2)


def test_a_simulation_as_a_dataframe_holds_its_columns():
    import pandas  # noqa: F401  (CI installs it: the package itself does not need it)
    sim = bentstraw.simulate(**REF2, points=800, image_model="eye")
    df = sim.to_dataframe()
    assert list(df.columns[:4]) == ["x", "y", "z", "color"] and len(df) == len(sim)
    assert np.array_equal(df[["x", "y", "z"]].to_numpy(), sim.xyz, equal_nan=True)
    assert (df["path"].to_numpy() == sim.path).all() and np.array_equal(df["s_h"], sim.s_h, equal_nan=True)
    assert np.array_equal(df[["object_x", "object_y", "object_z"]].to_numpy(), sim.object_point)


def test_plots_return_the_figure_and_axes_with_the_results_drawn():
    matplotlib = pytest.importorskip("matplotlib")
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    sim = bentstraw.simulate(**REF2, points=2000)
    fig, ax = sim.plot()
    assert ax.figure is fig and ax.name == "3d"
    # One set of points per colour, in that colour, named in the legend.
    codes = np.unique(sim.color)
    assert len(ax.collections) == len(codes)
    for code, drawn in zip(codes, ax.collections):
        assert np.array_equal(np.column_stack(drawn._offsets3d), sim.xyz[sim.color == code])
        assert np.allclose(drawn.get_facecolor()[0][:3], bentstraw.COLOR_RGB[code - 1])
    assert [t.get_text() for t in ax.get_legend().get_texts()] == [bentstraw.COLOR_NAMES[c - 1] for c in codes]
    # By light path: one set of points per kind, named in words in the legend.
    fig2, ax2 = plt.subplots(subplot_kw={"projection": "3d"})
    assert sim.plot(ax2, color_by="path") == (fig2, ax2)
    assert [t.get_text() for t in ax2.get_legend().get_texts()] == sim.path_words
    assert sum(len(c._offsets3d[0]) for c in ax2.collections) == len(sim)
    with pytest.raises(ValueError, match="color_by"):
        sim.plot(color_by="colour")
    # A ray: its broken path through each event to the object, and the line of sight to where
    # the eye sees it.
    ray = bentstraw.trace(**REF2, direction=sim.direction[5])
    fig4, ax4 = bentstraw.ray_diagram(**REF2, direction=sim.direction[5])
    path, sight = (np.column_stack(line.get_data_3d()) for line in ax4.lines)
    expected = [ray["observer"]] + [e["point"] for e in ray["events"]] + [ray["straw_point"]]
    assert np.allclose(path, expected) and np.allclose(sight, [ray["observer"], ray["image_point"]])
    assert ax4.get_title() == ray["path"]
    picture = bentstraw.render(**REF2, size=(40, 30))
    fig3, ax3 = picture.plot()
    assert np.array_equal(ax3.images[0].get_array(), picture)
    assert f"{picture.fov:.1f}" in ax3.get_title()
    plt.close("all")


def test_check_gives_the_command_lines_verdicts(tmp_path):
    sim = bentstraw.simulate(**REF2, points=3000)
    faulty = sim.xyz.copy()
    faulty[::7, 2] += 0.004  # a student who got some lengths wrong
    colors = sim.color.copy()
    colors[::11] = 5 - colors[::11] + 1  # and some colours
    for xyz, color in [(sim.xyz, sim.color), (faulty, colors), (sim.xyz[::40], sim.color[::40])]:
        path = tmp_path / "solution.csv"
        np.savetxt(path, np.column_stack([xyz, color]), delimiter=",", fmt=["%.17g"] * 3 + ["%d"])
        cli = json.loads(run("check", path, *REF2_FLAGS, "--json", ok=False).stdout)
        mine = bentstraw.check(xyz, color, **REF2)
        for key in ["seconds", "file"]:
            cli.pop(key), mine.pop(key)
        assert mine == cli
    assert bentstraw.check(sim.xyz, sim.color, **REF2)["verdict"] == "pass"
    assert bentstraw.check(faulty, colors, **REF2)["verdict"] == "fail"


def test_grade_writes_the_command_lines_files_and_returns_its_rows(tmp_path):
    """A class of three (a pass, a fail, a malformed file, files missing) as a folder and as a zip:
    the rows are the gradebook's, and the files the command line's, byte for byte."""
    import zipfile

    class_dir = tmp_path / "class"
    flags = ["--observer", "0,0.1,0.1", "--straw", "0.02,0.01", "--water-height", "0.15"]
    for student in ["ada", "bob", "carl"]:
        (class_dir / student).mkdir(parents=True)
    run("simulate", *flags, "--points", "3000", "--output", class_dir / "ada" / "sim1.csv")
    run("simulate", "--observer", "0.1,0,0.1", "--straw", "0.02,0.01", "--water-height", "0.15",
        "--points", "3000", "--output", class_dir / "bob" / "sim1.csv")
    (class_dir / "carl" / "sim1.txt").write_text("x y z color\n0.1 0.2 oops 1\n")
    rows = bentstraw.grade(class_dir, tmp_path / "py")
    run("grade", class_dir, "--out", tmp_path / "cli")
    for name in ["grades.csv", "index.html", "ada/index.html", "bob/results.json"]:
        assert (tmp_path / "py" / name).read_bytes() == (tmp_path / "cli" / name).read_bytes(), name
    with open(tmp_path / "cli" / "grades.csv", newline="") as f:
        book = list(csv.DictReader(f))
    assert len(rows) == len(book) == 12
    for row, line in zip(rows, book):
        for key in ["student", "case", "verdict", "note"]:
            assert str(row[key]) == line[key]
        for key in ["score", "max_score", "points", "correct"]:
            assert float(row[key]) == float(line[key])
    verdicts = {(r["student"], r["case"]): r for r in rows}
    assert verdicts["ada", "sim1"]["verdict"] == "pass"
    assert verdicts["bob", "sim1"]["verdict"] == "fail" and 0 < verdicts["bob", "sim1"]["score"] < 25
    assert verdicts["carl", "sim1"]["verdict"] == "unreadable"
    assert "line 2" in verdicts["carl", "sim1"]["note"]
    assert verdicts["ada", "sim2"]["verdict"] == "missing"
    # A zip of the same folders grades the same.
    with zipfile.ZipFile(tmp_path / "class.zip", "w", zipfile.ZIP_DEFLATED) as z:
        for f in sorted(class_dir.rglob("*.*")):
            z.write(f, f.relative_to(tmp_path))
    assert bentstraw.grade(tmp_path / "class.zip", tmp_path / "zipped") == rows
    fr = bentstraw.grade(class_dir, tmp_path / "fr", lang="fr")
    assert [r["score"] for r in fr] == [r["score"] for r in rows]
    assert "<html lang=\"fr\">" in (tmp_path / "fr" / "bob" / "index.html").read_text()
    with pytest.raises(ValueError, match="no sub-folder"):
        bentstraw.grade(tmp_path / "fr" / "ada", tmp_path / "none")
    assert not (tmp_path / "none").exists()
    with pytest.raises(ValueError, match="language"):
        bentstraw.grade(class_dir, tmp_path / "none", lang="de")


def test_assert_solution_passes_the_image_and_fails_the_rest_with_its_partial_score():
    sim = bentstraw.simulate(**REF2, points=3000)
    assert bentstraw.assert_solution(sim.xyz, sim.color, **REF2)["verdict"] == "pass"
    # Every third point's length wrong, and only the upper half of the image: a fail, scored by
    # the share of right points times the coverage over the coverage asked for.
    upper = sim.xyz[:, 2] > np.median(sim.xyz[:, 2])
    xyz, color = sim.xyz[upper].copy(), sim.color[upper]
    xyz[::3, 2] += 0.004
    with pytest.raises(AssertionError) as e:
        bentstraw.assert_solution(xyz, color, **REF2, points=10)
    report = bentstraw.check(xyz, color, **REF2)
    share = report["correct"] / report["points"]
    coverage = min(report["coverage"].values()) if isinstance(report["coverage"], dict) else min(report["coverage"])
    expected = 10 * share * min(1.0, coverage / bentstraw.DEFAULT_MIN_COVERAGE)
    assert isinstance(e.value, bentstraw.SolutionError)
    assert abs(e.value.score - expected) <= 0.006 and e.value.max_score == 10
    message = str(e.value)
    assert f"{report['points'] - report['correct']} of {report['points']} points wrong" in message
    assert "of its image" in message and "partial score" in message
    # Each missing region named as check names it.
    for region in e.value.row["missing"]:
        assert region in message
    assert len(e.value.row["missing"]) >= 1


@pytest.mark.parametrize(
    "call, words",
    [
        (lambda: bentstraw.simulate(**dict(REF2, water_height=-1)), "water height -1 m"),
        (lambda: bentstraw.simulate(observer=(0, 0, 0.1), straw=(0, 0.02), water_height=0.1), "observer"),
        (lambda: bentstraw.simulate(**REF2, points=0), "points=0 is not allowed"),
        (lambda: bentstraw.simulate(**REF2, points=3_000_000, image_model="eye"), "points=3000000 is too many"),
        (lambda: bentstraw.simulate(**REF2, image_model="retina"), "'retina' for 'image_model'"),
        (lambda: bentstraw.simulate(**dict(REF2, max_events=0)), "0"),
        (lambda: bentstraw.simulate(observer=(0.1, 0, 0.1)), "straw and water_height, or a scene file"),
        (lambda: bentstraw.render(**REF2, mode="photon"), "'photon' for 'mode'"),
        (lambda: bentstraw.render(**REF2, samples=17, prune=2), "prune=2 is not allowed"),
        (lambda: bentstraw.render(**REF2, size=(0, 10)), "0"),
        (lambda: bentstraw.check([[0, 0, 0]], [9], **REF2), "point 0: colour 9"),
        (lambda: bentstraw.check([[0, 0, math.nan]], [1], **REF2), "point 0: z = NaN"),
        (lambda: bentstraw.check([[0, 0, 0]], [1, 2], **REF2), "1 points but 2 colours"),
        (lambda: bentstraw.check([[0, 0]], [1], **REF2), "(N, 3)"),
        (lambda: bentstraw.check([[0, 0, 0]], [1], **REF2, tolerance=-1, min_coverage=2), "tolerance=-1"),
        (lambda: bentstraw.trace(**REF2, direction=(0, 0, 0)), "direction (0, 0, 0)"),
        (lambda: bentstraw.trace(**REF2, direction=(1, 0, 0), toward=(0, 0, 0)), "not both"),
        (lambda: bentstraw.Scene.from_toml('[container]\nshape = "glass"\nradius = -1\nheight = 0.2\n'), "radius"),
        (lambda: bentstraw.render(**REF2, size=(-3, 10)), "size (-3, 10)"),
        (lambda: bentstraw.Scene.gallery("teapot"), "teapot"),
    ],
)
def test_a_broken_rule_raises_value_error_naming_the_value(call, words):
    with pytest.raises(ValueError) as e:
        call()
    assert words in str(e.value)


@pytest.mark.parametrize(
    "call, words",
    [
        (lambda: bentstraw.simulate(**dict(REF2, observer="123")), "observer must be a sequence or array of 3 numbers, not str"),
        (lambda: bentstraw.simulate(**dict(REF2, observer={0.1, 0.0, 0.2})), "observer must be a sequence or array of 3 numbers, not set"),
        (lambda: bentstraw.simulate(**dict(REF2, straw={"x": 0, "y": 0.02})), "straw must be a sequence or array of 2 numbers, not dict"),
        (lambda: bentstraw.simulate(**dict(REF2, straw=(0, "0.02"))), "straw must be a number, not str"),
        (lambda: bentstraw.simulate(**dict(REF2, observer=(0.1, True, 0.1))), "observer must be a number, not bool"),
        (lambda: bentstraw.simulate(**dict(REF2, water_height="0.15")), "water_height must be a number, not str"),
        (lambda: bentstraw.simulate(**REF2, points=1000.0), "points must be a whole number, not float"),
        (lambda: bentstraw.simulate(**REF2, max_events=True), "max_events must be a whole number, not bool"),
        (lambda: bentstraw.render(**REF2, weights="no"), "weights must be True or False, not str"),
        (lambda: bentstraw.render(**REF2, fov="wide"), "fov must be a number, not str"),
        (lambda: bentstraw.render(**REF2, prune="0.01"), "prune must be a number, not str"),
    ],
)
def test_a_value_of_the_wrong_type_raises_type_error_naming_its_keyword(call, words):
    with pytest.raises(TypeError) as e:
        call()
    assert words in str(e.value)


def test_numbers_beyond_the_engines_integers_are_value_errors_naming_their_keyword():
    for call, words in [
        (lambda: bentstraw.render(**REF2, samples=2**40), "samples must be a whole number from 0 to"),
        (lambda: bentstraw.simulate(**REF2, points=2**70), "points must be a whole number from 0 to"),
    ]:
        with pytest.raises(ValueError, match=words):
            call()
    # numpy's numbers and arrays are numbers and vectors: the same points as plain ones.
    plain = bentstraw.simulate(**REF2, points=500)
    arrays = bentstraw.simulate(
        observer=np.array([0.1, 0.0, 0.1]), straw=np.array([0, 0.02]), water_height=np.float64(0.1), points=np.int64(500)
    )
    assert np.array_equal(plain.xyz, arrays.xyz)


def test_the_command_lines_messages_and_every_broken_rule_at_once(tmp_path):
    p = run("simulate", *REF2_FLAGS[:4], "--water-height", "-1", "--output", tmp_path / "x.csv", ok=False)
    with pytest.raises(ValueError) as e:
        bentstraw.simulate(**dict(REF2, water_height=-1))
    assert str(e.value) in p.stderr
    # The command line's words, its flags written as the keywords the call was given.
    p = run("simulate", *REF2_FLAGS, "--points", "0", "--output", tmp_path / "x.csv", ok=False)
    with pytest.raises(ValueError) as e:
        bentstraw.simulate(**REF2, points=0)
    assert "--points 0 is not allowed" in p.stderr
    assert str(e.value) in p.stderr.replace("--points 0", "points=0")
    assert "--" not in str(e.value)
    with pytest.raises(ValueError) as e:
        bentstraw.check([[0, 0, 0]], [1], **REF2, tolerance=-1, min_coverage=2)
    assert "tolerance=-1" in str(e.value) and "min_coverage=2" in str(e.value)
    with pytest.raises(FileNotFoundError):
        bentstraw.Scene.load(tmp_path / "absent.toml")
    with pytest.raises(FileNotFoundError, match="no-such-scene"):
        bentstraw.simulate("no-such-scene")


def test_centimetres_get_a_warning():
    big = '[container]\nshape = "glass"\nradius = 4\nheight = 20\n\n[[straw]]\nx = 0\ny = 0\n\n[observer]\nposition = [30, 0, 10]\n'
    with pytest.warns(UserWarning, match="big.toml: container.radius = 4: lengths are in metres"):
        bentstraw.simulate(bentstraw.Scene.from_toml(big, name="big.toml"), points=100)


def test_the_engine_lets_other_python_threads_run_while_it_works():
    """The lock is released during the work: a Python thread keeps counting meanwhile, and two
    simulations in two threads give each the points it gives alone."""
    alone = bentstraw.simulate(**REF2, points=200_000)
    counted, done = [0], threading.Event()

    def count():
        while not done.is_set():
            counted[0] += 1

    counter = threading.Thread(target=count)
    counter.start()
    before = counted[0]
    bentstraw.simulate(**REF2, points=200_000)
    during = counted[0] - before
    done.set()
    counter.join()
    assert during > 1000, f"the counting thread ran {during} times during the simulation"

    results = [None, None]

    def simulate(k):
        results[k] = bentstraw.simulate(**REF2, points=200_000)

    threads = [threading.Thread(target=simulate, args=(k,)) for k in range(2)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    for r in results:
        assert same_bits(r.xyz, alone.xyz) and np.array_equal(r.color, alone.color)


# A long call interrupted by Ctrl-C (SIGINT, as the terminal and Jupyter's "Interrupt kernel"
# send it) as the process's first call: how long after the signal KeyboardInterrupt came, and the
# processor time the process used in the 0.3 s after it (none: nothing left running). Each call
# takes seconds, the signal comes at 0.3 s.
INTERRUPTED = r"""
import os, signal, sys, threading, time
import bentstraw
fired = []
def fire():
    time.sleep(0.3)
    fired.append(time.perf_counter())
    os.kill(os.getpid(), signal.SIGINT)
threading.Thread(target=fire, daemon=True).start()
view = dict(observer=(0.1, 0, 0.1), straw=(0.02, 0.01), water_height=0.15)
try:
    if sys.argv[1] == "simulate":
        bentstraw.simulate(**view, points=5_000_000)
    else:
        bentstraw.render(**view, size=(6000, 4000), mode="fresnel")
    print("finished")
except KeyboardInterrupt:
    after = time.perf_counter() - fired[0]
    cpu = time.process_time()
    time.sleep(0.3)
    print("interrupted", after, time.process_time() - cpu)
"""


@pytest.mark.parametrize("call", ["simulate", "render"])
def test_ctrl_c_stops_a_long_call_at_once_with_keyboard_interrupt(call):
    p = subprocess.run([sys.executable, "-c", INTERRUPTED, call], capture_output=True, text=True, timeout=120)
    words = p.stdout.split()
    assert words and words[0] == "interrupted", p.stdout + p.stderr
    after, cpu = float(words[1]), float(words[2])
    assert after < 0.2, f"KeyboardInterrupt came {after:.3f} s after the signal"
    assert cpu < 0.02, f"{cpu:.3f} s of processor time after it: something still runs"


def test_arrays_are_the_engines_buffers_not_copies():
    sim = bentstraw.simulate(**REF2, points=1000)
    for a in [sim.xyz, sim.color, sim.path_length, sim.direction]:
        # Each array's memory is held by the engine's buffer it took over, not by another array.
        base = a
        while isinstance(base, np.ndarray) and base.base is not None:
            base = base.base
        assert not isinstance(base, np.ndarray), type(base)
    assert sim.xyz.flags["C_CONTIGUOUS"] and sim.xyz.dtype == np.float64 and sim.color.dtype == np.int64


def test_the_gallery_and_its_scenes():
    names = bentstraw.gallery()
    assert len(names) >= 16 and "leaning-straw" in names and "reversing-arrow" in names
    for name in names:
        assert bentstraw.Scene.gallery(name).name == name
    # A typo gets the nearest names first.
    with pytest.raises(ValueError, match="did you mean 'leaning-straw'"):
        bentstraw.Scene.gallery("leaning-staw")


@pytest.mark.parametrize("image_model", ["course", "eye", "stereo"])
def test_results_pickle_and_are_read_only(image_model):
    import pickle

    sim = bentstraw.simulate(**REF2, points=2000, image_model=image_model)
    again = pickle.loads(pickle.dumps(sim))
    for name in ["xyz", "image_xyz", "color", "direction", "path_length", "object_point", "events"]:
        assert same_bits(getattr(again, name), getattr(sim, name)), name
        # Results: none may be edited in place (the course's xyz is its image_xyz).
        with pytest.raises(ValueError):
            getattr(sim, name)[0] = 0
        with pytest.raises(ValueError):
            getattr(again, name)[0] = 0
    assert list(again.path) == list(sim.path) and again.observer == sim.observer
    assert repr(again) == repr(sim)


def test_the_docstrings_examples_run_as_written(monkeypatch, tmp_path):
    import doctest

    import matplotlib  # noqa: F401  (the examples draw: the tests need it, as the notebook does)
    monkeypatch.setenv("MPLBACKEND", "Agg")
    monkeypatch.chdir(ROOT)
    # (`tmp_path`: where the examples that write a file write it.)
    result = doctest.testmod(bentstraw, extraglobs={"bentstraw": bentstraw, "tmp_path": tmp_path},
                             optionflags=doctest.ELLIPSIS)
    assert result.failed == 0 and result.attempted >= 20, result


def test_the_notebook_runs_top_to_bottom():
    import nbclient
    import nbformat

    path = ROOT / "crates" / "bentstraw-py" / "examples" / "bentstraw.ipynb"
    notebook = nbformat.read(path, as_version=4)

    def words(nb):
        # Each code cell's printed text and values, as a reader of the file sees them.
        return [
            "".join(o.get("text", "") + o.get("data", {}).get("text/plain", "") for o in c.get("outputs", []))
            for c in nb.cells if c.cell_type == "code"
        ]

    def figures(nb):
        return [sum("image/png" in o.get("data", {}) for o in c.get("outputs", []))
                for c in nb.cells if c.cell_type == "code"]

    committed, committed_figures = words(notebook), figures(notebook)
    client = nbclient.NotebookClient(
        notebook, timeout=600, kernel_name="python3", resources={"metadata": {"path": str(path.parent)}}
    )
    client.execute()  # raises on the first cell that fails
    text = "".join(words(notebook))
    assert "fail -" in text and "the reference's own points: pass" in text
    # The file is kept with its outputs (a reader sees the figures without running it), and they
    # are today's: the same words and the same figures as a run now.
    assert committed == words(notebook)
    assert committed_figures == figures(notebook) and sum(committed_figures) >= 3


SOLIDS = """[container]
shape = "glass"
radius = 0.04
height = 0.15

[[liquid]]
name = "water"
index = 1.333
top = 0.1

[[straw]]
x = 0.02
y = 0.0

[[sphere]]
center = [-0.015, 0.0, 0.03]
radius = 0.012
index = 1.5

[[prism]]
corners = [[0.1, -0.03], [0.14, -0.03], [0.12, 0.0]]
bottom = 0.0
top = 0.1
index = 1.5

[[lens]]
center = [0.12, 0.02, 0.085]
axis = [1, 0, 0]
radius1 = 0.05
radius2 = -0.05
thickness = 0.008
diameter = 0.03
index = 1.5

[observer]
position = [0.25, 0.05, 0.12]
target = [0.0, 0.0, 0.05]
"""


def test_transparent_solids_give_the_command_lines_points_and_their_rules(tmp_path):
    scene = tmp_path / "solids.toml"
    scene.write_text(SOLIDS)
    (header, rows), sim = simulated(tmp_path, ["--scene", scene, "--points", "3000"], scene=scene, points=3000)
    assert_same_points(header, rows, sim)
    # Some light reaches the straw through a solid first.
    assert "solid" in set(sim.path)
    with pytest.raises(ValueError) as e:
        bentstraw.Scene.from_toml(SOLIDS.replace("radius = 0.012", "radius = 0.03"))
    assert "sphere[1]" in str(e.value)


def test_a_glass_of_revolution_gives_the_command_lines_points_and_its_rules(tmp_path):
    (header, rows), sim = simulated(
        tmp_path, ["--scene", "wine-glass", "--points", "3000"], scene="wine-glass", points=3000
    )
    assert_same_points(header, rows, sim)
    assert "wall" in set(sim.path)
    text = bentstraw.Scene.gallery("tapered-tumbler").text
    with pytest.raises(ValueError) as e:
        bentstraw.Scene.from_toml(text.replace("[0.0395, 0.12]", "[0.043, 0.12]"))
    assert "container.inner" in str(e.value) and "leaves the outer one" in str(e.value)


def test_explore_serves_the_page_on_the_view_asked_and_nothing_else():
    """The explorer's page and engine come with the package, served to this machine alone; its
    address holds the view; the keywords are refused as everywhere else."""
    import urllib.error
    import urllib.parse
    import urllib.request

    from bentstraw import _explore

    assert _explore.page_available(), (
        "the package holds no page: `cargo xtask site crates/bentstraw-py/python/bentstraw/page` "
        "before installing it"
    )
    page = bentstraw.explore("prism", observer=(0.3, 0.05, 0.2), mode="course", lang="fr")
    base, fragment = page.url.split("#")
    view = dict(urllib.parse.parse_qsl(fragment))
    assert view["scene"] == "prism" and view["lang"] == "fr" and view["mode"] == "course"
    assert [float(x) for x in view["observer"].split(",")] == [0.3, 0.05, 0.2]
    assert urllib.parse.urlsplit(base).hostname == "127.0.0.1"
    assert f'src="{page.url.replace("&", "&amp;")}"' in page._repr_html_()

    def get(path):
        with urllib.request.urlopen(urllib.parse.urljoin(base, path), timeout=10) as r:
            return r.status, r.headers["Content-Type"], r.read()

    status, kind, body = get("index.html")
    assert status == 200 and kind.startswith("text/html") and b"<html" in body
    status, kind, body = get("pkg/bentstraw_web_bg.wasm")
    assert kind == "application/wasm" and body[:4] == b"\0asm"
    for refused in ("pkg/", "../__init__.py", "%2e%2e/__init__.py"):
        with pytest.raises(urllib.error.HTTPError) as e:
            get(refused)
        assert e.value.code == 404, refused
    # Every call opens the same server.
    again = bentstraw.explore(**REF2)
    assert again.url.split("#")[0] == base
    assert dict(urllib.parse.parse_qsl(again.url.split("#")[1]))["straw"] == "0.0,0.02"

    # A scene file travels as its text.
    text = bentstraw.Scene.gallery("leaning-straw").text
    for scene in (bentstraw.Scene.from_toml(text), str(ROOT / "scenes" / "leaning-straw.toml")):
        fragment = bentstraw.explore(scene).url.split("#")[1]
        assert dict(urllib.parse.parse_qsl(fragment))["scene-file"] == text

    with pytest.raises(ValueError, match="mode"):
        bentstraw.explore(mode="colour", **REF2)  # type: ignore[arg-type]
    with pytest.raises(ValueError, match="lang"):
        bentstraw.explore(lang="de", **REF2)  # type: ignore[arg-type]
    with pytest.raises(TypeError, match="observer"):
        bentstraw.explore(observer="123", straw=(0, 0.02), water_height=0.1)
    with pytest.raises(ValueError, match="did you mean 'prism'"):
        bentstraw.explore("prysm")


def test_help_lists_the_calls_without_burying_them():
    """`help(bentstraw)` gives the calls and names what they return, without numpy's, dict's or
    AssertionError's own methods."""
    import pydoc

    text = pydoc.render_doc(bentstraw, renderer=pydoc.plaintext)
    assert len(text.splitlines()) < 250, len(text.splitlines())
    for call in bentstraw.__all__:
        assert f"\n    {call}(" in text, call
    for name in ("Simulation", "Picture", "CheckReport", "Ray", "Explorer", "Scene"):
        assert f":class:`{name}`" in text, name
    assert "ndarray" not in text.split("FUNCTIONS")[0]
    assert "with_traceback" not in text and "fromkeys" not in text


def test_a_wavelength_gives_the_command_lines_points_and_its_rule(tmp_path):
    """A dispersive scene traced at a wavelength: the command line's points, bit for bit; a
    wavelength outside the visible and a material not in the table are ValueErrors."""
    text = bentstraw.Scene.gallery("prism").text
    assert "index = 1.5\n" in text
    text = text.replace("index = 1.5\n", 'material = "f2"\n', 1)
    (tmp_path / "f2.toml").write_text(text)
    for nm in (410.0, 650.0):
        sim = bentstraw.simulate(bentstraw.Scene.from_toml(text), wavelength=nm, points=2000)
        run("simulate", "--scene", tmp_path / "f2.toml", "--wavelength", nm, "--points", 2000,
            "--output", tmp_path / "cli.csv")
        assert_same_points(*read_points(tmp_path / "cli.csv"), sim)
    with pytest.raises(ValueError, match="wavelength 300 nm is not allowed"):
        bentstraw.simulate(bentstraw.Scene.from_toml(text), wavelength=300, points=100)
    with pytest.raises(TypeError, match="wavelength"):
        bentstraw.simulate(bentstraw.Scene.from_toml(text), wavelength="450")  # type: ignore[arg-type]
    with pytest.raises(ValueError, match="did you mean 'f2'"):
        bentstraw.Scene.from_toml(text.replace('"f2"', '"f3"'))


def test_white_light_gives_the_command_lines_points_with_their_wavelengths(tmp_path):
    """White light through a flint prism: the command line's points and wavelengths, bit for
    bit, for the course's and the eye's points, saved alike; each point's light path is the
    one its ray takes at its own wavelength; a light not known is a ValueError."""
    text = bentstraw.Scene.gallery("prism").text.replace("index = 1.5\n", 'material = "f2"\n', 1)
    (tmp_path / "f2.toml").write_text(text)
    scene = bentstraw.Scene.from_toml(text)
    bands = {405.0, 455.0, 505.0, 555.0, 605.0, 655.0, 705.0, 755.0}
    for model in ("course", "eye"):
        sim = bentstraw.simulate(scene, points=2000, light="white", image_model=model)
        run("simulate", "--scene", tmp_path / "f2.toml", "--light", "white", "--points", 2000,
            "--image-model", model, "--output", tmp_path / "cli.csv")
        header, rows = read_points(tmp_path / "cli.csv")
        assert header[:5] == ["x", "y", "z", "color", "wavelength"]
        assert_same_points(header, rows, sim)
        assert set(np.unique(sim.wavelength)) == bands
        sim.save(tmp_path / "py.csv")
        assert (tmp_path / "py.csv").read_bytes() == (tmp_path / "cli.csv").read_bytes()
    assert list(sim.to_dataframe().columns[:6]) == ["x", "y", "z", "color", "wavelength", "path"]
    # Each point's kind of light path, traced again in the scene at its band's wavelength.
    for nm in (405.0, 755.0):
        mono = bentstraw.simulate(scene, wavelength=nm, points=10)
        chosen = sim.wavelength == nm
        again = bentstraw._engine.light_paths(mono._scene, np.ascontiguousarray(sim.direction[chosen]))
        keys = np.asarray(again["path_keys"], dtype=str)[again["path_index"]]
        assert list(keys) == list(sim.path[chosen])
    with pytest.raises(ValueError, match="light"):
        bentstraw.simulate(scene, points=100, light="blue")  # type: ignore[arg-type]


def test_full_sampling_is_the_command_lines_and_a_slip_is_refused(tmp_path):
    """``sampling="full"`` takes the samples at every pixel, as ``render --sampling full`` does
    (another picture than the adaptive one); a sampling not known is a ValueError naming it."""
    run("render", "--scene", "marble-in-water", "--sampling", "full", "--size", "96x72",
        "--output", tmp_path / "full.png")
    full = bentstraw.render("marble-in-water", sampling="full", size=(96, 72))
    assert np.array_equal(full, decode_png((tmp_path / "full.png").read_bytes()))
    assert not np.array_equal(full, bentstraw.render("marble-in-water", size=(96, 72)))
    with pytest.raises(ValueError, match="sampling"):
        bentstraw.render("marble-in-water", sampling="every", size=(8, 6))  # type: ignore[arg-type]
