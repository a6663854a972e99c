"""Read certipose's binary box store (boxes.cpbx) with numpy alone.

The format (docs/part.md#the-binary-box-store-boxescpbx, include/certipose/io/box_store.hpp): a 32-byte
little-endian header -- magic b"CPBOXES\\0", version (1), header bytes (32), record bytes (104),
flags (bit 0: occlusion was checked), the number of records (u64) -- then one 104-byte record per box.

    import box_store                      # scripts/ on sys.path, or copy this file
    boxes, occlusion_checked = box_store.read("run/boxes.cpbx")
    valid = boxes[boxes["cls"] == box_store.VALID]
    boxes["position"]                     # (N, 3, 2): [x, y, z] x [lower, upper], metres
    boxes["orientation"]                  # (N, 3, 2): [phi, gamma, beta] x [lower, upper], radians

The file is memory-mapped: reading 10^8 boxes costs nothing until they are used.
"""
import numpy as np

MAGIC = b"CPBOXES\0"
VERSION = 1
HEADER_BYTES = 32
RECORD_BYTES = 104
VALID, BOUNDARY = 0, 1
NO_REASON = 255

RECORD = np.dtype([("facet", "<u4"), ("cls", "u1"), ("reason", "u1"), ("pad", "<u2"),
                   ("position", "<f8", (3, 2)), ("orientation", "<f8", (3, 2))])
assert RECORD.itemsize == RECORD_BYTES


class BoxStoreError(ValueError):
    """A file that is not a version-1 certipose box store, or a damaged one."""


def read(path):
    """(records, occlusion_checked): the boxes as a read-only structured array (dtype RECORD)."""
    with open(path, "rb") as f:
        header = f.read(HEADER_BYTES)
    if len(header) < HEADER_BYTES:
        raise BoxStoreError(f"{path}: shorter than its 32-byte header")
    if header[:8] != MAGIC:
        raise BoxStoreError(f"{path}: not a certipose box store (no CPBOXES magic)")
    version, header_bytes, record_bytes, flags = np.frombuffer(header, "<u4", 4, 8)
    if version != VERSION:
        raise BoxStoreError(f"{path}: version {version}, this reader knows version {VERSION}")
    if header_bytes != HEADER_BYTES or record_bytes != RECORD_BYTES:
        raise BoxStoreError(f"{path}: header of {header_bytes} bytes and records of {record_bytes}; "
                            f"version 1 has {HEADER_BYTES} and {RECORD_BYTES}")
    size = np.memmap(path, dtype="u1", mode="r").size
    if (size - HEADER_BYTES) % RECORD_BYTES:
        raise BoxStoreError(f"{path}: truncated (its last record has "
                            f"{(size - HEADER_BYTES) % RECORD_BYTES} of {RECORD_BYTES} bytes)")
    count = (size - HEADER_BYTES) // RECORD_BYTES
    recorded = int(np.frombuffer(header, "<u8", 1, 24)[0])
    if recorded and recorded != count:
        raise BoxStoreError(f"{path}: truncated: {count} of the {recorded} records its header counts")
    records = (np.memmap(path, dtype=RECORD, mode="r", offset=HEADER_BYTES, shape=(count,))
               if count else np.zeros(0, RECORD))
    return records, bool(flags & 1)
