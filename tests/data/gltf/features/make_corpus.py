#!/usr/bin/env python3
"""Writes the glTF feature corpus in this directory: one small file per glTF feature limn reads
or refuses (README.md lists them). The compressed files are encoded by the libraries' own
encoders, never by hand: Draco by Debian's `draco_encoder` (package draco), meshopt by
meshoptimizer's C encoders (libmeshoptimizer, through ctypes), with the exact settings below.

Run from anywhere: python3 tests/data/gltf/features/make_corpus.py
The output is deterministic; the files are committed, so the tests need neither tool.
"""
import base64
import ctypes
import json
import os
import struct
import subprocess
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))

# A unit cube, 24 vertices (4 per side, each side its own UVs), 12 triangles, counter-clockwise
# seen from outside; glTF's UVs (v down).
SIDES = [  # (normal axis, sign): corners of the side in counter-clockwise order from outside
    [(0, 0, 1), (1, 0, 1), (1, 1, 1), (0, 1, 1)],  # +z
    [(1, 0, 0), (0, 0, 0), (0, 1, 0), (1, 1, 0)],  # -z
    [(1, 0, 1), (1, 0, 0), (1, 1, 0), (1, 1, 1)],  # +x
    [(0, 0, 0), (0, 0, 1), (0, 1, 1), (0, 1, 0)],  # -x
    [(0, 1, 1), (1, 1, 1), (1, 1, 0), (0, 1, 0)],  # +y
    [(0, 0, 0), (1, 0, 0), (1, 0, 1), (0, 0, 1)],  # -y
]
CUBE_POS = [p for side in SIDES for p in side]
CUBE_UV = [uv for _ in SIDES for uv in [(0, 1), (1, 1), (1, 0), (0, 0)]]
CUBE_IDX = [i for s in range(6) for i in (4 * s, 4 * s + 1, 4 * s + 2, 4 * s, 4 * s + 2, 4 * s + 3)]


def f32(values):
    return b"".join(struct.pack("<f", v) for v in values)


def u16(values):
    return b"".join(struct.pack("<H", v) for v in values)


def pad4(b):
    return b + b"\0" * (-len(b) % 4)


class Builder:
    """Collects buffer views in one embedded buffer and writes the JSON."""

    def __init__(self):
        self.data = b""
        self.doc = {"asset": {"version": "2.0", "generator": "limn tests/data/gltf/features/make_corpus.py"},
                    "bufferViews": [], "accessors": []}

    def view(self, payload, extra=None):
        self.data = pad4(self.data)
        v = {"buffer": 0, "byteOffset": len(self.data), "byteLength": len(payload)}
        v.update(extra or {})
        self.data += payload
        self.doc["bufferViews"].append(v)
        return len(self.doc["bufferViews"]) - 1

    def accessor(self, view, component, count, kind, extra=None):
        a = {"componentType": component, "count": count, "type": kind}
        if view is not None:
            a["bufferView"] = view
        a.update(extra or {})
        self.doc["accessors"].append(a)
        return len(self.doc["accessors"]) - 1

    def write(self, name, buffers_extra=None):
        buffer = {"byteLength": len(self.data),
                  "uri": "data:application/octet-stream;base64," + base64.b64encode(self.data).decode()}
        self.doc["buffers"] = [buffer] + (buffers_extra or [])
        with open(os.path.join(HERE, name), "w") as f:
            json.dump(self.doc, f, indent=1, sort_keys=True)
            f.write("\n")


def bounds(points):
    return {"min": [min(p[i] for p in points) for i in range(3)], "max": [max(p[i] for p in points) for i in range(3)]}


def one_node_scene(doc, mesh_extra=None, node_extra=None):
    doc["scene"] = 0
    doc["scenes"] = [{"nodes": [0]}]
    doc["nodes"] = [dict({"mesh": 0}, **(node_extra or {}))]
    doc["meshes"] = [dict({"primitives": [doc.pop("_prim")]}, **(mesh_extra or {}))]


def cube(name, extensions_used=None, required=None):
    b = Builder()
    pos = b.accessor(b.view(f32([c for p in CUBE_POS for c in p])), 5126, 24, "VEC3", bounds(CUBE_POS))
    uv = b.accessor(b.view(f32([c for p in CUBE_UV for c in p])), 5126, 24, "VEC2")
    idx = b.accessor(b.view(u16(CUBE_IDX)), 5123, 36, "SCALAR")
    b.doc["_prim"] = {"attributes": {"POSITION": pos, "TEXCOORD_0": uv}, "indices": idx}
    one_node_scene(b.doc)
    if extensions_used:
        b.doc["extensionsUsed"] = extensions_used
    if required:
        b.doc["extensionsRequired"] = required
    b.write(name)


