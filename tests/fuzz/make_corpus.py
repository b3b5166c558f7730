#!/usr/bin/env python3
"""Writes the seed corpus of the glTF fuzz target (tests/fuzz/corpus/): a few tiny, valid scenes that between
them reach every part of the loader (framing, accessors of each component type, data URIs, images, the node
hierarchy, lights, cameras, materials and their extensions), and the input that used to crash it.

    tests/fuzz/make_corpus.py        rewrites the files; the output is the same on every run

Seeds are kept small: libFuzzer mutates them, and a short input runs faster."""
import base64
import json
import os
import struct
import zlib

HERE = os.path.dirname(os.path.abspath(__file__))
OUT = os.path.join(HERE, "corpus")


def f32(*values):
    return struct.pack("<%df" % len(values), *values)


class Builder:
    """One buffer, one bufferView and accessor per call, as tests/core/gltf_test_builder.h does in C++."""

    def __init__(self):
        self.doc = {"asset": {"version": "2.0"}}
        self.bin = b""

    def view(self, data):
        self.bin += b"\0" * (-len(self.bin) % 4)
        self.doc.setdefault("bufferViews", []).append(
            {"buffer": 0, "byteOffset": len(self.bin), "byteLength": len(data)})
        self.bin += data
        return len(self.doc["bufferViews"]) - 1

    def accessor(self, data, type_, component, count, **extra):
        a = {"bufferView": self.view(data), "componentType": component, "count": count, "type": type_}
        a.update(extra)
        self.doc.setdefault("accessors", []).append(a)
        return len(self.doc["accessors"]) - 1

    def gltf(self):
        d = json.loads(json.dumps(self.doc))
        d["buffers"] = [{"byteLength": len(self.bin),
                         "uri": "data:application/octet-stream;base64," + base64.b64encode(self.bin).decode()}]
        return json.dumps(d, separators=(",", ":")).encode()

    def glb(self):
        d = json.loads(json.dumps(self.doc))
        d["buffers"] = [{"byteLength": len(self.bin)}]
        text = json.dumps(d, separators=(",", ":")).encode()
        text += b" " * (-len(text) % 4)
        body = self.bin + b"\0" * (-len(self.bin) % 4)
        chunks = struct.pack("<I4s", len(text), b"JSON") + text + struct.pack("<I4s", len(body), b"BIN\0") + body
        return b"glTF" + struct.pack("<II", 2, 12 + len(chunks)) + chunks


def png_1x1(rgba):
    def chunk(kind, data):
        return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data))
    raw = b"\0" + bytes(rgba)
    return (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", 1, 1, 8, 6, 0, 0, 0)) +
            chunk(b"IDAT", zlib.compress(raw, 9)) + chunk(b"IEND", b""))


def triangle(b, with_normals=True, index_type=5125):
    pos = b.accessor(f32(0, 0, 0, 1, 0, 0, 0, 1, 0), "VEC3", 5126, 3, min=[0, 0, 0], max=[1, 1, 0])
    attrs = {"POSITION": pos}
    if with_normals:
        attrs["NORMAL"] = b.accessor(f32(0, 0, 1, 0, 0, 1, 0, 0, 1), "VEC3", 5126, 3)
    fmt = {5121: "<3B", 5123: "<3H", 5125: "<3I"}[index_type]
    idx = b.accessor(struct.pack(fmt, 0, 1, 2), "SCALAR", index_type, 3)
    return {"attributes": attrs, "indices": idx}


