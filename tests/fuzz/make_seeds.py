#!/usr/bin/env python3
"""Writes the fuzzers' hand-made seed corpus (tests/fuzz/seeds/): a few valid glTF 2.0 files,
then one malformed file per rule of the glTF 2.0 specification that the loader enforces, named
after the rule, each the valid triangle with that one rule broken; and fe command lines and
bench sweep files for CliFuzzer. The files are committed; rerun after adding a rule."""
import base64
import copy
import json
import os
import struct
import zlib

HERE = os.path.dirname(os.path.abspath(__file__))
GLTF = os.path.join(HERE, "seeds", "gltf")
CLI = os.path.join(HERE, "seeds", "cli")

POS = struct.pack("<9f", 0, 0, 0, 1, 0, 0, 0, 1, 0)
IDX = struct.pack("<3H", 0, 1, 2) + b"\0\0"
UV = struct.pack("<6f", 0, 0, 1, 0, 0, 1)
BIN = POS + IDX + UV


def png(w, h):
    raw = b"".join(b"\0" + bytes([200, 100, 50, 255]) * w for _ in range(h))
    chunk = lambda t, d: struct.pack(">I", len(d)) + t + d + struct.pack(">I", zlib.crc32(t + d))
    return (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", w, h, 8, 6, 0, 0, 0))
            + chunk(b"IDAT", zlib.compress(raw)) + chunk(b"IEND", b""))


def uri(data, mime="application/octet-stream"):
    return "data:%s;base64,%s" % (mime, base64.b64encode(data).decode())


def triangle():
    return {
        "asset": {"version": "2.0"},
        "scene": 0,
        "scenes": [{"nodes": [0]}],
        "nodes": [{"mesh": 0, "name": "Tri"}],
        "meshes": [{"primitives": [{"attributes": {"POSITION": 1, "TEXCOORD_0": 2}, "indices": 0, "material": 0}]}],
        "materials": [{"pbrMetallicRoughness": {"baseColorFactor": [1, 0.5, 0.25, 1], "baseColorTexture": {"index": 0}}}],
        "textures": [{"source": 0, "sampler": 0}],
        "samplers": [{"magFilter": 9729, "minFilter": 9987, "wrapS": 10497, "wrapT": 33071}],
        "images": [{"uri": uri(png(2, 2), "image/png")}],
        "buffers": [{"uri": uri(BIN), "byteLength": len(BIN)}],
        "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 36},
                        {"buffer": 0, "byteOffset": 36, "byteLength": 6},
                        {"buffer": 0, "byteOffset": 44, "byteLength": 24}],
        "accessors": [{"bufferView": 1, "componentType": 5123, "count": 3, "type": "SCALAR"},
                      {"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3", "min": [0, 0, 0], "max": [1, 1, 0]},
                      {"bufferView": 2, "componentType": 5126, "count": 3, "type": "VEC2"}],
    }


def glb(doc, bin_chunk=BIN, chunks=None, version=2, length_delta=0):
    text = json.dumps(doc).encode()
    text += b" " * (-len(text) % 4)
    bin_chunk = bin_chunk + b"\0" * (-len(bin_chunk) % 4)
    if chunks is None:
        chunks = [(b"JSON", text), (b"BIN\0", bin_chunk)]
    body = b"".join(struct.pack("<I", len(d)) + t + d for t, d in chunks)
    return b"glTF" + struct.pack("<II", version, 12 + len(body) + length_delta) + body


def binary_doc():
    d = triangle()
    d["buffers"] = [{"byteLength": len(BIN)}]
    return d


def broken(edit):
    d = triangle()
    edit(d)
    return d


