#!/usr/bin/env bash
# cmake --install puts the package under <prefix>/lib/python3/dist-packages: Debian's python3
# imports it from there (outside the source and build trees), documents its units and frames,
# and flies a hover with it.
set -euo pipefail
build=$1
python=$2
prefix=$(mktemp -d)
trap 'rm -rf "$prefix"' EXIT
cmake --install "$build" --prefix "$prefix" > /dev/null
test -x "$prefix/bin/aerobox"
cd "$prefix"
# a sanitizer build's python3 needs its runtime preloaded (tests/CMakeLists.txt): for python3 alone
LD_PRELOAD="${AEROBOX_PYTHON_PRELOAD:-}" PYTHONPATH="$prefix/lib/python3/dist-packages" \
  PYTHONDONTWRITEBYTECODE=1 "$python" - <<'PY'
import os, pydoc, tempfile
import aerobox
assert aerobox.__file__.startswith(os.getcwd()), aerobox.__file__
text = pydoc.render_doc(aerobox.Simulator, renderer=pydoc.plaintext)
for words in ("[m]", "[N]", "[rad/s]", "[i, j, k, w]", "body", "[Hz]"):
    assert words in text, words
with tempfile.TemporaryDirectory() as folder:
    path = os.path.join(folder, "open.txt")
    with open(path, "w") as file:
        file.write("boundary -2 -2 0 2 2 3\n")
    sim = aerobox.Simulator(path, start=[0, 0, 1])
    hover = sim.quad_params["mass"] * 9.81 / 4
    class Hold:
        duration = 1.0
        def update(self, t):
            return {"x": [0.0, 0.0, 1.0]}
    class Thrusts:
        def update(self, t, state, flat_output):
            return {"cmd_motor_thrusts": [hover] * 4}
    result = sim.run(Thrusts(), Hold(), t_final=1.0)
    assert result["collisions"] == 0 and abs(result["state"]["x"][-1][2] - 1.0) < 0.01, result["status"]
print("installed package: ok")
PY
