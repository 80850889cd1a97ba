#!/usr/bin/env python3
"""Do two LAS files hold the same points? (tools/bench/slurm_e2e.sh: a merged SLURM run against `sacfuse run`.)

Usage: las_same_points.py A.las B.las

Same when: the same point format, record length, scale and offset, the same point count in the header, and the
same multiset of raw point records (order may differ: tiles can be merged in another order). Also says whether
the files are byte-identical apart from the header's creation date (bytes 90-93). Exit 0 same, 1 different.
"""
import collections
import struct
import sys


def read_las(path):
    with open(path, "rb") as f:
        data = f.read()
    if data[:4] != b"LASF":
        raise SystemExit(f"{path}: not a LAS file")
    major, minor = data[24], data[25]
    offset_to_points = struct.unpack_from("<I", data, 96)[0]
    point_format = data[104] & 0x3F  # bits 6-7 flag compression
    record_len = struct.unpack_from("<H", data, 105)[0]
    count = struct.unpack_from("<I", data, 107)[0]
    if (major, minor) >= (1, 4):
        count = max(count, struct.unpack_from("<Q", data, 247)[0])
    scale_offset = struct.unpack_from("<6d", data, 131)
    end = offset_to_points + count * record_len
    if end > len(data):
        raise SystemExit(f"{path}: {count} points of {record_len} B do not fit in {len(data)} B")
    records = collections.Counter(data[i:i + record_len] for i in range(offset_to_points, end, record_len))
    return {"path": path, "bytes": data, "version": f"{major}.{minor}", "format": point_format,
            "record_len": record_len, "count": count, "scale_offset": scale_offset, "records": records}


def main():
    if len(sys.argv) != 3:
        print(__doc__, file=sys.stderr)
        return 2
    a, b = read_las(sys.argv[1]), read_las(sys.argv[2])
    problems = []
    for key in ("version", "format", "record_len", "scale_offset", "count"):
        if a[key] != b[key]:
            problems.append(f"{key}: {a[key]} vs {b[key]}")
    only_a = a["records"] - b["records"]
    only_b = b["records"] - a["records"]
    if only_a or only_b:
        problems.append(f"point records: {sum(only_a.values())} only in A, {sum(only_b.values())} only in B")
    same_bytes = (len(a["bytes"]) == len(b["bytes"]) and a["bytes"][:90] == b["bytes"][:90]
                  and a["bytes"][94:] == b["bytes"][94:])
    print(f"A: {a['path']}: {a['count']} points (LAS {a['version']}, format {a['format']}, {len(a['bytes'])} B)")
    print(f"B: {b['path']}: {b['count']} points (LAS {b['version']}, format {b['format']}, {len(b['bytes'])} B)")
    print(f"distinct records A {len(a['records'])}, B {len(b['records'])}; "
          f"byte-identical apart from the creation date: {'yes' if same_bytes else 'no'}")
    if problems:
        print("different: " + "; ".join(problems))
        return 1
    print(f"same points: {a['count']} point records, equal as a multiset")
    return 0


if __name__ == "__main__":
    sys.exit(main())
