#!/usr/bin/env python3
"""Writes the fuzz targets' seed inputs: tiny valid files of every format, in
the variants their readers tell apart (types, byte orders, encodings, vectors).
Usage: make_corpus.py OUT_DIR  (makes OUT_DIR/<reader>/...)."""

import bz2
import gzip
import os
import struct
import sys
import zlib

out = sys.argv[1]


def put(reader, name, data):
    os.makedirs(os.path.join(out, reader), exist_ok=True)
    with open(os.path.join(out, reader, name), "wb") as f:
        f.write(data if isinstance(data, bytes) else data.encode())


# A 2 x 2 x 2 volume: labels 0/1 split along x; distances for two phases.
labels = [0, 1] * 4
dists = [v for x in range(8) for v in ((-0.5, 0.5) if x % 2 else (0.5, -0.5))]


def raw(fmt, values, big=False):
    return struct.pack(("<>"[big]) + fmt * len(values), *values)


def files(first, *named):
    """A multi-file input (fuzz/input_layouts.hpp, split_files): the first file, then each
    (name, bytes) after a "\n--- NAME\n" line."""
    data = first.encode() if isinstance(first, str) else first
    for name, body in named:
        data += b"\n--- " + name.encode() + b"\n" + (body.encode() if isinstance(body, str) else body)
    return data


# ---- scene JSON
put("scene", "spheres.json", """{"domain": {"min": [0, 0, 0], "max": [1, 1, 1]}, "grid": [8, 8, 9],
 "phases": [{"name": "out", "kind": "constant", "value": 0},
            {"kind": "sphere", "center": [0.5, 0.5, 0.5], "radius": 0.3}]}""")
put("scene", "expr.json", """{"description": "d", "domain": {"min": [-1, -1, -1], "max": [1, 1, 1]}, "grid": 8,
 "phases": [{"name": "a", "kind": "expr", "constants": {"r": 0.5}, "expr": "r - sqrt(x^2 + y^2 + z^2)"},
            {"name": "b", "kind": "expr", "expr": "-(cos(x)*sin(y))^3"}]}""")
put("scene", "grid_phase.json", """{"phases": [{"kind": "grid", "file": "input.nrrd", "component": 0},
 {"kind": "grid", "file": "input.nrrd", "component": 1}]}""")
# Deep nesting (issue 16: a 50,000-deep value crashed a message's dump): arrays and
# objects deeper than the 64 levels a scene may nest, where a description, a value
# and a name go, and a key given twice; each well within the 4 KiB inputs.
deep_array = "[" * 1000 + "]" * 1000
deep_object = '{"a": ' * 300 + "0" + "}" * 300
put("scene", "deep_description.json", '{"description": ' + deep_array + ', "phases": []}')
put("scene", "deep_value.json", '{"phases": [{"kind": "constant", "value": ' + deep_object +
    '}, {"kind": "constant", "value": 1}]}')
put("scene", "deep_name.json", '{"phases": [{"kind": "constant", "value": 0, "name": ' + "[" * 64 + "]" * 64 +
    '}, {"kind": "constant", "value": 1}]}')
put("scene", "duplicate_key.json", '{"phases": [{"kind": "constant", "value": 0, "value": 1}, '
    '{"kind": "constant", "value": 1}]}')

# ---- NRRD (attached header; Teem also reads gzip and ascii encodings)
head = "NRRD0004\ntype: {t}\ndimension: {d}\nsizes: {s}\nencoding: {e}\n{x}\n"
put("nrrd", "uchar.nrrd", head.format(t="uchar", d=3, s="2 2 2", e="raw", x="").encode() + bytes(labels))
put("nrrd", "short_be_space.nrrd",
    head.format(t="short", d=3, s="2 2 2", e="raw", x="endian: big\nspace: right-anterior-superior\n"
                "space directions: (1,0,0) (0,2,0) (0,0,0.5)\nspace origin: (1,2,3)\n").encode() + raw("h", labels, True))
