#!/usr/bin/env python3
"""Writes the model-loader test data: the good models, the bad files and the fuzz seeds.

    python3 tests/data/make_test_models.py        (from the repository root; deterministic)

Outputs (all committed; rerun after editing this script):
  models/alpha_quad.gltf   ground + alpha-masked quad (a 4x4 texture with holes) under a
                           KHR_lights_punctual sun whose size is in the light's extras, + a camera
  models/box.obj, box.mtl  a unit cube with a red Kd material
  models/lamps.gltf        a ground and a table top under a KHR_lights_punctual point light (its
                           sphere radius in extras) and a spot light with both cone angles, ranges
                           and colours: the importer must keep each light's kind and angles
  models/quantized_box.gltf  a unit box as gltfpack writes it (KHR_mesh_quantization): SHORT
                           normalised positions scaled back by the node, BYTE normals, USHORT
                           texture coordinates scaled back by KHR_texture_transform
  models/textured_quads.gltf  alpha_quad's masked quad over a ground whose colour is a JPEG
                           checker under KHR_texture_transform, with a WebP normal map that
                           nothing decodes (Penumbra ignores normal maps)
  scenes/obj_and_gltf.json a scene file that places the OBJ and the glTF side by side
  bad/*                    files every loader must reject with one clear error (docs/scenes.md)
  fuzz/gltf/*, fuzz/obj/*, fuzz/scene/* seed corpora for the libFuzzer targets
The compressed glTF files (Draco, meshopt) come from tests/support/CompressedModels.cpp
(penumbra_make_compressed_models tests/data).
Only the standard library is used (PNG, JPEG and GLB are written by hand).
"""
import base64
import json
import os
import struct
import zlib

ROOT = os.path.dirname(os.path.abspath(__file__))

# The alpha mask of alpha_quad.gltf, row 0 = the image's top row (glTF uv v = 0). 'X' = opaque,
# '.' = a hole. Asymmetric under both flips, so a loader that flips rows or columns fails the test
# (tests/gl/GltfTest.cpp holds the same pattern).
MASK = ["X.XX",
        "..X.",
        "X...",
        "XX.X"]
QUAD_HALF_M = 1.0     # the masked quad spans x, z in [-1, 1] at height QUAD_HEIGHT_M
QUAD_HEIGHT_M = 1.0
GROUND_HALF_M = 3.0
SUN_SIZE_RAD = 0.005  # extras.size of the sun: a small angular radius, sharp enough for probes


def png(width, height, rgba_rows):
    """RGBA8 PNG from rows of bytes (row 0 = top)."""
    raw = b"".join(b"\x00" + bytes(row) for row in rgba_rows)
    def chunk(kind, data):
        return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data) & 0xFFFFFFFF)
    return (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", width, height, 8, 6, 0, 0, 0))
            + chunk(b"IDAT", zlib.compress(raw, 9)) + chunk(b"IEND", b""))


def mask_png():
    rows = []
    for line in MASK:
        row = []
        for c in line:
            row += [220, 40, 30, 255] if c == "X" else [0, 0, 0, 0]
        rows.append(row)
    return png(4, 4, rows)


# The ground texture of textured_quads.gltf: 4 x 4 blocks of 8 x 8 texels, row 0 = the image's
# top row. Asymmetric under flips and quarter turns, so a wrong transform shows.
CHECKER = ["ABAA",
           "BBAB",
           "ABBB",
           "AABA"]
CHECKER_RGB = {"A": (230, 200, 40), "B": (30, 60, 190)}
CHECKER_BLOCK = 8
# KHR_texture_transform of the ground: uv' = offset + rotate(rotation) (scale * uv).
GROUND_UV_SCALE = [2.0, 2.0]
GROUND_UV_ROTATION = 1.5707963267948966  # a quarter turn: u' = 2v, v' = -2u
GROUND_UV_OFFSET = [0.0, 0.0]


