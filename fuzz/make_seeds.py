#!/usr/bin/env python3
"""Writes the fuzzers' seed corpora (fuzz/corpus/TARGET/), the soup and texture dictionaries
(fuzz/TARGET.dict) and the constructed regression inputs of fuzz/regressions/. The scene and
override dictionaries are generated from the scene schema by relief_scene_docs.

Run from the repository root after the seeds change:
    python3 fuzz/make_seeds.py
The outputs are committed; the fuzzers and tests/cli/fuzz_corpus_test.cc read them, not this
script. Standard library only: the PNGs are written chunk by chunk with zlib.
"""
import json
import pathlib
import struct
import zlib

ROOT = pathlib.Path(__file__).resolve().parent.parent
FUZZ = ROOT / "fuzz"
CORPUS = FUZZ / "corpus"


def write(target, name, data):
    path = CORPUS / target / name
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_bytes(data if isinstance(data, bytes) else data.encode())


def field_paths(value, prefix=""):
    """Every JSON path of the complete scene: "terrain.warp.c1", "shading.layers"."""
    for key, item in value.items():
        path = f"{prefix}.{key}" if prefix else key
        yield path, item
        if isinstance(item, dict):
            yield from field_paths(item, path)


# --- scenes: the presets, and small scenes just inside and just outside the rules ---------
presets = sorted((ROOT / "scenes").glob("*.json"))
alpine = json.loads((ROOT / "scenes" / "alpine.json").read_text())
for preset in presets:
    write("scene", preset.name, preset.read_bytes())
scenes = {
    "empty_object.json": "{}",
    "look_at.json": '{"camera": {"position": [10, 500, -3], "look_at": [0, 0, -1000]}}',
    "layer_patch.json": '{"shading": {"layers": {"2": {"specular": 0.5, "slope_deg": [30, 90]}}}}',
    "one_layer.json": '{"shading": {"layers": [{"name": "a", "texture": "builtin:rock"}]}}',
    "png_layer.json": '{"shading": {"layers": [{"texture": "rock.png", "tile_size": 1e-4}]}}',
    "no_water.json": '{"terrain": {"water_level": null, "warp": {"enabled": true}}}',
    "nyquist.json": '{"terrain": {"lod": {"criterion": "nyquist", "bias": -8}, "H": 0.00025}}',
    "integers.json": '{"grid": {"width": 5.12e2, "height": 512.0, "margin": 0}, '
                     '"terrain": {"seed": 18446744073709551615}}',
    "small.json": '{"viewport": {"width": 1, "height": 1}, "grid": {"width": 2, "height": 2, '
                  '"margin": 0}, "camera": {"fov_y_deg": 1}}',
    "outputs.json": '{"output": {"image": "a.png", "float_image": "a.exr", "stages_dir": "s"}}',
    "h_out_of_range.json": '{"terrain": {"H": 2}}',
    "duplicate_key.json": '{"time": 1, "time": 2}',
    "deep.json": '{"a": ' * 17 + "1" + "}" * 17,
    "octaves_reversed.json": '{"terrain": {"first_octave": 10, "last_octave": 2}}',
    "both_directions.json": '{"camera": {"yaw_deg": 3, "look_at": [1, 2, 3]}}',
    "utf8_name.json": '{"shading": {"layers": {"0": {"name": "s\\u00e9dim\\u00e9nt"}}}}',
}
for name, text in scenes.items():
    write("scene", name, text)

# --- overrides: byte 0 picks the base scene, then one KEY=VALUE per line ----------------------
overrides = [
    b"\x00terrain.H=0.5",
    b"\x01camera.look_at=[1,2,3]\ncamera.position=[0,10,0]",
    b"\x02shading.layers.2.texture=builtin:rock\nshading.layers.2.slope_deg=[30,90]",
    b"\x03terrain.interpolant=cubic\nterrain.lod.criterion=nyquist",
    b"\x04terrain.water_level=null\nsky.fog_density=0",
    b"\x05viewport.width=16\nviewport.height=12\ngrid.width=8\ngrid.height=8",
    b"\x00terrain.warp.c1=[1,-2]\nterrain.warp.enabled=true",
    b"\x00terrain.seed=18446744073709551615",
    b"\x00terrain.H=nan",
    b"\x00terrain.r=1e999",
    b"\x00camera.yaw_deg=30\ncamera.look_at=[0,0,0]",
    b"\x00shading.layers=[{\"texture\":\"builtin:sand\"}]",
    b"\x00output.image=out.png\noutput.float_image=out.pfm",
    b"\x00a..b=1",
    b"\x00=1",
]
for k, data in enumerate(overrides):
    write("override", f"seed{k:02d}", data)

# --- soups: the two documented samples and small variations ---------------------------------
for sample in sorted((ROOT / "docs" / "soups").glob("*.txt")):
    write("soup", sample.name, sample.read_bytes())
soups = {
    "bom_crlf.txt": b"\xef\xbb\xbf4 4\r\n0 0 0  4 0 0  0 4 1\r\n",
    "clip_one.txt": b"8 8 # comment\n-1 -1 0.5 1  1 -1 0.5 1  0 1 0.5 1\n",
    "header_only.txt": b"16384 16384",
    "near_plane.txt": b"2 2\n0 0 2 1  1 0 0 1e-30  0 1 -1 -1\n",
    "guard_band.txt": b"1 1\n-2097152 2097152 0  2097152 -2097152 1  0 0 0.5\n",
    "mixed_kinds.txt": b"4 4\n0 0 0 1 0 0 0 1 0\n0 0 0 1  1 0 0 1  0 1 0 1\n",
    "bad_header.txt": b"0 4\n",
    "nul.txt": b"4 4\n0 0 0\x00",
}
for name, data in soups.items():
    write("soup", name, data)


