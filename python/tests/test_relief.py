"""The pytest suite of `import relief` (python/relief_module.cc, docs/python.md).

Each test checks the module against what it stands for: the relief command line's own files
(the same PNG bytes, the same scene text), numpy's own reading of the arrays, or a property
that holds whatever the numbers (determinism, the error of an image against itself).
"""
import json
import os
import subprocess
import zlib

import numpy as np
import pytest

import relief

SMALL = ["viewport.width=96", "viewport.height=64", "grid.width=64", "grid.height=64"]
BINARY = os.environ.get("RELIEF_BINARY")


def png_pixels(png):
    """The RGB rows of a PNG that relief wrote (8-bit RGB, Sub filter per row), decoded by hand:
    an oracle independent of the module's arrays."""
    assert png[:8] == b"\x89PNG\r\n\x1a\n"
    pos, data, width, height = 8, b"", 0, 0
    while pos < len(png):
        length = int.from_bytes(png[pos:pos + 4], "big")
        kind = png[pos + 4:pos + 8]
        body = png[pos + 8:pos + 8 + length]
        if kind == b"IHDR":
            width, height = int.from_bytes(body[:4], "big"), int.from_bytes(body[4:8], "big")
        elif kind == b"IDAT":
            data += body
        pos += 12 + length
    raw = zlib.decompress(data)
    stride = 3 * width + 1
    rows = []
    for y in range(height):
        line = bytearray(raw[y * stride + 1:(y + 1) * stride])
        assert raw[y * stride] == 1  # Sub
        for x in range(3, len(line)):
            line[x] = (line[x] + line[x - 3]) & 255
        rows.append(bytes(line))
    return np.frombuffer(b"".join(rows), dtype=np.uint8).reshape(height, width, 3)


def test_presets_are_the_command_lines():
    assert "default" in relief.presets() and "planet" in relief.presets()


def test_a_scene_prints_as_relief_scene_does():
    scene = relief.Scene("lava", ["terrain.H=0.7"])
    assert json.loads(scene.json)["terrain"]["H"] == 0.7
    assert scene.get("terrain.H") == 0.7
    assert scene.get("camera.position") == json.loads(scene.json)["camera"]["position"]
    if BINARY:
        printed = subprocess.run([BINARY, "scene", "lava", "--set", "terrain.H=0.7"],
                                 check=True, capture_output=True, text=True).stdout
        assert printed == scene.json


def test_set_validates_like_the_command_line():
    scene = relief.Scene()
    scene.set("terrain.r", 2.5)
    assert scene.get("terrain.r") == 2.5
    with pytest.raises(relief.SceneError) as error:
        scene.set("terrain.H", 2)
    assert error.value.field == "terrain.H"
    assert error.value.exit_code == 2
    assert "out of range" in str(error.value)
    assert scene.get("terrain.H") == 0.85  # a refused value leaves the scene as it was
    with pytest.raises(relief.SceneError):
        scene.set("terrain.nonsense", 1)
    with pytest.raises(relief.SceneError):
        relief.Scene("no-such-preset-or-file")
    with pytest.raises(KeyError):
        scene.get("terrain.nope")
    for bad in (float("nan"), float("inf"), 10**30, "quintic"):
        with pytest.raises(relief.SceneError):
            scene.set("terrain.H", bad)
    with pytest.raises(relief.SceneError):
        relief.render(scene, backend="vulkan")
    with pytest.raises(relief.SceneError):
        relief.render(scene, outputs=["albedo"])
    with pytest.raises(relief.SceneError):
        relief.render(scene, threads=-1)
    with pytest.raises(MemoryError):  # estimated before any work
        relief.render(relief.Scene("default", ["viewport.width=4096", "viewport.height=4096"]),
                      outputs=["linear", "normal"], max_memory="64M")
    with pytest.raises(relief.SceneError):
        relief.render(scene, max_memory="lots")


def test_a_field_set_between_frames_renders_what_a_fresh_scene_renders():
    # Resources are kept across set() unless a terrain or shading field changes: the frame after
    # each set() must be a fresh scene's of the same fields, whichever field it was.
    scene = relief.Scene("default", SMALL)
    relief.render(scene)
    applied = []
    for key, value in [("camera.yaw_deg", 50.0), ("terrain.seed", 9),
                       ("shading.texture_size", 32), ("lighting.sun_elevation_deg", 40.0)]:
        scene.set(key, value)
        applied.append("%s=%s" % (key, json.dumps(value)))
        fresh = relief.Scene("default", SMALL + applied)
        assert np.array_equal(relief.render(scene)["image"], relief.render(fresh)["image"]), key


