"""File.render, metrics, diff, movies and transfer functions against the CLI's outputs."""
import json
import os
import shutil
import subprocess
import sys
import threading
import time

import numpy as np
import pytest

import tspplay

SIZE = (96, 64)


def cli_frames(cli, path, out, steps, *options):
    cli("render", path, "--steps", steps, "--size", f"{SIZE[0]}x{SIZE[1]}", "-o", out, *options)
    return json.loads((out / "frames.json").read_text())


@pytest.mark.parametrize("cli_options, py_options", [
    ((), {}),
    (("--view", "70,-15", "--spatial-tol", "0.05", "--temporal-tol", "0.1",
      "--compositing", "rays", "--shade", "off", "--tf", "preset:viridis", "--annotate"),
     dict(view=(70, -15), spatial_tol=0.05, temporal_tol=0.1, compositing="rays", shade=False,
          tf="viridis", annotate=True)),
])
def test_render_gives_the_cli_pixels_byte_for_byte(built, cli, tmp_path, cli_options, py_options):
    frames = cli_frames(cli, built.path, tmp_path / "cli", "1:4", *cli_options)
    images = built.render(steps=range(1, 5), size=SIZE, **py_options)
    assert images.steps == [1, 2, 3, 4]
    assert len(images.reports) == len(frames["frames"]) == 4
    for k, img in zip(images.steps, images):
        assert img.shape == (SIZE[1], SIZE[0], 4) and img.dtype == np.uint8
        png = tspplay.read_png(str(tmp_path / "cli" / f"step_{k:04d}.png"))
        assert png.tobytes() == img.tobytes(), f"step {k}"
    for mine, theirs in zip(images.reports, frames["frames"]):
        assert mine.keys() == theirs.keys()
        assert mine["step"] == theirs["step"] and mine["caster"] == theirs["caster"]
        assert mine["new_texture"] == theirs["new_texture"]
    assert images.info["context"] == frames["context"]


def test_render_output_folder_and_steps_forms(built, tmp_path):
    frames = built.render(steps="0:4:2", size=SIZE, output=tmp_path / "out")
    assert frames.steps == [0, 2, 4]
    assert sorted(p.name for p in (tmp_path / "out").iterdir()) == [
        "frames.json", "step_0000.png", "step_0002.png", "step_0004.png"]
    assert built.render(steps=slice(None, None, 3), size=SIZE).steps == [0, 3]
    assert built.render(steps=5, size=SIZE).steps == [5]


def test_settings_are_checked_with_the_cli_messages(built, cli, tmp_path):
    with pytest.raises(tspplay.UsageError) as e:
        built.render(steps=0, spacing=0)
    r = cli("render", built.path, "--spacing", "0", "-o", tmp_path / "x", check=False)
    assert r.returncode != 0 and str(e.value) in r.stderr
    with pytest.raises(tspplay.UsageError) as e:
        built.render(steps=99)
    r = cli("render", built.path, "--steps", "99", "-o", tmp_path / "x", check=False)
    assert str(e.value) in r.stderr
    with pytest.raises(tspplay.UsageError, match="--compositing"):
        built.render(steps=0, compositing="voxels")
    with pytest.raises(tspplay.UsageError, match="no option --colour"):
        built.render(steps=0, colour="red")
    with pytest.raises(tspplay.UsageError, match="--size"):
        built.render(steps=0, size=(0, 10))


def test_metrics_are_the_cli_metrics(built, cli):
    mine = built.metrics("preset:sparse", metric="approximate")
    r = cli("metrics", built.path, "--tf", "preset:sparse", "--metric", "approximate", "--json",
            "--nodes")
    theirs = json.loads(r.stdout)["nodes"]
    np.testing.assert_allclose(mine["spatial_error"], [n["spatial_error"] for n in theirs], rtol=1e-6)
    np.testing.assert_allclose(mine["temporal_error"], [n["temporal_error"] for n in theirs], rtol=1e-6)
    np.testing.assert_array_equal(mine["transparent"], [n["transparent"] for n in theirs])
    assert mine["mean_colour"].shape == (len(theirs), 4)


def test_diff_is_the_cli_diff(built, cli, tmp_path):
    cli_frames(cli, built.path, tmp_path / "a", "2")
    cli_frames(cli, built.path, tmp_path / "b", "2", "--spatial-tol", "0.3", "--spacing", "2")
    a, b = tmp_path / "a" / "step_0002.png", tmp_path / "b" / "step_0002.png"
    theirs = json.loads(cli("diff", a, b, "--json").stdout)
    mine = tspplay.diff(str(a), str(b))
    for k in ("mean", "p99", "max", "pixels", "width", "height"):
        assert mine[k] == theirs[k], k
    assert tspplay.diff(tspplay.read_png(str(a)), tspplay.read_png(str(b))) == mine
    assert tspplay.diff(str(a), str(a))["max"] == 0
    with pytest.raises(tspplay.UsageError):
        tspplay.diff(np.zeros((4, 4, 4), np.uint8), np.zeros((4, 5, 4), np.uint8))