def cube_draco():
    # draco_encoder reads the cube as OBJ (vt as glTF's UVs, unflipped): Draco ids 0 POSITION,
    # 1 TEXCOORD_0. 14 position bits over the unit cube: a step of 1/16383.
    with tempfile.TemporaryDirectory() as tmp:
        obj = os.path.join(tmp, "cube.obj")
        with open(obj, "w") as f:
            for p in CUBE_POS:
                f.write("v %g %g %g\n" % p)
            for t in CUBE_UV:
                f.write("vt %g %g\n" % t)
            for t in range(12):
                f.write("f " + " ".join("%d/%d" % (i + 1, i + 1) for i in CUBE_IDX[3 * t:3 * t + 3]) + "\n")
        drc = os.path.join(tmp, "cube.drc")
        subprocess.run(["draco_encoder", "-i", obj, "-o", drc, "-qp", "14", "-qt", "12", "-cl", "7"],
                       check=True, stdout=subprocess.DEVNULL)
        payload = open(drc, "rb").read()
    b = Builder()
    view = b.view(payload)
    pos = b.accessor(None, 5126, 24, "VEC3", bounds(CUBE_POS))
    uv = b.accessor(None, 5126, 24, "VEC2")
    idx = b.accessor(None, 5123, 36, "SCALAR")
    b.doc["_prim"] = {"attributes": {"POSITION": pos, "TEXCOORD_0": uv}, "indices": idx,
                      "extensions": {"KHR_draco_mesh_compression": {"bufferView": view,
                                                                    "attributes": {"POSITION": 0, "TEXCOORD_0": 1}}}}
    one_node_scene(b.doc)
    b.doc["extensionsUsed"] = b.doc["extensionsRequired"] = ["KHR_draco_mesh_compression"]
    b.write("cube_draco.gltf")


def cube_meshopt(extension):
    lib = ctypes.CDLL("libmeshoptimizer.so")
    for fn in ("meshopt_encodeVertexBufferBound", "meshopt_encodeVertexBuffer", "meshopt_encodeIndexBufferBound",
               "meshopt_encodeIndexBuffer"):
        getattr(lib, fn).restype = ctypes.c_size_t
    lib.meshopt_encodeVertexVersion(0)  # the version both EXT and KHR decode
    lib.meshopt_encodeIndexVersion(1)

    def vertices(raw, count, stride):
        out = ctypes.create_string_buffer(lib.meshopt_encodeVertexBufferBound(ctypes.c_size_t(count), ctypes.c_size_t(stride)))
        n = lib.meshopt_encodeVertexBuffer(out, ctypes.c_size_t(len(out)), raw, ctypes.c_size_t(count), ctypes.c_size_t(stride))
        return out.raw[:n]

    def indices(values):
        arr = (ctypes.c_uint * len(values))(*values)
        out = ctypes.create_string_buffer(lib.meshopt_encodeIndexBufferBound(ctypes.c_size_t(len(values)), ctypes.c_size_t(24)))
        n = lib.meshopt_encodeIndexBuffer(out, ctypes.c_size_t(len(out)), arr, ctypes.c_size_t(len(values)))
        return out.raw[:n]

    b = Builder()
    streams = [(f32([c for p in CUBE_POS for c in p]), 24, 12, "ATTRIBUTES"),
               (f32([c for p in CUBE_UV for c in p]), 24, 8, "ATTRIBUTES"),
               (u16(CUBE_IDX), 36, 2, "TRIANGLES")]
    fallback = 0
    views = []
    for raw, count, stride, mode in streams:
        encoded = vertices(raw, count, stride) if mode == "ATTRIBUTES" else indices(CUBE_IDX)
        b.data = pad4(b.data)
        offset = len(b.data)
        b.data += encoded
        fallback = (fallback + 3) // 4 * 4
        v = {"buffer": 1, "byteOffset": fallback, "byteLength": count * stride,
             "extensions": {extension: {"buffer": 0, "byteOffset": offset, "byteLength": len(encoded),
                                        "byteStride": stride, "count": count, "mode": mode}}}
        if mode == "ATTRIBUTES":
            v["byteStride"] = stride
        fallback += count * stride
        b.doc["bufferViews"].append(v)
        views.append(len(b.doc["bufferViews"]) - 1)
    pos = b.accessor(views[0], 5126, 24, "VEC3", bounds(CUBE_POS))
    uv = b.accessor(views[1], 5126, 24, "VEC2")
    idx = b.accessor(views[2], 5123, 36, "SCALAR")
    b.doc["_prim"] = {"attributes": {"POSITION": pos, "TEXCOORD_0": uv}, "indices": idx}
    one_node_scene(b.doc)
    b.doc["extensionsUsed"] = b.doc["extensionsRequired"] = [extension]
    name = "cube_meshopt.gltf" if extension.startswith("EXT") else "cube_meshopt_khr.gltf"
    b.write(name, [{"byteLength": fallback, "extensions": {extension: {"fallback": True}}}])