def jpeg_blocks(width, height, block_rgb):
    """Baseline JPEG (4:4:4, quantisation 1) of an image whose 8 x 8 blocks are each one colour:
    only DC coefficients, so a few lines encode it exactly. block_rgb(bx, by) -> (r, g, b)."""
    def segment(marker, payload):
        return struct.pack(">BBH", 0xFF, marker, len(payload) + 2) + payload

    def canonical(counts, symbols):  # JPEG Huffman codes from the per-length counts
        codes, code, k = {}, 0, 0
        for length in range(1, 17):
            for _ in range(counts[length - 1]):
                codes[symbols[k]] = (code, length)
                code += 1
                k += 1
            code <<= 1
        return codes
    dc_counts = [0, 1, 5, 1, 1, 1, 1, 1, 1, 0, 0, 0, 0, 0, 0, 0]  # ITU T.81 table K.3
    dc_symbols = list(range(12))
    ac_counts = [1] + [0] * 15  # one code: end of block
    ac_symbols = [0x00]
    dc_codes, ac_codes = canonical(dc_counts, dc_symbols), canonical(ac_counts, ac_symbols)

    bits = []
    def put(value, length):
        bits.extend((value >> (length - 1 - i)) & 1 for i in range(length))
    def put_dc(diff):
        category = abs(diff).bit_length()
        put(*dc_codes[category])
        if category:
            put(diff if diff >= 0 else diff + (1 << category) - 1, category)
    previous = [0, 0, 0]
    for by in range(height // 8):
        for bx in range(width // 8):
            r, g, b = block_rgb(bx, by)
            ycc = (0.299 * r + 0.587 * g + 0.114 * b,
                   -0.168736 * r - 0.331264 * g + 0.5 * b + 128,
                   0.5 * r - 0.418688 * g - 0.081312 * b + 128)
            for c in range(3):
                dc = 8 * (int(round(ycc[c])) - 128)  # the DCT's DC term of a flat block
                put_dc(dc - previous[c])
                previous[c] = dc
                put(*ac_codes[0x00])
    bits.extend([1] * (-len(bits) % 8))
    scan = bytearray()
    for i in range(0, len(bits), 8):
        byte = int("".join(map(str, bits[i:i + 8])), 2)
        scan.append(byte)
        if byte == 0xFF:
            scan.append(0x00)  # byte stuffing
    return (b"\xFF\xD8"
            + segment(0xE0, b"JFIF\x00\x01\x01\x00\x00\x01\x00\x01\x00\x00")
            + segment(0xDB, b"\x00" + bytes([1] * 64))
            + segment(0xC0, struct.pack(">BHHB", 8, height, width, 3) + b"".join(bytes([c, 0x11, 0]) for c in (1, 2, 3)))
            + segment(0xC4, b"\x00" + bytes(dc_counts) + bytes(dc_symbols))
            + segment(0xC4, b"\x10" + bytes(ac_counts) + bytes(ac_symbols))
            + segment(0xDA, b"\x03" + b"".join(bytes([c, 0x00]) for c in (1, 2, 3)) + b"\x00\x3F\x00")
            + bytes(scan) + b"\xFF\xD9")


def checker_jpeg():
    return jpeg_blocks(4 * CHECKER_BLOCK, 4 * CHECKER_BLOCK, lambda bx, by: CHECKER_RGB[CHECKER[by][bx]])


# The first bytes of a WebP file: enough for a loader to see what it is, nothing to decode.
WEBP_HEADER = b"RIFF\x1a\x00\x00\x00WEBPVP8L\x0d\x00\x00\x00\x2f\x00\x00\x00\x10\x07\x10\x11\x11\x88\x88\xfe\x07\x00"


class Gltf:
    """A minimal glTF 2.0 builder: one buffer, accessors appended as they are added."""

    def __init__(self):
        self.doc = {"asset": {"version": "2.0", "generator": "penumbra tests/data/make_test_models.py"},
                    "buffers": [], "bufferViews": [], "accessors": [], "meshes": [], "nodes": [],
                    "scenes": [{"nodes": []}], "scene": 0}
        self.bin = bytearray()

    def view(self, data):
        while len(self.bin) % 4:
            self.bin.append(0)
        self.doc["bufferViews"].append({"buffer": 0, "byteOffset": len(self.bin), "byteLength": len(data)})
        self.bin += data
        return len(self.doc["bufferViews"]) - 1

    def accessor(self, fmt, values, kind, component):
        flat = [x for v in values for x in (v if isinstance(v, (list, tuple)) else [v])]
        view = self.view(struct.pack("<%d%s" % (len(flat), fmt), *flat))
        a = {"bufferView": view, "componentType": component, "count": len(values), "type": kind}
        if kind == "VEC3" and all(abs(x) < float("inf") for x in flat):  # NaN/inf are no JSON numbers
            a["min"] = [min(v[i] for v in values) for i in range(3)]
            a["max"] = [max(v[i] for v in values) for i in range(3)]
        self.doc["accessors"].append(a)
        return len(self.doc["accessors"]) - 1

    def quad(self, half, height, material, name):
        """A horizontal quad, normal +Y, uv (0,0) at (-half, -half) in x, z."""
        pos = [(-half, height, -half), (half, height, -half), (half, height, half), (-half, height, half)]
        uv = [(0.0, 0.0), (1.0, 0.0), (1.0, 1.0), (0.0, 1.0)]
        prim = {"attributes": {"POSITION": self.accessor("f", pos, "VEC3", 5126),
                               "NORMAL": self.accessor("f", [(0.0, 1.0, 0.0)] * 4, "VEC3", 5126),
                               "TEXCOORD_0": self.accessor("f", uv, "VEC2", 5126)},
                "indices": self.accessor("H", [0, 2, 1, 0, 3, 2], "SCALAR", 5123), "material": material}
        self.doc["meshes"].append({"name": name, "primitives": [prim]})
        return len(self.doc["meshes"]) - 1

    def node(self, **fields):
        self.doc["nodes"].append(fields)
        return len(self.doc["nodes"]) - 1

    def finish_embedded(self):
        self.doc["buffers"] = [{"byteLength": len(self.bin),
                                "uri": "data:application/octet-stream;base64," + base64.b64encode(bytes(self.bin)).decode()}]
        return json.dumps(self.doc, indent=1).encode()


def alpha_quad_gltf():
    g = Gltf()
    g.doc["images"] = [{"uri": "data:image/png;base64," + base64.b64encode(mask_png()).decode()}]
    g.doc["textures"] = [{"source": 0}]
    g.doc["materials"] = [
        {"name": "ground", "pbrMetallicRoughness": {"baseColorFactor": [0.7, 0.7, 0.7, 1.0], "metallicFactor": 0.0}},
        {"name": "leaf mask", "alphaMode": "MASK", "alphaCutoff": 0.5, "doubleSided": True,
         "pbrMetallicRoughness": {"baseColorTexture": {"index": 0}, "metallicFactor": 0.0}}]
    ground = g.quad(GROUND_HALF_M, 0.0, 0, "ground")
    masked = g.quad(QUAD_HALF_M, QUAD_HEIGHT_M, 1, "masked quad")
    g.doc["extensionsUsed"] = ["KHR_lights_punctual"]
    g.doc["extensions"] = {"KHR_lights_punctual": {"lights": [
        {"name": "sun", "type": "directional", "intensity": 2.0, "color": [1.0, 0.97, 0.9],
         "extras": {"size": SUN_SIZE_RAD}}]}}
    g.doc["cameras"] = [{"type": "perspective", "perspective": {"yfov": 0.9, "znear": 0.1, "zfar": 100.0}}]
    # The sun shines straight down: local -Z turned onto -Y (-90° about X). The camera looks down
    # 50° from (0, 5.5, 4.6) (local -Z tilted by -50° about X).
    s50, c50 = -0.42261826, 0.90630779  # sin, cos of -25°
    roots = [g.node(name="ground", mesh=ground), g.node(name="masked quad", mesh=masked),
             g.node(name="sun", rotation=[-0.70710678, 0.0, 0.0, 0.70710678],
                    extensions={"KHR_lights_punctual": {"light": 0}}),
             g.node(name="camera", camera=0, translation=[0.0, 5.5, 4.6], rotation=[s50, 0.0, 0.0, c50])]
    g.doc["scenes"][0]["nodes"] = roots
    return g.finish_embedded()


def textured_quads_gltf():
    """alpha_quad.gltf with a JPEG-textured ground (KHR_texture_transform) and a WebP normal map."""
    g = json.loads(alpha_quad_gltf())
    g["images"].append({"uri": "data:image/jpeg;base64," + base64.b64encode(checker_jpeg()).decode()})
    g["images"].append({"uri": "data:image/webp;base64," + base64.b64encode(WEBP_HEADER).decode()})
    g["textures"] += [{"source": 1}, {"source": 2}]
    ground = g["materials"][0]
    ground["pbrMetallicRoughness"]["baseColorFactor"] = [1.0, 1.0, 1.0, 1.0]
    ground["pbrMetallicRoughness"]["baseColorTexture"] = {"index": 1, "extensions": {"KHR_texture_transform": {
        "offset": GROUND_UV_OFFSET, "rotation": GROUND_UV_ROTATION, "scale": GROUND_UV_SCALE}}}
    ground["normalTexture"] = {"index": 2}
    g["extensionsUsed"] += ["KHR_texture_transform"]
    g["extensionsRequired"] = ["KHR_texture_transform"]
    g["asset"]["generator"] = "penumbra tests/data/make_test_models.py"
    return json.dumps(g, indent=1).encode()


# lamps.gltf: a point lamp over a table top and a spot on the ground beside it.
LAMP_POSITION = [0.5, 1.6, 0.0]
LAMP_SIZE_M = 0.05
LAMP_RANGE_M = 8.0
SPOT_POSITION = [-2.0, 3.0, 0.0]
SPOT_INNER_RAD = 0.3
SPOT_OUTER_RAD = 0.6
SPOT_RANGE_M = 10.0


def lamps_gltf():
    g = Gltf()
    g.doc["materials"] = [
        {"name": "ground", "pbrMetallicRoughness": {"baseColorFactor": [0.7, 0.7, 0.7, 1.0], "metallicFactor": 0.0}},
        {"name": "wood", "doubleSided": True,
         "pbrMetallicRoughness": {"baseColorFactor": [0.55, 0.36, 0.22, 1.0], "metallicFactor": 0.0}}]
    ground = g.quad(GROUND_HALF_M, 0.0, 0, "ground")
    top = g.quad(0.5, 0.75, 1, "table top")
    g.doc["extensionsUsed"] = ["KHR_lights_punctual"]
    g.doc["extensions"] = {"KHR_lights_punctual": {"lights": [
        {"name": "lamp", "type": "point", "intensity": 3.0, "color": [1.0, 0.85, 0.65], "range": LAMP_RANGE_M,
         "extras": {"size": LAMP_SIZE_M}},
        {"name": "spot", "type": "spot", "intensity": 6.0, "color": [0.8, 0.9, 1.0], "range": SPOT_RANGE_M,
         "spot": {"innerConeAngle": SPOT_INNER_RAD, "outerConeAngle": SPOT_OUTER_RAD}}]}}
    g.doc["cameras"] = [{"type": "perspective", "perspective": {"yfov": 0.9, "znear": 0.1, "zfar": 100.0}}]
    # The spot shines straight down (local -Z turned onto -Y: -90 degrees about X); the camera
    # looks down 50 degrees as alpha_quad's does.
    s50, c50 = -0.42261826, 0.90630779  # sin, cos of -25 degrees
    roots = [g.node(name="ground", mesh=ground), g.node(name="table top", mesh=top),
             g.node(name="lamp", translation=LAMP_POSITION, extensions={"KHR_lights_punctual": {"light": 0}}),
             g.node(name="spot", translation=SPOT_POSITION, rotation=[-0.70710678, 0.0, 0.0, 0.70710678],
                    extensions={"KHR_lights_punctual": {"light": 1}}),
             g.node(name="camera", camera=0, translation=[0.0, 5.5, 4.6], rotation=[s50, 0.0, 0.0, c50])]
    g.doc["scenes"][0]["nodes"] = roots
    return g.finish_embedded()


# quantized_box.gltf: positions in [-1, 1] as normalised SHORT, the node scales them by half a
# metre; texture coordinates in [0, 1] as normalised USHORT, KHR_texture_transform scales by 2.
QUANT_BOX_HALF_M = 0.5
QUANT_UV_SCALE = 2.0


def quantized_box_gltf():
    g = Gltf()
    faces = [((0, 0, 1), (1, 0, 0), (0, 1, 0)), ((0, 0, -1), (-1, 0, 0), (0, 1, 0)), ((1, 0, 0), (0, 0, -1), (0, 1, 0)),
             ((-1, 0, 0), (0, 0, 1), (0, 1, 0)), ((0, 1, 0), (1, 0, 0), (0, 0, -1)), ((0, -1, 0), (1, 0, 0), (0, 0, 1))]
    pos, nrm, uv, idx = [], [], [], []
    for n, u, v in faces:
        base = len(pos)
        for su, sv in ((-1, -1), (1, -1), (1, 1), (-1, 1)):
            pos.append([n[i] + su * u[i] + sv * v[i] for i in range(3)])
            nrm.append(n)
            uv.append(((su + 1) / 2, (1 - sv) / 2))
        idx += [base, base + 1, base + 2, base, base + 2, base + 3]
    def packed(fmt, rows, pad):  # one element per stride, padded to 4 bytes as the extension requires
        return b"".join(struct.pack("<" + fmt, *r) + b"\x00" * pad for r in rows)
    def view(data, stride):
        index = g.view(data)
        g.doc["bufferViews"][index]["byteStride"] = stride
        return index
    q_pos = [[round(c * 32767) for c in p] for p in pos]
    q_nrm = [[round(c * 127) for c in n] for n in nrm]
    q_uv = [[round(c * 65535) for c in t] for t in uv]
    acc = g.doc["accessors"]
    acc.append({"bufferView": view(packed("3h", q_pos, 2), 8), "componentType": 5122, "normalized": True, "count": 24, "type": "VEC3",
                "min": [-32767] * 3, "max": [32767] * 3})
    acc.append({"bufferView": view(packed("3b", q_nrm, 1), 4), "componentType": 5120, "normalized": True, "count": 24, "type": "VEC3"})
    acc.append({"bufferView": view(packed("2H", q_uv, 0), 4), "componentType": 5123, "normalized": True, "count": 24, "type": "VEC2"})
    indices = g.accessor("H", idx, "SCALAR", 5123)
    g.doc["images"] = [{"uri": "data:image/png;base64," + base64.b64encode(mask_png()).decode()}]
    g.doc["textures"] = [{"source": 0}]
    g.doc["materials"] = [{"name": "quantized", "pbrMetallicRoughness": {"baseColorTexture": {"index": 0, "extensions": {
        "KHR_texture_transform": {"scale": [QUANT_UV_SCALE, QUANT_UV_SCALE]}}}}}]
    g.doc["meshes"].append({"name": "box", "primitives": [{"attributes": {"POSITION": 0, "NORMAL": 1, "TEXCOORD_0": 2},
                                                            "indices": indices, "material": 0}]})
    g.doc["scenes"][0]["nodes"] = [g.node(name="box", mesh=0, scale=[QUANT_BOX_HALF_M] * 3, translation=[0, QUANT_BOX_HALF_M, 0])]
    g.doc["extensionsUsed"] = g.doc["extensionsRequired"] = ["KHR_mesh_quantization", "KHR_texture_transform"]
    return g.finish_embedded()


def glb(doc_bytes, bin_bytes=b"", version=2, length=None, json_type=0x4E4F534A):
    doc_bytes += b" " * (-len(doc_bytes) % 4)
    body = struct.pack("<II", len(doc_bytes), json_type) + doc_bytes
    if bin_bytes:
        bin_bytes += b"\x00" * (-len(bin_bytes) % 4)
        body += struct.pack("<II", len(bin_bytes), 0x004E4942) + bin_bytes
    total = 12 + len(body) if length is None else length
    return struct.pack("<III", 0x46546C67, version, total) + body


def triangle_gltf(positions=None, indices=(0, 1, 2), mutate=None):
    """One triangle; `mutate(doc)` edits the document before it is written."""
    g = Gltf()
    pos = positions or [(0.0, 0.0, 0.0), (1.0, 0.0, 0.0), (0.0, 1.0, 0.0)]
    prim = {"attributes": {"POSITION": g.accessor("f", pos, "VEC3", 5126)},
            "indices": g.accessor("H", list(indices), "SCALAR", 5123)}
    g.doc["meshes"].append({"primitives": [prim]})
    g.doc["scenes"][0]["nodes"] = [g.node(mesh=0)]
    if mutate:
        mutate(g.doc)
    return g, g.finish_embedded()


def moving_triangle_gltf(times, translations, time_format="f", time_component=5126):
    """One triangle whose node's translation is keyed: `times` (an accessor of `time_component`)
    and one translation per key."""
    g, _ = triangle_gltf()
    t = g.accessor(time_format, list(times), "SCALAR", time_component)
    v = g.accessor("f", list(translations), "VEC3", 5126)
    g.doc["animations"] = [{"channels": [{"sampler": 0, "target": {"node": 0, "path": "translation"}}],
                            "samplers": [{"input": t, "output": v}]}]
    return g.finish_embedded()


def triangle_glb(mutate=None):
    g, _ = triangle_gltf(mutate=mutate)
    g.doc["buffers"] = [{"byteLength": len(g.bin)}]
    return glb(json.dumps(g.doc).encode(), bytes(g.bin))


def write(rel, data):
    path = os.path.join(ROOT, rel)
    os.makedirs(os.path.dirname(path), exist_ok=True)
    with open(path, "wb") as f:
        f.write(data if isinstance(data, bytes) else data.encode())


BOX_OBJ = """# a unit cube, base on y = 0 (written by make_test_models.py)
mtllib box.mtl
o box
v -0.5 0 -0.5
v 0.5 0 -0.5
v 0.5 0 0.5
v -0.5 0 0.5
v -0.5 1 -0.5
v 0.5 1 -0.5
v 0.5 1 0.5
v -0.5 1 0.5
usemtl red
f 1 2 3 4
f 5 8 7 6
f 1 5 6 2
f 2 6 7 3
f 3 7 8 4
f 4 8 5 1
"""
BOX_MTL = """newmtl red
Kd 0.8 0.1 0.1
Ns 32
"""

SCENE = {
    "name": "obj and gltf",
    "camera": {"position": [0, 5, 7], "target": [0, 0.5, 0], "fovYDeg": 50},
    "lights": [{"type": "sun", "direction": [-0.5, -1, -0.3], "size": 0.005}],
    "objects": [
        {"name": "floor", "shape": "plane", "size": [12, 12], "castsShadow": False},
        {"name": "box", "file": "../models/box.obj", "translate": [-2, 0, 0]},
        {"name": "quad", "file": "../models/alpha_quad.gltf", "translate": [2, 0.01, 0], "scale": [0.5, 0.5, 0.5]},
    ],
}


def bad_files():
    """name → bytes. Every one must be rejected with exit 1 and a message naming it."""
    out = {}
    nan = float("nan")
    out["nan_position.gltf"] = triangle_gltf([(0.0, 0.0, 0.0), (nan, 0.0, 0.0), (0.0, 1.0, 0.0)])[1]
    out["inf_position.gltf"] = triangle_gltf([(0.0, 0.0, 0.0), (float("inf"), 0.0, 0.0), (0.0, 1.0, 0.0)])[1]
    out["index_out_of_range.gltf"] = triangle_gltf(indices=(0, 1, 99))[1]
    # Triangles whose corners lie on one line draw nothing: an empty image with exit 0 once.
    out["degenerate_triangles.gltf"] = triangle_gltf([(0.0, 0.0, 0.0), (1.0, 1.0, 1.0), (2.0, 2.0, 2.0)])[1]
    out["zero_triangles.gltf"] = triangle_gltf(mutate=lambda d: d["meshes"][0]["primitives"][0].update(mode=1))[1]
    out["missing_buffer.gltf"] = triangle_gltf(mutate=lambda d: None)[1].replace(
        b'"uri": "data:application/octet-stream;base64,', b'"uri": "no_such_file.bin", "x": "')

    def cycle(d):
        d["nodes"][0]["children"] = [1]
        d["nodes"].append({"children": [0]})
    out["recursive_nodes.gltf"] = triangle_gltf(mutate=cycle)[1]

    def absurd_count(d):
        d["accessors"][0]["count"] = 4000000000
    out["absurd_count.gltf"] = triangle_gltf(mutate=absurd_count)[1]

    def view_past_end(d):  # an image decoded from a view that runs past its buffer
        d["bufferViews"].append({"buffer": 0, "byteOffset": 16, "byteLength": 1 << 30})
        d["images"] = [{"bufferView": len(d["bufferViews"]) - 1, "mimeType": "image/png"}]
    out["view_past_buffer.gltf"] = triangle_gltf(mutate=view_past_end)[1]

    def huge_image(d):  # a valid PNG header that claims 10000 x 10000 texels (400 MB decoded)
        header = mask_png()[:33]
        header = header[:16] + struct.pack(">II", 10000, 10000) + header[24:29]
        header = header[:29] + struct.pack(">I", zlib.crc32(header[12:29]) & 0xFFFFFFFF)
        d["images"] = [{"uri": "data:image/png;base64," + base64.b64encode(header + mask_png()[33:]).decode()}]
        d["textures"] = [{"source": 0}]
        d["materials"] = [{"pbrMetallicRoughness": {"baseColorTexture": {"index": 0}}}]
        d["meshes"][0]["primitives"][0]["material"] = 0  # images are decoded when a material uses them
    out["huge_image.gltf"] = triangle_gltf(mutate=huge_image)[1]

    def deep(d):
        d["extras"] = "DEEP"
    out["deep_json.gltf"] = triangle_gltf(mutate=deep)[1].replace(b'"DEEP"', b"[" * 100000 + b"]" * 100000)

    def huge_scale(d):
        d["nodes"][0]["scale"] = [1e30, 1e30, 1e30]
    out["huge_coordinates.gltf"] = triangle_gltf(mutate=huge_scale)[1]

    g, _ = triangle_gltf()  # a base-colour texture in a format Penumbra does not decode, in a buffer view
    g.doc["images"] = [{"bufferView": g.view(WEBP_HEADER), "mimeType": "image/webp"}]
    g.doc["textures"] = [{"source": 0}]
    g.doc["materials"] = [{"pbrMetallicRoughness": {"baseColorTexture": {"index": 0}}}]
    g.doc["meshes"][0]["primitives"][0]["material"] = 0
    out["webp_base_colour.gltf"] = g.finish_embedded()

    def bad_transform(d):
        d["images"] = [{"uri": "data:image/png;base64," + base64.b64encode(mask_png()).decode()}]
        d["textures"] = [{"source": 0}]
        d["materials"] = [{"pbrMetallicRoughness": {"baseColorTexture": {"index": 0, "extensions": {
            "KHR_texture_transform": {"rotation": "a quarter turn"}}}}}]
        d["meshes"][0]["primitives"][0]["material"] = 0
    out["bad_texture_transform.gltf"] = triangle_gltf(mutate=bad_transform)[1]

    def sparse(d):
        d["accessors"][0]["sparse"] = {"count": 1, "indices": {"bufferView": 1, "componentType": 5123},
                                       "values": {"bufferView": 0}}
    out["sparse_accessor.gltf"] = triangle_gltf(mutate=sparse)[1]

    def required_ext(d):
        d["extensionsUsed"] = d["extensionsRequired"] = ["EXT_mesh_gpu_instancing"]  # instances Penumbra would not place
    out["required_extension.gltf"] = triangle_gltf(mutate=required_ext)[1]

    def bad_light(d):
        d["extensions"] = {"KHR_lights_punctual": {"lights": [{"type": "directional", "extras": {"size": -1}}]}}
        d["nodes"][0]["extensions"] = {"KHR_lights_punctual": {"light": 0}}
    out["bad_light_size.gltf"] = triangle_gltf(mutate=bad_light)[1]

    # KHR_lights_punctual as scene files are checked: each was accepted (a light that lit nothing,
    # an unlimited one, a default intensity, a light lost to a default sun).
    def light(**fields):
        def mutate(d):
            d["extensions"] = {"KHR_lights_punctual": {"lights": [dict(type="point", **fields)]}}
            d["nodes"][0]["extensions"] = {"KHR_lights_punctual": {"light": 0}}
        return mutate
    out["gltf_light_range_below_size.gltf"] = triangle_gltf(mutate=light(range=0.2, extras={"size": 0.5}))[1]
    out["gltf_light_negative_range.gltf"] = triangle_gltf(mutate=light(range=-2))[1]
    out["gltf_light_intensity_text.gltf"] = triangle_gltf(mutate=light(intensity="bright"))[1]

    def light_extension_array(d):
        light()(d)
        d["nodes"][0]["extensions"]["KHR_lights_punctual"] = [{"light": 0}]
    out["gltf_light_extension_array.gltf"] = triangle_gltf(mutate=light_extension_array)[1]
    # Animation: key times are floats; a translation to 1e30 m made the triangle vanish.
    out["gltf_animation_integer_times.gltf"] = moving_triangle_gltf([0, 1], [(0, 0, 0), (1, 0, 0)], "H", 5123)
    out["gltf_animation_far.gltf"] = moving_triangle_gltf([0.0, 1.0], [(0, 0, 0), (1e30, 0, 0)])

    def stride(d):
        d["bufferViews"][0]["byteStride"] = 4
    out["stride_too_small.gltf"] = triangle_gltf(mutate=stride)[1]

    def terminal_escape(d):  # a string the message quotes: an ANSI "clear screen" and a newline
        d["materials"] = [{"alphaMode": "\u001b[2J\nOPAQUE"}]
        d["meshes"][0]["primitives"][0]["material"] = 0
    out["control_chars.gltf"] = triangle_gltf(mutate=terminal_escape)[1]

    # glTF 1.0 (named and refused) and members tinygltf requires: its own messages named no field.
    out["gltf1.gltf"] = json.dumps({"asset": {"version": "1.0"}, "meshes": {"box": {"primitives": []}},
                                    "nodes": {"root": {"meshes": ["box"]}}}, indent=1)
    out["empty_object.gltf"] = b"{}"
    out["missing_byte_length.gltf"] = triangle_gltf(mutate=lambda d: d["bufferViews"][0].pop("byteLength"))[1]
    out["primitive_without_attributes.gltf"] = triangle_gltf(mutate=lambda d: d["meshes"][0]["primitives"].append({"mode": 4}))[1]
    out["not_json.gltf"] = b'{"asset": {"version": "2.0"}, "meshes": [ {"primitives": '
    out["empty.glb"] = b""
    good_glb = triangle_glb()
    out["truncated.glb"] = good_glb[: len(good_glb) // 2]
    out["glb_version1.glb"] = glb(b'{"asset":{"version":"2.0"}}', version=1)
    out["glb_chunk_too_long.glb"] = good_glb[:12] + struct.pack("<I", 1 << 30) + good_glb[16:]

    out["index_out_of_range.obj"] = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 99\n"
    out["inf_position.obj"] = "v 0 0 0\nv 1e999 0 0\nv 0 1 0\nf 1 2 3\n"
    out["degenerate_triangles.obj"] = "v 0 0 0\nv 1 0 0\nv 2 0 0\nv 0 1 0\nf 1 2 3\nf 4 4 1\n"
    out["zero_triangles.obj"] = "v 0 0 0\nv 1 0 0\nv 0 1 0\nl 1 2\n"
    out["missing_mtl.obj"] = "mtllib no_such.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n"
    # tinyobjloader reads what it cannot parse as 0: each of these loaded silently once.
    out["nan_position.obj"] = "v nan 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n"
    out["letters_position.obj"] = "v 0 0 0\nv 1 zero 0\nv 0 1 0\nf 1 2 3\n"
    out["huge_index.obj"] = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 99999999999999999999\n"
    # tinyobjloader converts a skin weight's joint id (its own `vw` extension) to int unchecked:
    # undefined behaviour found by fuzzing. Penumbra reads no `vw`; the face is out of range.
    out["skin_weight_overflow.obj"] = "v 0 0 0\nv 1 0 0\nv 0 1 0\nvw 0 1e40 0.5\nf 1 2 4\n"
    out["nan_kd.obj"] = "mtllib nan_kd.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl black\nf 1 2 3\n"
    out["nan_kd.mtl"] = "newmtl black\nKd nan 0.5 0.5\n"

    base = {"lights": [{"type": "sun"}], "objects": [{"shape": "plane"}]}
    def scene(obj):
        s = json.loads(json.dumps(base))
        s["objects"].append(obj)
        return json.dumps(s, indent=1)
    out["scene_missing_model.json"] = scene({"file": "no_such_model.glb"})
    out["scene_bad_model.json"] = scene({"file": "index_out_of_range.gltf", "translate": [1, 0, 0]})
    out["scene_model_with_shape.json"] = scene({"file": "../models/box.obj", "shape": "box"})
    out["scene_model_not_a_model.json"] = scene({"file": "scene_missing_model.json"})
    out["scene_number_overflow.json"] = scene({"shape": "box", "translate": [0, 0, 0]}).replace("[\n    0,", "[\n    1e999,", 1)
    out["scene_huge_translate.json"] = scene({"shape": "box", "translate": [1e20, 0, 0]})

    def with_top(**fields):
        s = json.loads(json.dumps(base))
        s.update(fields)
        return json.dumps(s, indent=1)
    # Each of these rendered an empty, black or garbage image with exit 0, or exited 2 without
    # naming the file.
    out["scene_camera_down.json"] = with_top(camera={"position": [0, 10, 0], "target": [0, 0, 0]})
    out["scene_camera_zero_up.json"] = with_top(camera={"position": [0, 2, 5], "up": [0, 0, 0]})
    out["scene_camera_up_along_view.json"] = with_top(camera={"position": [0, 0, 5], "up": [0, 0, -2]})
    out["scene_light_color_huge.json"] = with_top(lights=[{"type": "sun", "color": [1e38, 1, 1]}])
    out["scene_light_color_negative.json"] = with_top(lights=[{"type": "sun", "color": [1, -0.5, 1]}])
    out["scene_ambient_huge.json"] = with_top(ambient=[1e38, 0, 0])
    out["scene_bad_filter.json"] = with_top(shadow={"filter": "blurry"})
    out["scene_bad_param.json"] = with_top(shadow={"params": {"hard.nothing": 1}})
    out["scene_param_out_of_range.json"] = with_top(shadow={"params": {"hard.slopeBias": 99}})
    # Light entries: each names its field (tests/unit/SceneFileTest.cpp tests every check).
    out["scene_light_unknown_type.json"] = with_top(lights=[{"type": "area"}])
    out["scene_light_inner_above_outer.json"] = with_top(lights=[
        {"type": "spot", "position": [0, 3, 0], "target": [0, 0, 0], "innerConeDeg": 40, "outerConeDeg": 30}])
    out["scene_light_range_below_size.json"] = with_top(lights=[{"type": "point", "position": [0, 3, 0], "size": 0.5, "range": 0.2}])
    out["scene_binary.json"] = mask_png()  # not JSON: the message must not echo its bytes
    # Animation within the still pose's bounds: a camera keyed to look straight down its up
    # vector, a box scaled past ±1e6 m (each rendered empty frames with exit 0).
    out["scene_camera_animated_down.json"] = with_top(camera={
        "position": [0, 2, 5], "target": [0, 0, 0],
        "animation": {"keys": [{"timeS": 0, "position": [0, 2, 5]}, {"timeS": 1, "position": [0, 9, 0]}]}})
    out["scene_animated_scale_huge.json"] = scene({"shape": "box", "size": [1000, 1000, 1000], "animation": {
        "keys": [{"timeS": 0, "scale": [1, 1, 1]}, {"timeS": 2, "scale": [1e5, 1, 1]}]}})
    out["scene_sun_translate_keys.json"] = with_top(lights=[{"type": "sun", "animation": {
        "keys": [{"timeS": 0, "translate": [0, 0, 0]}, {"timeS": 1, "translate": [5, 0, 0]}]}}])
    out["scene_spot_target_and_direction.json"] = with_top(lights=[
        {"type": "spot", "position": [0, 3, 0], "target": [0, 0, 0], "direction": [1, -1, 0]}])

    return out


def main():
    write("models/alpha_quad.gltf", alpha_quad_gltf())
    write("models/textured_quads.gltf", textured_quads_gltf())
    write("models/quantized_box.gltf", quantized_box_gltf())
    write("models/box.obj", BOX_OBJ)
    write("models/box.mtl", BOX_MTL)
    write("models/lamps.gltf", lamps_gltf())
    write("scenes/obj_and_gltf.json", json.dumps(SCENE, indent=1) + "\n")
    for name, data in bad_files().items():
        write("bad/" + name, data)
    # Fuzz seeds: small valid files of each kind plus a few of the bad ones.
    write("fuzz/gltf/triangle.gltf", triangle_gltf()[1])
    write("fuzz/gltf/triangle.glb", triangle_glb())
    write("fuzz/gltf/strip.gltf", triangle_gltf(indices=(0, 1, 2, 1), mutate=lambda d: d["meshes"][0]["primitives"][0].update(mode=5))[1])
    write("fuzz/gltf/alpha_quad.gltf", alpha_quad_gltf())
    write("fuzz/gltf/textured_quads.gltf", textured_quads_gltf())  # the JPEG decoder and KHR_texture_transform
    write("fuzz/gltf/quantized_box.gltf", quantized_box_gltf())
    write("fuzz/gltf/lamps.gltf", lamps_gltf())  # KHR_lights_punctual point and spot lights
    write("fuzz/gltf/recursive_nodes.gltf", bad_files()["recursive_nodes.gltf"])
    write("fuzz/obj/box.obj", BOX_OBJ)
    write("fuzz/obj/box.mtl", BOX_MTL)
    write("fuzz/obj/quad_with_uv_and_normals.obj",  # vt, vn, negative indices, a polygon, o/g, usemtl
          "# seed\nmtllib box.mtl\no quad\nv -1 0 -1\nv 1 0 -1\nv 1 0 1\nv -1 0 1\nvt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n"
          "vn 0 1 0\ng top\nusemtl red\nf -4/1/1 -3/2/1 -2/3/1 -1/4/1\nf 1//1 3//1 2//1\n")
    write("fuzz/scene/obj_and_gltf.json", json.dumps(SCENE).replace("../models/", "models/"))
    write("fuzz/scene/number_overflow.json", bad_files()["scene_number_overflow.json"])  # found by fuzzing
    write("fuzz/scene/shapes.json", json.dumps({
        "camera": {"position": [0, 2, 5]}, "lights": [{"type": "spot", "position": [0, 4, 0], "target": [0, 0, 0], "size": 0.1}],
        "objects": [{"shape": "box", "size": [1, 2, 1], "rotateDeg": [0, 30, 0]}, {"shape": "sphere", "radius": 0.5}],
        "shadow": {"filter": "hard", "mapSize": 512, "params": {"hard.bias": "slope"}}}))
    write("fuzz/scene/lamps.json", json.dumps({  # every light key: point, spot cones, ranges, per-light overrides
        "lights": [{"type": "point", "position": [0, 2, 0], "size": 0.05, "range": 6, "color": [1, 0.8, 0.6], "intensity": 3,
                    "shadow": {"mapSize": 256, "params": {"pcf.radiusTexels": 2}}},
                   {"type": "spot", "position": [2, 3, 0], "target": [0, 0, 0], "innerConeDeg": 20, "outerConeDeg": 35,
                    "size": 0.04, "range": 8, "castsShadow": False},
                   {"type": "sun", "direction": [0.2, -1, 0.1], "size": 0.01, "intensity": 0.2}],
        "objects": [{"shape": "plane", "size": [8, 8]}, {"shape": "box", "size": [1, 0.05, 1], "translate": [0, 0.75, 0]}],
        "shadow": {"filter": "pcf"}}))


if __name__ == "__main__":
    main()