def main():
    for folder in (GLTF, CLI):
        os.makedirs(folder, exist_ok=True)
        for f in os.listdir(folder):
            os.remove(os.path.join(folder, f))
    files = {}
    # Valid files.
    files["valid-triangle.gltf"] = triangle()
    files["valid-triangle.glb"] = glb(binary_doc())
    files["valid-lights-camera.gltf"] = broken(lambda d: d.update({
        "extensionsUsed": ["KHR_lights_punctual"],
        "extensions": {"KHR_lights_punctual": {"lights": [{"type": "spot", "intensity": 10, "spot": {"outerConeAngle": 0.5}},
                                                         {"type": "directional", "color": [1, 0.9, 0.8]}]}},
        "cameras": [{"type": "perspective", "perspective": {"yfov": 0.8, "znear": 0.1}}],
        "nodes": d["nodes"] + [{"camera": 0, "translation": [0, 0, 3]},
                               {"extensions": {"KHR_lights_punctual": {"light": 0}}, "rotation": [0, 0, 0, 1]},
                               {"extensions": {"KHR_lights_punctual": {"light": 1}}, "matrix": [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1]}],
        "scenes": [{"nodes": [0, 1, 2, 3]}]}))
    files["valid-sparse.gltf"] = broken(lambda d: d["accessors"][1].update({"sparse": {
        "count": 1, "indices": {"bufferView": 1, "componentType": 5123}, "values": {"bufferView": 0}}}))
    # One rule broken per file (glTF 2.0 section in the name where it has one).
    rules = {
        "asset-version-missing": lambda d: d["asset"].pop("version"),
        "asset-version-1.0": lambda d: d["asset"].update({"version": "1.0"}),
        "asset-minversion-2.1": lambda d: d["asset"].update({"minVersion": "2.1"}),
        "scene-without-scenes": lambda d: d.pop("scenes"),
        "scene-index-out-of-range": lambda d: d.update({"scene": 5}),
        "node-mesh-out-of-range": lambda d: d["nodes"][0].update({"mesh": 9}),
        "node-cycle": lambda d: d["nodes"][0].update({"children": [0]}),
        "node-two-parents": lambda d: d.update({"nodes": [{"children": [2]}, {"children": [2]}, {"mesh": 0}],
                                                "scenes": [{"nodes": [0, 1]}]}),
        "node-matrix-and-trs": lambda d: d["nodes"][0].update({"matrix": [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1],
                                                               "translation": [1, 0, 0]}),
        "node-non-finite-scale": lambda d: d["nodes"][0].update({"scale": [1e39, 1, 1]}),
        "accessor-past-bufferview": lambda d: d["accessors"][1].update({"count": 30}),
        "accessor-offset-past-end": lambda d: d["accessors"][1].update({"byteOffset": 400}),
        "accessor-component-type-invalid": lambda d: d["accessors"][1].update({"componentType": 5130}),
        "accessor-type-wrong-for-position": lambda d: d["accessors"][1].update({"type": "VEC2"}),
        "accessor-huge-without-bufferview": lambda d: d["accessors"][1].pop("bufferView") or d["accessors"][1].update({"count": 4000000000}),
        "accessor-sparse-index-out-of-range": lambda d: d["accessors"][1].update({"sparse": {
            "count": 1, "indices": {"bufferView": 0, "byteOffset": 14, "componentType": 5123}, "values": {"bufferView": 0}}}),  # index 16256
        "bufferview-past-buffer": lambda d: d["bufferViews"][0].update({"byteLength": 4000}),
        "bufferview-buffer-out-of-range": lambda d: d["bufferViews"][0].update({"buffer": 3}),
        "buffer-bytelength-mismatch": lambda d: d["buffers"][0].update({"byteLength": 4}),
        "buffer-uri-missing-file": lambda d: d["buffers"][0].update({"uri": "missing.bin"}),
        "indices-out-of-range": lambda d: d["accessors"][0].update({"bufferView": 2, "componentType": 5125}),
        "indices-not-scalar": lambda d: d["accessors"][0].update({"type": "VEC3", "count": 1}),
        "primitive-mode-invalid": lambda d: d["meshes"][0]["primitives"][0].update({"mode": 9}),
        "primitive-no-position": lambda d: d["meshes"][0]["primitives"][0]["attributes"].pop("POSITION"),
        "material-out-of-range": lambda d: d["meshes"][0]["primitives"][0].update({"material": 4}),
        "texture-source-out-of-range": lambda d: d["textures"][0].update({"source": 7}),
        "texture-sampler-out-of-range": lambda d: d["textures"][0].update({"sampler": 7}),
        "image-undecodable": lambda d: d["images"][0].update({"uri": uri(b"\x89PNG garbage", "image/png")}),
        "image-missing-file": lambda d: d["images"][0].update({"uri": "missing.png"}),
        "extension-required-unsupported": lambda d: d.update({"extensionsUsed": ["KHR_draco_mesh_compression"],
                                                              "extensionsRequired": ["KHR_draco_mesh_compression"]}),
        "camera-yfov-zero": lambda d: d.update({"cameras": [{"type": "perspective", "perspective": {"yfov": 0, "znear": 0.1}}],
                                                "nodes": d["nodes"] + [{"camera": 0}], "scenes": [{"nodes": [0, 1]}]}),
        "light-type-invalid": lambda d: d.update({"extensions": {"KHR_lights_punctual": {"lights": [{"type": "area"}]}},
                                                  "nodes": d["nodes"] + [{"extensions": {"KHR_lights_punctual": {"light": 0}}}],
                                                  "scenes": [{"nodes": [0, 1]}]}),
    }
    for name, edit in rules.items():
        files["rule-%s.gltf" % name] = broken(edit)
    text = json.dumps(triangle())
    files["rule-json-truncated.gltf"] = text[: len(text) // 2].encode()
    files["rule-json-byte-order-mark.gltf"] = b"\xef\xbb\xbf" + text.encode()
    files["rule-json-nested-too-deep.gltf"] = ("[" * 5000 + "]" * 5000).encode()
    j = json.dumps(binary_doc()).encode()
    j += b" " * (-len(j) % 4)
    b = BIN + b"\0" * (-len(BIN) % 4)
    files["rule-glb-bad-magic.glb"] = b"gLtF" + glb(binary_doc())[4:]
    files["rule-glb-version-1.glb"] = glb(binary_doc(), version=1)
    files["rule-glb-length-mismatch.glb"] = glb(binary_doc(), length_delta=8)
    files["rule-glb-duplicate-json.glb"] = glb(None, chunks=[(b"JSON", j), (b"BIN\0", b), (b"JSON", j)])
    files["rule-glb-duplicate-bin.glb"] = glb(None, chunks=[(b"JSON", j), (b"BIN\0", b), (b"BIN\0", b)])
    files["rule-glb-bin-first.glb"] = glb(None, chunks=[(b"BIN\0", b), (b"JSON", j)])
    files["rule-glb-misaligned-chunk.glb"] = glb(None, chunks=[(b"JSON", j + b" "), (b"BIN\0", b)])
    files["rule-glb-truncated.glb"] = glb(binary_doc())[:40]
    for name, content in files.items():
        data = content if isinstance(content, bytes) else json.dumps(content, indent=1).encode()
        with open(os.path.join(GLTF, name), "wb") as f:
            f.write(data)
    # CliFuzzer: "render" and its arguments one per line, or "sweep" and a sweep file.
    lines = {
        "render-default": ["render"],
        "render-techniques": ["render", "builtin:lights", "--technique", "deferred-tiled", "--lights", "64", "--size", "64x48"],
        "render-redeferred": ["render", "builtin:spheres", "--technique", "redeferred-tiled", "--illum-scale", "2", "--illum-split",
                              "--rates", "punctual=2,ibl-diffuse=4"],
        "render-shadows": ["render", "builtin:shadows", "--shadows", "on", "--shadow-map-size", "512", "--shadow-filter", "none"],
        "render-post": ["render", "--tonemap", "aces", "--aa", "taa", "--frames", "4", "--orbit", "30", "--exposure", "2.5"],
        "render-auto": ["render", "--technique", "auto", "--error-budget", "1.5", "--verbose", "--strict"],
        "render-bad-size": ["render", "--size", "0x99999"],
        "render-unknown-flag": ["render", "--bogus"],
        "render-help": ["render", "--help"],
        "render-missing-file": ["render", "/nonexistent/scene.gltf"],
    }
    for name, args in lines.items():
        with open(os.path.join(CLI, name), "w") as f:
            f.write("\n".join(args))
    sweeps = {
        "sweep-matrix": {"description": "x", "size": "64x48", "cases": [{"technique": "all", "scene": "builtin:lights", "lights": [1, 8]}]},
        "sweep-options": {"cases": [{"technique": "redeferred-tiled", "illumScale": [1, 2, 4], "illumSplit": True, "tonemap": "aces",
                                     "aa": "fxaa", "shadows": True}]},
        "sweep-bad": {"cases": [{"technique": "forward", "msaa": "four"}], "extra": 1},
    }
    for name, sweep in sweeps.items():
        with open(os.path.join(CLI, name), "w") as f:
            f.write("sweep\n" + json.dumps(sweep))
    print("wrote %d glTF seeds and %d command-line seeds" % (len(files), len(lines) + len(sweeps)))


if __name__ == "__main__":
    main()
