"""boxes.cpbx read with numpy alone (scripts/box_store.py) holds exactly the boxes of
boxes.jsonl, bit for bit, in the same order; damaged stores are refused with a message."""
import json
import os
import pathlib
import shutil
import subprocess
import sys

import numpy as np
import pytest

ROOT = pathlib.Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "scripts"))
import box_store  # noqa: E402

PART = os.environ.get("CERTIPOSE_PART", "certipose-part")
MESH = os.environ.get("CERTIPOSE_SAMPLE_PART", str(ROOT / "build" / "sample_part.off"))
CAMERA = str(ROOT / "examples" / "data" / "camera.json")


@pytest.fixture(scope="module")
def run(tmp_path_factory):
    out = tmp_path_factory.mktemp("run") / "part"
    subprocess.run([PART, "--mesh", MESH, "--camera", CAMERA, "--position-eps", "0.4", "--orientation-eps", "0.38",
                    "--facets", "0-5,700", "--boundary", "--threads", "2", "--box-store", "both", "--out", str(out), "-q"], check=True)
    return out


def test_same_boxes_as_jsonl_bit_for_bit(run):
    boxes, checked = box_store.read(run / "boxes.cpbx")
    lines = [json.loads(l) for l in open(run / "boxes.jsonl") if l.strip()]
    assert checked
    assert len(boxes) == len(lines) > 0
    assert (boxes["facet"] == [l["facet"] for l in lines]).all()
    assert (boxes["cls"] == [box_store.VALID if l["class"] == "valid" else box_store.BOUNDARY for l in lines]).all()
    # Shortest round-trip decimals read back to the same doubles: equal bit for bit.
    assert np.array_equal(boxes["position"].view("<u8"), np.array([l["position"] for l in lines]).view("<u8"))
    assert np.array_equal(boxes["orientation"].view("<u8"), np.array([l["orientation"] for l in lines]).view("<u8"))
    assert ((boxes["cls"] == box_store.VALID) == (boxes["reason"] == box_store.NO_REASON)).all()
    assert (boxes["position"][:, :, 0] <= boxes["position"][:, :, 1]).all()
    summary = json.load(open(run / "summary.json"))
    assert (boxes["cls"] == box_store.VALID).sum() == summary["totals"]["valid"]


def test_damaged_stores_are_refused(run, tmp_path):
    data = (run / "boxes.cpbx").read_bytes()
    (tmp_path / "cut.cpbx").write_bytes(data[:-7])
    with pytest.raises(box_store.BoxStoreError, match="truncated"):
        box_store.read(tmp_path / "cut.cpbx")
    (tmp_path / "whole.cpbx").write_bytes(data[:-104])  # cut at a record boundary: the header counts
    with pytest.raises(box_store.BoxStoreError, match="truncated"):
        box_store.read(tmp_path / "whole.cpbx")
    (tmp_path / "magic.cpbx").write_bytes(b"XX" + data[2:])
    with pytest.raises(box_store.BoxStoreError, match="magic"):
        box_store.read(tmp_path / "magic.cpbx")
    (tmp_path / "v2.cpbx").write_bytes(data[:8] + (2).to_bytes(4, "little") + data[12:])
    with pytest.raises(box_store.BoxStoreError, match="version 2"):
        box_store.read(tmp_path / "v2.cpbx")
    (tmp_path / "short.cpbx").write_bytes(data[:10])
    with pytest.raises(box_store.BoxStoreError, match="header"):
        box_store.read(tmp_path / "short.cpbx")
    (tmp_path / "empty.cpbx").write_bytes(data[:24] + bytes(8))
    empty, _ = box_store.read(tmp_path / "empty.cpbx")
    assert len(empty) == 0


def test_keep_largest_keeps_the_largest(run, tmp_path):
    out = tmp_path / "kept"
    subprocess.run([PART, "--mesh", MESH, "--camera", CAMERA, "--position-eps", "0.4", "--orientation-eps", "0.38",
                    "--facets", "0-5,700", "--keep-largest", "3", "--box-store", "binary", "--threads", "2",
                    "--out", str(out), "-q"], check=True)
    assert not (out / "boxes.jsonl").exists()
    kept, _ = box_store.read(out / "boxes.cpbx")
    full, _ = box_store.read(run / "boxes.cpbx")
    full = full[full["cls"] == box_store.VALID]
    summary = json.load(open(out / "summary.json"))
    assert summary["settings"]["keep_largest"] == 3
    volume = lambda b: np.prod(b["position"][:, :, 1] - b["position"][:, :, 0], axis=1) * \
        np.prod(b["orientation"][:, :, 1] - b["orientation"][:, :, 0], axis=1)
    for rec in summary["facets"]:
        f = rec["index"]
        mine, all_ = kept[kept["facet"] == f], full[full["facet"] == f]
        assert len(mine) == min(3, len(all_)) == rec["valid"]
        assert rec.get("dropped", 0) == len(all_) - len(mine)
        if len(all_):
            # The kept boxes are boxes of the full run, and none left out is larger.
            assert {r.tobytes() for r in mine} <= {r.tobytes() for r in all_}
            assert volume(mine).min() >= np.sort(volume(all_))[::-1][min(3, len(all_)) - 1]