# --- textures: small PNGs of every colour type and bit depth --------------------------------
def chunk(kind, data):
    return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data))


def png(width, height, bit_depth, colour_type, rows, palette=None, interlace=0):
    """rows: one bytes object per scanline, already in the PNG sample layout."""
    raw = b"".join(b"\x00" + row for row in rows)  # filter type 0 (None) on every line
    data = b"\x89PNG\r\n\x1a\n"
    data += chunk(b"IHDR", struct.pack(">IIBBBBB", width, height, bit_depth, colour_type, 0, 0,
                                       interlace))
    if palette:
        data += chunk(b"PLTE", palette)
    data += chunk(b"IDAT", zlib.compress(raw, 9)) + chunk(b"IEND", b"")
    return data


def samples(width, height, channels, bit_depth):
    """A gradient, `channels` samples per pixel of `bit_depth` bits (8 or 16)."""
    rows = []
    for y in range(height):
        row = b""
        for x in range(width):
            for c in range(channels):
                v = (x * 37 + y * 91 + c * 53) % 256
                row += bytes([v]) if bit_depth == 8 else struct.pack(">H", v * 257)
        rows.append(row)
    return rows


CHANNELS = {0: 1, 2: 3, 4: 2, 6: 4}
for colour_type, name in [(0, "grey"), (2, "rgb"), (4, "grey_alpha"), (6, "rgba")]:
    for bit_depth in (8, 16):
        n = CHANNELS[colour_type]
        write("texture", f"{name}{bit_depth}_4x4.png",
              png(4, 4, bit_depth, colour_type, samples(4, 4, n, bit_depth)))
write("texture", "rgb8_8x8.png", png(8, 8, 8, 2, samples(8, 8, 3, 8)))
write("texture", "rgb8_1x1.png", png(1, 1, 8, 2, samples(1, 1, 3, 8)))
write("texture", "rgb8_8x4.png", png(8, 4, 8, 2, samples(8, 4, 3, 8)))
write("texture", "grey8_3x3.png", png(3, 3, 8, 0, samples(3, 3, 1, 8)))
palette = bytes(range(48))  # 16 colours
write("texture", "palette4_4x4.png",
      png(4, 4, 4, 3, [bytes([0x01, 0x23]), bytes([0x45, 0x67]), bytes([0x89, 0xab]),
                       bytes([0xcd, 0xef])], palette))
write("texture", "grey1_8x8.png", png(8, 8, 1, 0, [bytes([0xa5])] * 8))
# Adam7: the seven passes of an 8x8 image, each line filtered; stb decodes it.
passes = [(1, 1), (1, 1), (2, 1), (2, 2), (4, 2), (4, 4), (8, 4)]
interlaced = b"".join(b"".join(b"\x00" + bytes(3 * w) for _ in range(h)) for w, h in passes)
ihdr = struct.pack(">IIBBBBB", 8, 8, 8, 2, 0, 0, 1)
write("texture", "rgb8_8x8_adam7.png",
      b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", ihdr) + chunk(b"IDAT", zlib.compress(interlaced)) +
      chunk(b"IEND", b""))
write("texture", "truncated.png", png(4, 4, 8, 2, samples(4, 4, 3, 8))[:45])

# A regression (tests/cli/fuzz_regression_test.cc): a 4x4 RGB texture whose image data inflates to
# 1 MB instead of the 52 bytes its header gives; stb_image would inflate any amount.
bomb = zlib.compress(bytes(1 << 20), 9)
(FUZZ / "regressions" / "texture_inflates_past_header.png").write_bytes(
    b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", 4, 4, 8, 2, 0, 0, 0)) +
    chunk(b"IDAT", bomb) + chunk(b"IEND", b""))

# --- dictionaries ----------------------------------------------------------------------------
def dict_file(target, tokens):
    lines = [f"# Tokens for the {target} fuzzer, written by fuzz/make_seeds.py."]
    for token in sorted(set(tokens)):
        escaped = "".join(c if 32 <= ord(c) < 127 and c not in '"\\' else f"\\x{ord(c):02x}"
                          for c in token)
        lines.append(f'"{escaped}"')
    (FUZZ / f"{target}.dict").write_text("\n".join(lines) + "\n")


# The scene and override dictionaries come from the scene schema (relief_scene_docs --write .),
# so that every field and choice reaches them; the soup and texture ones are written here.
dict_file("soup", ["#", "\r\n", "\n", "\xef\xbb\xbf", "1e30", "-1e30", "2097152", "16384",
                   "0.5", "1e-45", "-0", "nan", "inf", "0x1p3", "1e-400"])
dict_file("texture", ["IHDR", "IDAT", "IEND", "PLTE", "tRNS", "gAMA", "CgBI", "iTXt",
                      "\x89PNG\r\n\x1a\n", "\x00\x00\x00\x0dIHDR", "\x00\x00\x10\x00",
                      "\x00\x00\x00\x04", "\x08\x02\x00\x00\x00", "\x08\x06\x00\x00\x00"])