# A 2 x 1 strip of two unit squares in the XY plane as four triangles, facing +z.
STRIP = [(0, 0, 0), (1, 0, 0), (2, 0, 0), (0, 1, 0), (1, 1, 0), (2, 1, 0)]
STRIP_IDX = [0, 1, 4, 0, 4, 3, 1, 2, 5, 1, 5, 4]


def strip_file(name, positions_accessor, extra_doc=None, prim_extra=None, mesh_extra=None):
    b = Builder()
    pos = positions_accessor(b)
    idx = b.accessor(b.view(u16(STRIP_IDX)), 5123, 12, "SCALAR")
    b.doc["_prim"] = dict({"attributes": {"POSITION": pos}, "indices": idx}, **(prim_extra(b) if prim_extra else {}))
    one_node_scene(b.doc, mesh_extra)
    b.doc.update(extra_doc or {})
    b.write(name)


def sparse_positions(b):
    # Dense strip, then vertices 4 and 5 lifted to z = 0.5 by a sparse substitution.
    base = b.view(f32([c for p in STRIP for c in p]))
    ind = b.view(u16([4, 5]))
    val = b.view(f32([1, 1, 0.5, 2, 1, 0.5]))
    return b.accessor(base, 5126, 6, "VEC3", {"min": [0, 0, 0], "max": [2, 1, 0.5],
                                              "sparse": {"count": 2, "indices": {"bufferView": ind, "componentType": 5123},
                                                         "values": {"bufferView": val}}})


def zero_positions(b):
    # No buffer view: six zeros, then every vertex but 0 given by a sparse substitution (glTF
    # 2.0, 3.6.2.3): vertex 0 stays at the origin.
    ind = b.view(u16([1, 2, 3, 4, 5]))
    val = b.view(f32([c for p in STRIP[1:] for c in p]))
    return b.accessor(None, 5126, 6, "VEC3", {"min": [0, 0, 0], "max": [2, 1, 0],
                                              "sparse": {"count": 5, "indices": {"bufferView": ind, "componentType": 5123},
                                                         "values": {"bufferView": val}}})


def dense_positions(b):
    return b.accessor(b.view(f32([c for p in STRIP for c in p])), 5126, 6, "VEC3", {"min": [0, 0, 0], "max": [2, 1, 0]})


def morph_targets(b):
    # Target 0 lifts the top row by (0, 0, 1); target 1 moves vertex 2 by (1, 0, 0), given
    # sparsely on an accessor without a buffer view. Default weights: 0.25, 0.5.
    t0 = b.accessor(b.view(f32([0, 0, 0] * 3 + [0, 0, 1] * 3)), 5126, 6, "VEC3", {"min": [0, 0, 0], "max": [0, 0, 1]})
    ind = b.view(u16([2]))
    val = b.view(f32([1, 0, 0]))
    t1 = b.accessor(None, 5126, 6, "VEC3", {"min": [0, 0, 0], "max": [1, 0, 0],
                                            "sparse": {"count": 1, "indices": {"bufferView": ind, "componentType": 5123},
                                                       "values": {"bufferView": val}}})
    return {"targets": [{"POSITION": t0}, {"POSITION": t1}]}


# A 1 x 1 PNG (opaque red), for the texture transform file.
RED_PNG = base64.b64decode(
    "iVBORw0KGgoAAAANSUhEUgAAAAEAAAABCAIAAACQd1PeAAAADElEQVR4nGP4z8AAAAMBAQDJ/pLvAAAAAElFTkSuQmCC")


def texture_transform():
    b = Builder()
    pos = dense_positions(b)
    uv = b.accessor(b.view(f32([0, 1, 0.5, 1, 1, 1, 0, 0, 0.5, 0, 1, 0])), 5126, 6, "VEC2")
    idx = b.accessor(b.view(u16(STRIP_IDX)), 5123, 12, "SCALAR")
    b.doc["_prim"] = {"attributes": {"POSITION": pos, "TEXCOORD_0": uv}, "indices": idx, "material": 0}
    one_node_scene(b.doc)
    # Scale (0.5, 0.5) then offset (0.5, 0): the texture's right half at the top, as a viewer shows it.
    b.doc["materials"] = [{"pbrMetallicRoughness": {"baseColorTexture": {
        "index": 0, "extensions": {"KHR_texture_transform": {"offset": [0.5, 0], "scale": [0.5, 0.5]}}}}}]
    b.doc["textures"] = [{"source": 0}]
    b.doc["images"] = [{"uri": "data:image/png;base64," + base64.b64encode(RED_PNG).decode()}]
    b.doc["extensionsUsed"] = ["KHR_texture_transform"]
    b.write("texture_transform.gltf")