@pytest.mark.skipif(shutil.which("ffmpeg") is None, reason="needs ffmpeg")
def test_movie(built, tmp_path):
    out = tmp_path / "run.mp4"
    frames = built.movie(out, steps=range(0, 4), size=SIZE, fps=4)
    assert len(frames) == 4 and out.stat().st_size > 0
    probe = subprocess.run(["ffprobe", "-v", "error", "-count_frames", "-select_streams", "v:0",
                            "-show_entries", "stream=nb_read_frames", "-of", "csv=p=0", str(out)],
                           capture_output=True, text=True)
    if probe.returncode == 0:
        assert probe.stdout.strip() == "4"
    with pytest.raises(tspplay.UsageError, match="mp4 or .gif"):
        built.movie(tmp_path / "run.avi", steps=0)


def test_render_releases_the_gil(built):
    # With a huge switch interval this thread keeps the GIL until it blocks or a C call releases
    # it: the counter can move while render() runs only if render() released the GIL.
    counter, stop = [0], threading.Event()
    started = threading.Event()

    def count():
        started.set()
        while not stop.is_set():
            counter[0] += 1
            time.sleep(0)  # not a wait: a call that releases the GIL, so the main thread gets it

    interval = sys.getswitchinterval()
    sys.setswitchinterval(1000)
    worker = threading.Thread(target=count)
    try:
        worker.start()
        started.wait()
        before = counter[0]
        built.render(size=SIZE)  # every step
        during = counter[0] - before
    finally:
        stop.set()
        worker.join()
        sys.setswitchinterval(interval)
    assert during > 0


def test_interrupted_render_stops_cleanly(built, tmp_path):
    import signal
    out = tmp_path / "frames"

    def ctrl_c(phase, done, total):
        signal.raise_signal(signal.SIGINT)

    with pytest.raises(KeyboardInterrupt):
        built.render(size=SIZE, output=out, progress=ctrl_c)
    assert not out.exists()


def test_transfer_functions(built, cli, tmp_path):
    lo, hi = built.value_range
    pts = [(lo, 0, 0, 1, 0), ((lo + hi) / 2, 0, 1, 0, 0.2), (hi, 1, 0, 0, 0.8)]
    tf = tspplay.TransferFunction(pts)
    (domain, entries) = tf.table()
    assert domain == (lo, hi) and entries.shape == (256, 4)
    path = tmp_path / "tf.json"
    path.write_text(json.dumps({"range": [lo, hi], "points": [list(p) for p in pts]}))
    cli_frames(cli, built.path, tmp_path / "cli", "3", "--tf", path)
    img = built.render(steps=3, size=SIZE, tf=tf)[0]
    assert tspplay.read_png(str(tmp_path / "cli" / "step_0003.png")).tobytes() == img.tobytes()
    assert tspplay.TransferFunction.from_file(path).table()[0] == (lo, hi)
    assert tspplay.TransferFunction.preset("viridis").arg == "preset:viridis"
    with pytest.raises(tspplay.UsageError, match="unknown preset"):
        tspplay.TransferFunction.preset("nope")
    with pytest.raises(tspplay.UsageError):
        tspplay.TransferFunction([(0, 1, 1)])
    bad = tmp_path / "bad.json"
    bad.write_text('{"points": 3}')
    with pytest.raises(tspplay.FormatError):
        tspplay.TransferFunction.from_file(bad)
    try:
        import matplotlib  # noqa: F401
    except ImportError:
        with pytest.raises(tspplay.UsageError, match="matplotlib"):
            tspplay.TransferFunction.from_matplotlib("magma")
    else:
        assert tspplay.TransferFunction.from_matplotlib("magma").table()[1].shape == (256, 4)


@pytest.mark.skipif(not os.environ.get("DISPLAY"), reason="needs an X display (scripts/test.sh runs one)")
def test_play_opens_the_window_on_an_array(series, tmp_path):
    shot = tmp_path / "shot.png"
    tspplay.play(series[:3], cache_dir=tmp_path / "cache", screenshot=shot, size=(160, 120))
    assert tspplay.read_png(str(shot)).shape == (120, 160, 4)
    cached = list((tmp_path / "cache").iterdir())
    assert len(cached) == 1 and cached[0].suffix == ".tsp"
    # The same samples again: the cached tree is played, not rebuilt.
    mtime = cached[0].stat().st_mtime_ns
    tspplay.play(series[:3].copy(), cache_dir=tmp_path / "cache", screenshot=shot, size=(160, 120))
    assert cached[0].stat().st_mtime_ns == mtime


def test_renders_from_two_threads_at_once_give_the_sequential_pictures(built):
    sequential = {k: built.render(steps=k, size=SIZE)[0] for k in (1, 4)}
    concurrent = {}

    def render(k):
        concurrent[k] = built.render(steps=k, size=SIZE)[0]

    threads = [threading.Thread(target=render, args=(k,)) for k in sequential]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    for k, img in sequential.items():
        assert concurrent[k].tobytes() == img.tobytes()
