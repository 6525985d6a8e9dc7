"""The force kernel compiles each contact law once (docs/performance.md, *Compiling*).

numba compiles a function once per distinct argument type, and a literal constant at a call
site (`True`, `0`, `-1`) is a type of its own: two call sites that pass `True` and `False`
compile the callee, and everything it links in, twice. That doubled ~15 s of a machine's
first run. This test compiles the force kernel from an empty cache in a child process (the
cache would otherwise hold the callers and never compile the callees) and counts the
overloads of the kernels a ball–race contact calls (its two phases, `race_contact_normal` and
`race_contact_forces`, are inlined into the force kernel's contact loop, so they have none of
their own) and of `add_pair`, which used to be compiled more than once.
"""

from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]

_CHILD = """
import json
import numpy as np
from bearingsim.dynamics.bearing import BearingModel, ModelOptions
from bearingsim.dynamics.bearing import race_forces, tangents
from bearingsim.dynamics.contact import race
from bearingsim.dynamics.traction import fast
from bearingsim.dynamics.bearing.run import initial_coordinates
from bearingsim.dynamics.lubrication.lubricant import load_builtin_lubricant
from tests.bearing_fixtures import reference_model

params, start = reference_model(options=ModelOptions(), lubricant=load_builtin_lubricant("nato-o156"))
model = BearingModel(params)
q, v = initial_coordinates(params, start)
n = model.n_dof
model.evaluate(0.0, q, v, np.zeros(n), np.zeros(n), np.zeros(n))
model.jacobian(0.0, q, v, np.zeros(n), 1.0, 1e-6, 1e-12)
print(json.dumps({f.py_func.__name__: [str(sig) for sig in f.overloads]
                  for f in (race.ball_race_contact_kernel, race_forces._contact_stiffness, race_forces.nvm_terms_into,
                            race_forces._wrenches, fast.traction_fast, tangents.add_pair)}))
"""


@pytest.mark.slow
def test_contact_kernels_compile_once(tmp_path):
    env = dict(os.environ, NUMBA_CACHE_DIR=str(tmp_path / "numba"))
    out = subprocess.run([sys.executable, "-c", _CHILD], cwd=ROOT, env=env, capture_output=True, text=True,
                         check=True)
    overloads = json.loads(out.stdout.strip().splitlines()[-1])
    # each was compiled: an empty list would mean the child found them in a cache
    assert all(len(sigs) >= 1 for sigs in overloads.values()), overloads
    assert {name: len(sigs) for name, sigs in overloads.items()} == {
        "ball_race_contact_kernel": 1, "_contact_stiffness": 1, "nvm_terms_into": 1, "_wrenches": 1, "traction_fast": 1,
        "add_pair": 1}, overloads