put("nrrd", "float_vector.nrrd",
    head.format(t="float", d=4, s="2 2 2 2", e="raw", x="endian: little\nkinds: vector domain domain domain\n"
                "spacings: nan 1 1 1\n").encode() + raw("f", dists))
put("nrrd", "double_gzip.nrrd",
    head.format(t="double", d=3, s="2 2 2", e="gzip", x="endian: little\n").encode()
    + gzip.compress(raw("d", dists[::2])))
put("nrrd", "int_ascii.nrrd", head.format(t="int", d=3, s="2 2 2", e="ascii", x="") + " ".join(map(str, labels)))
put("nrrd", "ushort_bzip2.nrrd",
    head.format(t="ushort", d=3, s="2 2 2", e="bzip2", x="endian: little\n").encode() + bz2.compress(raw("H", labels)))

# ---- NRRD with the data compressed by the target (fuzz_nrrd_compressed), as its encoding says
put("nrrd_compressed", "uchar_gzip.nrrd", head.format(t="uchar", d=3, s="2 2 2", e="gzip", x="").encode() + bytes(labels))
put("nrrd_compressed", "float_vector_bzip2.nrrd",
    head.format(t="float", d=4, s="2 2 2 2", e="bzip2", x="endian: little\nkinds: vector domain domain domain\n"
                "byte skip: 4\n").encode() + bytes(4) + raw("f", dists))
put("nrrd_compressed", "short_be_gz.nrrd",
    head.format(t="short", d=3, s="2 2 2", e="gz", x="endian: big\n").encode() + raw("h", labels, True))

# ---- detached NRRD headers and their data files (fuzz_nrrd_detached): one name, LIST, pattern, SKIPLIST
detached = "NRRD0004\ntype: {t}\ndimension: 3\nsizes: 2 2 2\nencoding: {e}\n{x}data file: {f}\n"
put("nrrd_detached", "one_raw.nhdr", files(detached.format(t="uchar", e="raw", x="", f="d.raw"), ("d.raw", bytes(labels))))
put("nrrd_detached", "list_slices.nhdr",
    files(detached.format(t="short", e="raw", x="endian: big\n", f="LIST 2") + "s0.raw\ns1.raw\n",
          ("s0.raw", raw("h", labels[:4], True)), ("s1.raw", raw("h", labels[4:], True))))
put("nrrd_detached", "pattern_slices.nhdr",
    files(detached.format(t="uchar", e="raw", x="", f="s%03d.raw 0 1 1"),
          ("s000.raw", bytes(labels[:4])), ("s001.raw", bytes(labels[4:]))))
put("nrrd_detached", "pattern_down_gzip.nhdr",
    files(detached.format(t="double", e="gzip", x="endian: little\n", f="z%d.gz 1 0 -1 2"),
          ("z1.gz", gzip.compress(raw("d", dists[:8:2]))), ("z0.gz", gzip.compress(raw("d", dists[8::2])))))
put("nrrd_detached", "one_bzip2_skips.nhdr",
    files(detached.format(t="int", e="bzip2", x="endian: little\nline skip: 1\nbyte skip: 2\n", f="d.bz2"),
          ("d.bz2", b"text\n" + bz2.compress(bytes(2) + raw("i", labels)))))
put("nrrd_detached", "skiplist.nhdr",
    files("NRRD0006\ntype: uchar\ndimension: 3\nsizes: 2 2 2\nencoding: raw\ndata file: SKIPLIST 2\n"
          "3 a.raw\n0 b.raw\n", ("a.raw", b"abc" + bytes(labels[:4])), ("b.raw", bytes(labels[4:]))))
put("nrrd_detached", "ascii_list.nhdr",
    files(detached.format(t="float", e="ascii", x="", f="LIST") + "a.txt\nb.txt\n",
          ("a.txt", "0.5 -0.5 0.5 -0.5"), ("b.txt", "-1 1 -1 1")))


