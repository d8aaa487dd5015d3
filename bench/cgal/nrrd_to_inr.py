#!/usr/bin/env python3
"""Converts a raw NRRD label volume to INR, the format CGAL::Image_3 reads.

    nrrd_to_inr.py IN.nrrd OUT.inr

For bench/race.sh: CGAL 5.5's ImageIO reads INR (and a few others) but not
NRRD, so the same voxels are handed to CGAL as INR. Only what
bench/make_label_volume writes is handled (attached raw data, integer types,
little endian, axis-aligned spacings, no origin), and anything else is refused
rather than guessed: the voxels are copied byte for byte, so both tools mesh
exactly the same volume in the same coordinates (voxel (i, j, k) at
(i, j, k) * spacing in both).
"""
import sys

# NRRD type -> (INR TYPE, bits)
TYPES = {
    "uchar": ("unsigned fixed", 8), "unsigned char": ("unsigned fixed", 8), "uint8": ("unsigned fixed", 8),
    "char": ("signed fixed", 8), "signed char": ("signed fixed", 8), "int8": ("signed fixed", 8),
    "ushort": ("unsigned fixed", 16), "unsigned short": ("unsigned fixed", 16), "uint16": ("unsigned fixed", 16),
    "short": ("signed fixed", 16), "int16": ("signed fixed", 16),
    "uint": ("unsigned fixed", 32), "unsigned int": ("unsigned fixed", 32), "uint32": ("unsigned fixed", 32),
    "int": ("signed fixed", 32), "int32": ("signed fixed", 32),
}


def fail(why):
    sys.exit(f"nrrd_to_inr: {why}")


def main():
    if len(sys.argv) != 3:
        fail("usage: nrrd_to_inr.py IN.nrrd OUT.inr")
    data = open(sys.argv[1], "rb").read()
    end = data.find(b"\n\n")
    if not data.startswith(b"NRRD") or end < 0:
        fail("not a NRRD file with attached data")
    fields = {}
    for line in data[:end].decode("ascii").splitlines()[1:]:
        if line.startswith("#") or ":" not in line:
            continue
        key, value = line.split(":", 1)
        fields[key.strip()] = value.strip().lstrip("=").strip()
    if fields.get("dimension") != "3":
        fail("need a 3-D volume")
    if fields.get("encoding") != "raw":
        fail(f"encoding {fields.get('encoding')} is not supported (raw only)")
    if fields.get("type") not in TYPES:
        fail(f"type {fields.get('type')} is not supported")
    inr_type, bits = TYPES[fields["type"]]
    if bits > 8 and fields.get("endian") != "little":
        fail("need little-endian data")
    for key in ("space origin", "space directions", "data file", "datafile", "byte skip", "line skip"):
        if key in fields:
            fail(f"'{key}' is not supported")
    sizes = [int(s) for s in fields["sizes"].split()]
    spacing = [float(s) for s in fields.get("spacings", "1 1 1").split()]
    voxels = data[end + 2:]
    if len(voxels) != sizes[0] * sizes[1] * sizes[2] * bits // 8:
        fail(f"{len(voxels)} bytes of data, expected {sizes[0] * sizes[1] * sizes[2] * bits // 8}")
    header = (f"#INRIMAGE-4#{{\nXDIM={sizes[0]}\nYDIM={sizes[1]}\nZDIM={sizes[2]}\nVDIM=1\n"
              f"TYPE={inr_type}\nPIXSIZE={bits} bits\nSCALE=2**0\nCPU=decm\n"
              f"VX={spacing[0]!r}\nVY={spacing[1]!r}\nVZ={spacing[2]!r}\n")
    # The header is padded with newlines to a multiple of 256 bytes, "##}\n" last.
    pad = -(len(header) + 4) % 256
    header += "\n" * pad + "##}\n"
    with open(sys.argv[2], "wb") as out:
        out.write(header.encode("ascii"))
        out.write(voxels)


if __name__ == "__main__":
    main()