def test_the_image_array_is_the_png_relief_writes():
    scene = relief.Scene("default", SMALL)
    frame = relief.render(scene)
    image = frame["image"]
    assert image.shape == (64, 96, 3) and image.dtype == np.uint8
    assert not image.flags.writeable
    assert np.array_equal(image, png_pixels(frame["png"]))
    if BINARY:
        out = os.path.join(os.environ.get("TMPDIR", "/tmp"), "relief-pytest-%d.png" % os.getpid())
        args = [BINARY, "render", "-o", out]
        for s in SMALL:
            args += ["--set", s]
        subprocess.run(args, check=True, capture_output=True)
        with open(out, "rb") as f:
            assert f.read() == frame["png"]  # the same bytes as relief render
        os.remove(out)


def test_frames_are_bit_identical_across_threads_and_backends_agree_in_shape():
    scene = relief.Scene("alpine", SMALL)
    one = relief.render(scene, threads=1)["image"]
    two = relief.render(scene, threads=2)["image"]
    reference = relief.render(scene, backend="reference")["image"]
    assert np.array_equal(one, two)
    assert np.array_equal(one, reference)  # simd is reference's bytes (docs/architecture.md)


def test_extra_outputs_view_the_frame_without_copies():
    scene = relief.Scene("lake", SMALL)
    frame = relief.render(scene, outputs=["linear", "depth", "normal", "height", "primitive"])
    depth, normal, primitive = frame["depth"], frame["normal"], frame["primitive"]
    assert frame["octaves"] is None
    assert depth.shape == (64, 96) and depth.dtype == np.float32
    assert normal.shape == (64, 96, 3)
    assert depth.strides[0] < 0  # rows stored bottom first, viewed top first: a view
    covered = primitive != 0xFFFFFFFF
    assert covered.any()
    lengths = np.sqrt((normal[covered].astype(np.float64) ** 2).sum(axis=1))
    assert np.all(np.abs(lengths - 1) < 1e-5)
    assert np.all(depth[~covered] == 0)  # reverse-Z cleared to 0 where nothing is drawn
    assert np.all(np.isfinite(frame["linear"]))
    # The arrays outlive the frame dict: they hold the frame.
    kept = frame["height"]
    del frame
    assert np.isfinite(kept[covered]).all()


def test_stats_report_the_stages():
    frame = relief.render(relief.Scene("default", SMALL))
    stages = frame["stats"]["stages"]
    assert "frame plan" in stages
    assert frame["stats"]["total_ms"] > 0
    assert any(stage["counters"] for stage in stages.values())


def test_stage_buffers_are_relief_stages():
    scene = relief.Scene("default", SMALL)
    buffers = relief.stages(scene)
    height = buffers["height"]
    assert height.shape == (64, 64)
    valid = buffers["valid"].astype(bool)
    assert valid.any()
    assert np.all(np.isfinite(height[valid]))
    assert np.array_equal(relief.stages(scene, backend="reference")["height"][valid], height[valid])


def test_compare_gives_relief_compares_figures():
    a = np.random.default_rng(1).random((16, 24, 3), dtype=np.float32)
    same = relief.compare(a, a)
    assert same["verdict"] == "PASS" and same["exit_code"] == 0 and same["max_error"] == 0
    b = a.copy()
    b[5, 7, 1] += 0.25
    diff = relief.compare(a, b)
    assert diff["verdict"] == "FAILURE" and diff["exit_code"] == 2
    assert (diff["max_x"], diff["max_y"]) == (7, 5)
    assert diff["max_error"] == pytest.approx(0.25, rel=1e-6)
    assert diff["rms_error"] == pytest.approx(0.25 / np.sqrt(a.size), rel=1e-6)
    assert relief.compare(a, a[:8])["verdict"] == "SIZE MISMATCH"


def test_a_users_gpu_test():
    """Written as a graphics team would: their GPU image (here a perturbed copy of Relief's,
    standing in for it) against Relief's reference, with a tolerance and a PSNR floor."""
    scene = relief.Scene("alpine", SMALL)
    reference = relief.render(scene, outputs=["linear"])["linear"]
    gpu = reference + np.float32(1e-4) * np.sin(np.arange(reference.size, dtype=np.float32)
                                               ).reshape(reference.shape)
    result = relief.compare(gpu, reference, fail=1e-3, warn=1e-4)
    assert result["verdict"] in ("PASS", "WARNING")
    assert result["psnr"] > 60