# ---- NIfTI-1 (.nii, data at vox_offset 352)
def nifti(datatype, bitpix, fmt, values, dims=(3, 2, 2, 2, 1, 1, 1, 1), sform=0, qform=0, slope=0.0):
    h = struct.pack("<i", 348) + bytes(36)                      # sizeof_hdr .. regular, dim_info
    h += struct.pack("<8h", *dims)                               # dim
    h += struct.pack("<3f", 0, 0, 0)                             # intent_p1..3
    h += struct.pack("<hhhh", 0, datatype, bitpix, 0)            # intent_code datatype bitpix slice_start
    h += struct.pack("<8f", 1, 1, 2, 0.5, 1, 1, 1, 1)            # pixdim (qfac first)
    h += struct.pack("<ff", 352, slope) + struct.pack("<f", 0)   # vox_offset scl_slope scl_inter
    h += struct.pack("<hbb", 0, 0, 10)                           # slice_end slice_code xyzt_units
    h += struct.pack("<ffffii", 0, 0, 0, 0, 0, 0)                # cal_max cal_min slice_duration toffset glmax glmin
    h += bytes(80 + 24)                                          # descrip aux_file
    h += struct.pack("<hh", qform, sform)
    h += struct.pack("<6f", 0, 0, 0, 1, 2, 3)                    # quatern_b..d qoffset_x..z
    h += struct.pack("<12f", 1, 0, 0, 5, 0, 2, 0, 6, 0, 0, 0.5, 7)  # srow_x/y/z
    h += bytes(16) + b"n+1\0"                                    # intent_name magic
    assert len(h) == 348
    return h + bytes(4) + raw(fmt, values)


put("nifti", "uint8.nii", nifti(2, 8, "B", labels))
put("nifti", "int16_sform.nii", nifti(4, 16, "h", labels, sform=1))
put("nifti", "float_vector_qform.nii", nifti(16, 32, "f", dists, dims=(5, 2, 2, 2, 1, 2, 1, 1), qform=1))
put("nifti", "double_scaled.nii", nifti(64, 64, "d", dists[::2], slope=2.0))
# .nii.gz: the gzip stream fuzzed as it is (fuzz_nifti_gz), or made by the target (fuzz_nifti_gzipped)
for name, data in [("uint8", nifti(2, 8, "B", labels)), ("float_vector_qform", nifti(16, 32, "f", dists, dims=(5, 2, 2, 2, 1, 2, 1, 1), qform=1)),
                   ("int16_sform", nifti(4, 16, "h", labels, sform=1))]:
    put("nifti_gz", name + ".nii.gz", gzip.compress(data))
    put("nifti_gzipped", name + ".nii", data)

# ---- MetaImage (.mha, data after ElementDataFile = LOCAL)
mha = ("ObjectType = Image\nNDims = {n}\nDimSize = {s}\n{x}ElementType = {t}\nElementDataFile = LOCAL\n")
put("metaimage", "uchar.mha", mha.format(n=3, s="2 2 2", x="", t="MET_UCHAR").encode() + bytes(labels))
put("metaimage", "short_msb_geometry.mha",
    mha.format(n=3, s="2 2 2", t="MET_SHORT", x="BinaryData = True\nBinaryDataByteOrderMSB = True\n"
               "ElementSpacing = 1 2 0.5\nOffset = 1 2 3\nTransformMatrix = 1 0 0 0 1 0 0 0 1\n").encode()
    + raw("h", labels, True))
put("metaimage", "float_channels_2d.mha",
    mha.format(n=2, s="2 4", t="MET_FLOAT", x="ElementNumberOfChannels = 2\nElementSize = 1 1\n").encode()
    + raw("f", dists))
compressed = zlib.compress(raw("d", dists[::2]))
put("metaimage", "double_compressed.mha",
    mha.format(n=3, s="2 2 2", t="MET_DOUBLE",
               x="CompressedData = True\nCompressedDataSize = %d\n" % len(compressed)).encode() + compressed)