def mirrored():
    # The cube twice: node 0 as it is, node 1 mirrored by scale (-1, 1, 1) and moved to x = -2..-1.
    b = Builder()
    pos = b.accessor(b.view(f32([c for p in CUBE_POS for c in p])), 5126, 24, "VEC3", bounds(CUBE_POS))
    idx = b.accessor(b.view(u16(CUBE_IDX)), 5123, 36, "SCALAR")
    b.doc["meshes"] = [{"primitives": [{"attributes": {"POSITION": pos}, "indices": idx}]}]
    b.doc["nodes"] = [{"mesh": 0}, {"mesh": 0, "translation": [-1, 0, 0], "scale": [-1, 1, 1]}]
    b.doc["scenes"] = [{"nodes": [0, 1]}]
    b.doc["scene"] = 0
    b.write("mirrored_node.gltf")


def graph(name, nodes, roots):
    b = Builder()
    pos = dense_positions(b)
    idx = b.accessor(b.view(u16(STRIP_IDX)), 5123, 12, "SCALAR")
    b.doc["meshes"] = [{"primitives": [{"attributes": {"POSITION": pos}, "indices": idx}]}]
    b.doc["nodes"] = nodes
    b.doc["scenes"] = [{"nodes": roots}]
    b.doc["scene"] = 0
    b.write(name)


def ngon():
    # A quad (0 1 4 3) and a pentagon (1 2 5 6 4) stored as FB_ngon_encoding fans: the triangles of
    # one polygon are consecutive and share their first index.
    b = Builder()
    points = STRIP + [(1.5, 1.5, 0)]
    pos = b.accessor(b.view(f32([c for p in points for c in p])), 5126, 7, "VEC3", {"min": [0, 0, 0], "max": [2, 1.5, 0]})
    fans = [0, 1, 4, 0, 4, 3, 1, 2, 5, 1, 5, 6, 1, 6, 4]
    idx = b.accessor(b.view(u16(fans)), 5123, 15, "SCALAR")
    b.doc["_prim"] = {"attributes": {"POSITION": pos}, "indices": idx, "extensions": {"FB_ngon_encoding": {}}}
    one_node_scene(b.doc)
    b.doc["extensionsUsed"] = ["FB_ngon_encoding"]
    b.write("ngon_encoding.gltf")


def morph_animation():
    # The strip with one target (the top row lifted by 1), default weight 0.25, and an animation
    # of that weight: 0, 1, 0.5 at 0, 1, 2 seconds, linear.
    b = Builder()
    pos = dense_positions(b)
    target = b.accessor(b.view(f32([0, 0, 0] * 3 + [0, 0, 1] * 3)), 5126, 6, "VEC3", {"min": [0, 0, 0], "max": [0, 0, 1]})
    idx = b.accessor(b.view(u16(STRIP_IDX)), 5123, 12, "SCALAR")
    times = b.accessor(b.view(f32([0, 1, 2])), 5126, 3, "SCALAR", {"min": [0], "max": [2]})
    weights = b.accessor(b.view(f32([0, 1, 0.5])), 5126, 3, "SCALAR")
    b.doc["_prim"] = {"attributes": {"POSITION": pos}, "indices": idx, "targets": [{"POSITION": target}]}
    one_node_scene(b.doc, {"weights": [0.25]})
    b.doc["animations"] = [{"channels": [{"sampler": 0, "target": {"node": 0, "path": "weights"}}],
                            "samplers": [{"input": times, "output": weights, "interpolation": "LINEAR"}]}]
    b.write("morph_animation.gltf")


def main():
    cube("cube.gltf")
    cube_draco()
    cube_meshopt("EXT_meshopt_compression")
    cube_meshopt("KHR_meshopt_compression")
    strip_file("sparse.gltf", sparse_positions)
    strip_file("no_buffer_view.gltf", zero_positions)
    strip_file("morph_targets.gltf", dense_positions, prim_extra=morph_targets, mesh_extra={"weights": [0.25, 0.5]})
    morph_animation()
    texture_transform()
    mirrored()
    # 60 nodes, each listing the next twice: 2^60 paths to the last one.
    graph("dag.gltf", [{"children": [i + 1, i + 1]} for i in range(59)] + [{"mesh": 0}], [0])
    graph("cycle.gltf", [{"children": [1]}, {"children": [2], "mesh": 0}, {"children": [1]}], [0])
    cube("requires_unknown.gltf", ["KHR_materials_clearcoat", "KHR_texture_basisu"], ["KHR_texture_basisu"])
    cube("uses_unknown.gltf", ["KHR_materials_clearcoat"])
    ngon()


if __name__ == "__main__":
    main()