def lit_scene():
    """A triangle with a material using the extensions the loader reads, a camera and every light type."""
    b = Builder()
    prim = triangle(b)
    prim["material"] = 0
    b.doc["extensionsUsed"] = ["KHR_lights_punctual", "KHR_materials_specular", "KHR_materials_emissive_strength"]
    b.doc["materials"] = [{"pbrMetallicRoughness": {"baseColorFactor": [0.8, 0.5, 0.2, 1], "metallicFactor": 0.1,
                                                    "roughnessFactor": 0.6},
                           "emissiveFactor": [1, 0.5, 0.25], "doubleSided": True,
                           "extensions": {"KHR_materials_specular": {"specularFactor": 0.5,
                                                                     "specularColorFactor": [1, 0.9, 0.8]},
                                          "KHR_materials_emissive_strength": {"emissiveStrength": 2}}}]
    b.doc["meshes"] = [{"primitives": [prim]}]
    b.doc["cameras"] = [{"type": "perspective", "perspective": {"yfov": 0.7, "znear": 0.01, "zfar": 100,
                                                                "aspectRatio": 1}}]
    b.doc["extensions"] = {"KHR_lights_punctual": {"lights": [
        {"type": "point", "color": [1, 1, 1], "intensity": 10},
        {"type": "spot", "intensity": 5, "spot": {"innerConeAngle": 0.2, "outerConeAngle": 0.7}},
        {"type": "directional", "color": [1, 0.9, 0.8], "intensity": 2}]}}
    b.doc["nodes"] = [{"mesh": 0},
                      {"camera": 0, "translation": [0.5, 0.5, 2]},
                      {"extensions": {"KHR_lights_punctual": {"light": 0}}, "translation": [0, 1, 1]},
                      {"extensions": {"KHR_lights_punctual": {"light": 1}}, "rotation": [-0.7071068, 0, 0, 0.7071068],
                       "translation": [0.5, 2, 0.5]},
                      {"extensions": {"KHR_lights_punctual": {"light": 2}},
                       "matrix": [1, 0, 0, 0, 0, 0, -1, 0, 0, 1, 0, 0, 0, 0, 0, 1]}]
    b.doc["scenes"] = [{"nodes": [0, 1, 2, 3, 4]}]
    b.doc["scene"] = 0
    return b


def textured_scene():
    """Texture coordinates and a 1x1 PNG base-colour texture, from a data URI or (GLB) a bufferView."""
    b = Builder()
    prim = triangle(b, index_type=5123)
    prim["attributes"]["TEXCOORD_0"] = b.accessor(f32(0, 0, 1, 0, 0, 1), "VEC2", 5126, 3)
    prim["material"] = 0
    b.doc["meshes"] = [{"primitives": [prim]}]
    b.doc["materials"] = [{"pbrMetallicRoughness": {"baseColorTexture": {"index": 0}}}]
    b.doc["textures"] = [{"source": 0, "sampler": 0}]
    b.doc["samplers"] = [{"magFilter": 9729, "minFilter": 9729}]
    b.doc["nodes"] = [{"mesh": 0}]
    b.doc["scenes"] = [{"nodes": [0]}]
    return b


def hierarchy_scene():
    """A node tree with TRS at every level, a mesh used twice, flat normals (no NORMAL), byte indices,
    normalised short texture coordinates, a line primitive the loader skips, and no camera (framed)."""
    b = Builder()
    tri = triangle(b, with_normals=False, index_type=5121)
    tri["attributes"]["TEXCOORD_0"] = b.accessor(struct.pack("<6H", 0, 0, 65535, 0, 0, 65535), "VEC2", 5123, 3,
                                                 normalized=True)
    lines = {"attributes": {"POSITION": tri["attributes"]["POSITION"]}, "mode": 1}
    b.doc["meshes"] = [{"primitives": [tri, lines]}]
    b.doc["nodes"] = [{"children": [1, 2], "scale": [2, 2, 2]},
                      {"mesh": 0, "translation": [1, 0, 0]},
                      {"children": [3], "rotation": [0, 0.3826834, 0, 0.9238795]},
                      {"mesh": 0, "translation": [0, 0, -1], "extras": {"note": [1, [2, [3]]]}}]
    b.doc["scenes"] = [{"nodes": [0]}]
    b.doc["scene"] = 0
    return b


def write(name, data):
    with open(os.path.join(OUT, name), "wb") as f:
        f.write(data)


def main():
    os.makedirs(OUT, exist_ok=True)
    write("minimal.gltf", b'{"asset":{"version":"2.0"}}')
    write("lit.gltf", lit_scene().gltf())
    write("lit.glb", lit_scene().glb())

    t = textured_scene()
    png = png_1x1([200, 100, 50, 255])
    t.doc["images"] = [{"uri": "data:image/png;base64," + base64.b64encode(png).decode()}]
    write("textured.gltf", t.gltf())
    t = textured_scene()
    t.doc["images"] = [{"bufferView": t.view(png), "mimeType": "image/png"}]
    write("textured.glb", t.glb())

    write("hierarchy.gltf", hierarchy_scene().gltf())
    # The crash of the reliability review: arrays nested 30,000 deep in `extras` overflowed the stack in
    # tinygltf's recursive JSON conversion (exit 139). core/json_depth.h now refuses it first.
    depth = 30000
    write("deep-extras-30000.gltf",
          b'{"asset":{"version":"2.0","extras":' + b"[" * depth + b"]" * depth + b'}}')


if __name__ == "__main__":
    main()