# ---- MetaImage .mhd with the data in files of their own (fuzz_metaimage_detached)
mhd = "ObjectType = Image\nNDims = 3\nDimSize = 2 2 2\n{x}ElementType = {t}\nElementDataFile = {f}\n"
put("metaimage_detached", "uchar.mhd", files(mhd.format(x="", t="MET_UCHAR", f="d.raw"), ("d.raw", bytes(labels))))
put("metaimage_detached", "short_msb_headersize.mhd",
    files(mhd.format(x="BinaryDataByteOrderMSB = True\nHeaderSize = 3\n", t="MET_SHORT", f="d.raw"),
          ("d.raw", b"abc" + raw("h", labels, True))))
put("metaimage_detached", "float_end_of_file.mhd",
    files(mhd.format(x="HeaderSize = -1\n", t="MET_FLOAT", f="d.raw"), ("d.raw", b"header" + raw("f", dists[::2]))))
put("metaimage_detached", "double_compressed.mhd",
    files(mhd.format(x="CompressedData = True\n", t="MET_DOUBLE", f="d.zraw"), ("d.zraw", zlib.compress(raw("d", dists[::2])))))
put("metaimage_detached", "list.mhd",
    files(mhd.format(x="", t="MET_UCHAR", f="LIST 2D") + "s0.raw\ns1.raw\n", ("s0.raw", bytes(labels[:4])), ("s1.raw", bytes(labels[4:]))))

# ---- INR (256-byte header blocks; zlib's gzread reads gzip too)
def inr(fields, data, dims="XDIM=2\nYDIM=2\nZDIM=2\n"):
    h = "#INRIMAGE-4#{\n" + dims + fields
    h += "\n" * (256 - (len(h) + 4) % 256) + "##}\n"
    return h.encode() + data


put("inr", "uchar.inr", inr("VDIM=1\nTYPE=unsigned fixed\nPIXSIZE=8 bits\nSCALE=2**0\nCPU=decm\nVX=0.5\nTX=1\n",
                            bytes(labels)))
put("inr", "short_sun.inr", inr("TYPE=signed fixed\nPIXSIZE=16 bits\nCPU=sun\n", raw("h", labels, True)))
put("inr", "float_vectors.inr.gz", gzip.compress(
    inr("VDIM=2\nTYPE=float\nPIXSIZE=32 bits\nCPU=pc\nVX=2\nVY=2\nVZ=3\n", raw("f", dists))))

# ---- TIFF stacks: two pages of 2 x 2 (one strip each), classic little- and big-endian
#      with ImageJ's description and resolution, and a BigTIFF of floats


def tiff(fmt, values, big=False, imagej=False, bigtiff=False):
    """A 2-page TIFF of 2 x 2 samples packed with struct format `fmt` (B, h, f...)."""
    e = "<>"[big]
    sample = struct.calcsize(fmt)
    bits = 8 * sample
    kind = 3 if fmt in "fd" else 2 if fmt in "bhi" else 1
    description = b"ImageJ=1.54f\nimages=2\nslices=2\nspacing=2\n\0" if imagej else b""
    head = 16 if bigtiff else 8
    entry, count, offset = ("HHQQ", "Q", "Q") if bigtiff else ("HHII", "H", "I")
    pages = [raw(fmt, values[4 * k:4 * k + 4], big) for k in range(2)]
    data = b"".join(pages) + description + (struct.pack(e + "II", 1, 2) * 2 if imagej else b"")
    place = head  # pixels first, then the extras, then the directories
    strips = [place, place + len(pages[0])]
    text_at = place + len(pages[0]) * 2
    resolution_at = text_at + len(description)
    directories = b""
    first_directory = head + len(data)
    for k in range(2):
        tags = [(256, 3, 1, 2), (257, 3, 1, 2), (258, 3, 1, bits), (259, 3, 1, 1), (262, 3, 1, 1),
                (273, 4, 1, strips[k]), (277, 3, 1, 1), (278, 3, 1, 2), (279, 4, 1, len(pages[k])),
                (339, 3, 1, kind)]
        if imagej and k == 0:
            tags += [(270, 2, len(description), text_at), (282, 5, 1, resolution_at),
                     (283, 5, 1, resolution_at + 8), (296, 3, 1, 1)]
        tags.sort()
        size = struct.calcsize(e + count) + len(tags) * struct.calcsize(e + entry) + struct.calcsize(e + offset)
        next_directory = first_directory + len(directories) + size if k == 0 else 0
        body = struct.pack(e + count, len(tags))
        for tag, type_, n, value in tags:
            # A SHORT value sits in the entry's first bytes, in the file's byte order.
            if type_ == 3 and n == 1:
                pad = struct.calcsize(e + offset) - 2
                body += struct.pack(e + "HH", tag, type_) + struct.pack(e + offset, n) + \
                    struct.pack(e + "H", value) + b"\0" * pad
            else:
                body += struct.pack(e + entry, tag, type_, n, value)
        directories += body + struct.pack(e + offset, next_directory)
    magic = (b"MM" if big else b"II") + struct.pack(e + "H", 43 if bigtiff else 42)
    magic += struct.pack(e + "HHQ", 8, 0, first_directory) if bigtiff else struct.pack(e + "I", first_directory)
    return magic + data + directories


