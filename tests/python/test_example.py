"""docs/python.md's example runs (a whole part solved, a plan, a coverage plot), and every
```python block of docs/python.md is an excerpt of examples/python/*.py, so the page cannot rot."""
import os
import pathlib
import subprocess
import sys

ROOT = pathlib.Path(__file__).resolve().parents[2]
SHARED = pathlib.Path(os.environ.get("CERTIPOSE_SHARED", ROOT.parent / "shared"))
EXAMPLE = ROOT / "examples" / "python" / "plan_cameras.py"


def test_the_example_solves_plans_and_plots(tmp_path):
    (tmp_path / "kept").mkdir()
    out = subprocess.run([sys.executable, str(EXAMPLE), "coverage.png", "--mesh", str(SHARED / "meshes" / "angle_block.off"),
                          "--camera", str(SHARED / "cases" / "camera.json"), "--threads", "2", "--plan", "kept/plan.json"],
                         cwd=tmp_path, capture_output=True, text=True, check=True)
    assert "704 facets:" in out.stdout and "cameras certify" in out.stdout, out.stdout
    png = (tmp_path / "coverage.png").read_bytes()
    assert png.startswith(b"\x89PNG") and len(png) > 20000
    assert (tmp_path / "kept" / "plan.json").read_text().startswith("{")


def test_the_docs_command_runs_on_what_comes_with_the_module(tmp_path):
    # The page's command: the sample part and the example camera from the package, and nothing
    # written but the picture it was told to write.
    out = subprocess.run([sys.executable, str(EXAMPLE), "python.png", "--threads", "2"],
                         cwd=tmp_path, capture_output=True, text=True, check=True)
    assert "2300 facets:" in out.stdout and "cameras certify" in out.stdout, out.stdout
    assert sorted(p.name for p in tmp_path.iterdir()) == ["python.png"]


def python_blocks(page):
    blocks, block = [], None
    for line in page:
        if line.strip() == "```python":
            block = []
        elif line.strip() == "```" and block is not None:
            blocks.append(block)
            block = None
        elif block is not None:
            block.append(line.strip())
    return blocks


def test_every_python_block_of_the_docs_is_an_excerpt_of_an_example():
    examples = [[line.strip() for line in p.read_text().splitlines()] for p in (ROOT / "examples" / "python").glob("*.py")]
    page = (ROOT / "docs" / "python.md").read_text().splitlines()
    readme = (ROOT / "README.md").read_text().splitlines()
    assert len(python_blocks(page)) >= 3 and len(python_blocks(readme)) >= 1
    for b in python_blocks(page) + python_blocks(readme):
        lines = [x for x in b if x]
        found = any(any(all(e[i + k] == lines[k] for k in range(len(lines))) for i in range(len(e) - len(lines) + 1))
                    for e in [[x for x in ex if x] for ex in examples])
        assert found, "this ```python block of docs/python.md is not an excerpt of examples/python/*.py:\n" + "\n".join(b)


def test_the_one_facet_example_runs(tmp_path):
    out = subprocess.run([sys.executable, str(ROOT / "examples" / "python" / "one_facet.py")], cwd=tmp_path,
                         capture_output=True, text=True, check=True).stdout
    assert "VALID boxes in" in out and "certifies facets [2" in out and "error: facet 12 is out of range" in out, out
