#!/usr/bin/env bash
# README's install of the Python module: a venv that sees Debian's packages (numpy, setuptools,
# pip), `pip install --no-build-isolation` from the checkout, then the installed module (not
# the build tree's) imports and solves a facet.
#   pip_install.sh PYTHON SOURCE_DIR WORK_DIR
set -euo pipefail
python=$1 source=$2 work=$3
rm -rf "$work"
"$python" -m venv --system-site-packages --without-pip "$work/venv"
cd "$work"  # not the checkout: `import certipose` must find the installed package
unset PYTHONPATH
"$work/venv/bin/python" -m pip install --no-build-isolation --no-deps --no-input -q "$source"
"$work/venv/bin/python" - "$source" <<'PY'
import pathlib, sys
import certipose
source = pathlib.Path(sys.argv[1])
where = pathlib.Path(certipose.__file__).resolve()
assert where.is_relative_to(pathlib.Path(sys.prefix).resolve()) and "site-packages" in where.parts, where  # the venv's
mesh = certipose.Mesh.read(str(source / "examples" / "data" / "fixture_plate.off"))
r = certipose.solve_facet(mesh, str(source / "examples" / "data" / "camera.json"), 6)
assert len(r) > 0 and r.bounds.shape == (len(r), 6, 2), r
# What comes with the package alone: the sample part, the example camera, the version.
part = certipose.sample_part()
first = certipose.solve_facet(part, certipose.example_camera(), 900, position_eps=0.1, orientation_eps=0.38)
assert part.num_faces == 2300 and first.valid.sum() > 0 and certipose.__version__, (part, first)
stub = where.parent / "__init__.pyi"
assert stub.exists() and stub.stat().st_size > 0 and (where.parent / "py.typed").exists()
print(f"installed {where.parent}: facet 6 of the fixture plate gives {int(r.valid.sum())} VALID boxes")
PY