put("tiff", "uchar.tif", tiff("B", labels))
put("tiff", "short_big_imagej.tif", tiff("h", labels, big=True, imagej=True))
put("tiff", "float_bigtiff.tif", tiff("f", [float(v) for v in labels], bigtiff=True))

# ---- text points ("x y z label"; .csv may have a header row)
put("points", "header.csv", "x,y,z,label\n0,0,0,1\n1,0,0,2\n0,1,0.5,1\n# comment\n1,1,1,2\n")
put("points", "spaces.csv", "0 0 0 3\n1e-3 2 -1.5 7\n\n0.5 0.5 0.5 3 # near\n")

# ---- PLY labelled points
ply_points = "ply\nformat {f} 1.0\nelement vertex 3\nproperty {c} x\nproperty {c} y\nproperty {c} z\nproperty {l} label\n{x}end_header\n"
pts = [(0, 0, 0, 1), (1, 0, 0, 2), (0, 1, 1, 1)]
put("ply_points", "ascii.ply", ply_points.format(f="ascii", c="float", l="int", x="") +
    "".join("%g %g %g %d\n" % p for p in pts))
put("ply_points", "binary_be_extra.ply",
    ply_points.format(f="binary_big_endian", c="double", l="ushort", x="property uchar red\n").encode()
    + b"".join(struct.pack(">dddHB", *p, 9) for p in pts))

# ---- PLY interface mesh (as write_ply writes it: a tetrahedron between phases 1 and 2)
verts = [(0, 0, 0), (1, 0, 0), (0, 1, 0), (0, 0, 1)]
faces = [(0, 2, 1), (0, 1, 3), (0, 3, 2), (1, 2, 3)]
mesh = ("ply\nformat {f} 1.0\ncomment phase 1 inside\ncomment phase 2 outside\nelement vertex 4\n"
        "property {c} x\nproperty {c} y\nproperty {c} z\nelement face 4\n"
        "property list uchar {i} vertex_indices\nproperty int phase0\nproperty int phase1\nend_header\n")
put("ply_mesh", "ascii.ply", mesh.format(f="ascii", c="double", i="int") +
    "".join("%g %g %g\n" % v for v in verts) + "".join("3 %d %d %d 1 2\n" % f for f in faces))
put("ply_mesh", "binary_le.ply", mesh.format(f="binary_little_endian", c="double", i="int").encode() +
    b"".join(struct.pack("<3d", *v) for v in verts) + b"".join(struct.pack("<B3i2i", 3, *f, 1, 2) for f in faces))
put("ply_mesh", "binary_be_float_ushort.ply", mesh.format(f="binary_big_endian", c="float", i="ushort").encode() +
    b"".join(struct.pack(">3f", *v) for v in verts) + b"".join(struct.pack(">B3H2i", 3, *f, 1, 2) for f in faces))
