"""Importing bearingsim changes nothing of numba (docs/performance.md, *Cold start*): every
attribute of every numba module and of every class those modules define is the same object after
every bearingsim module is imported and one of its kernels compiled, so other numba code in the
same process compiles and runs exactly as it would without bearingsim. The kernels shape their
compile cost with numba's public `jit` options only (dynamics/_speed/compile_policy.py).

Runs in a fresh interpreter: numba is imported first, its state recorded, then bearingsim."""

from __future__ import annotations

import json
import subprocess
import sys
import textwrap

SCRIPT = textwrap.dedent(r"""
    import importlib, inspect, json, os, pkgutil, sys, tempfile
    os.environ["NUMBA_CACHE_DIR"] = tempfile.mkdtemp()
    import numba, numba.core.registry, numba.core.dispatcher, numba.core.typing.templates
    import numba.core.cpu, numba.core.codegen, numba.core.compiler, numba.core.typeinfer

    # what a patch replaces: functions, methods, classes and descriptors; numba's own lazy state
    # (caches filled on first compile, `__slotnames__` of pickled classes) is data
    def code(value):
        return (inspect.isroutine(value) or inspect.isclass(value)
                or isinstance(value, (property, staticmethod, classmethod)))

    def state():
        modules, classes = {}, {}
        for name, module in list(sys.modules.items()):
            if not (name == "numba" or name.startswith("numba.")) or module is None:
                continue
            attrs = dict(vars(module))
            modules[name] = {k: id(v) for k, v in attrs.items() if code(v)}
            for k, v in attrs.items():
                if inspect.isclass(v) and getattr(v, "__module__", None) == name:
                    classes[f"{name}.{v.__qualname__}"] = {a: id(b) for a, b in vars(v).items() if code(b)}
        return modules, classes, {name: vars(m) for name, m in sys.modules.items()
                                  if name.startswith("numba")}

    before_modules, before_classes, keep = state()
    kept = {name: dict(attrs) for name, attrs in keep.items()}  # hold the objects so ids stay theirs

    import bearingsim
    imported = []
    for part in ("dynamics", "fe_model", "pipeline"):   # the product (tests and benchmarks are not)
        package = importlib.import_module(f"bearingsim.{part}")
        for info in pkgutil.walk_packages(package.__path__, f"bearingsim.{part}."):
            if not info.name.endswith("__main__"):
                importlib.import_module(info.name)
                imported.append(info.name)
    from bearingsim.dynamics.contact.hertz import hertz_exact
    hertz_exact(200.0, 0.9, 2.3e11)   # compile one kernel too: a patch might wait for the first compile

    after_modules, after_classes, _ = state()
    changed = []
    for name, attrs in before_modules.items():
        now = after_modules.get(name, {})
        changed += [f"{name}.{k}" for k, v in attrs.items() if now.get(k) != v]
        changed += [f"{name}.{k} (added)" for k in now.keys() - attrs.keys()]
    for name, attrs in before_classes.items():
        now = after_classes.get(name, {})
        changed += [f"{name}.{k}" for k, v in attrs.items() if now.get(k) != v]
        changed += [f"{name}.{k} (added)" for k in now.keys() - attrs.keys()]
    print(json.dumps({"imported": len(imported), "modules": len(before_modules),
                      "classes": len(before_classes), "changed": changed}))
""")


def test_importing_bearingsim_leaves_numba_as_it_was(tmp_path):
    done = subprocess.run([sys.executable, "-c", SCRIPT], capture_output=True, text=True, cwd=tmp_path,
                          timeout=900)
    assert done.returncode == 0, done.stderr[-3000:]
    report = json.loads(done.stdout.strip().splitlines()[-1])
    assert report["imported"] > 100 and report["modules"] > 100 and report["classes"] > 500, report
    assert report["changed"] == [], report["changed"][:20]


def test_the_check_sees_a_replaced_method(tmp_path):
    """The comparison above can fail: one numba method replaced by a wrapper that gives the same
    answers shows up in it."""
    patched = SCRIPT.replace("import bearingsim\n",
                             "import bearingsim\nimport numba.core.dispatcher as _d\n"
                             "_f = _d.Dispatcher.get_call_template\n"
                             "_d.Dispatcher.get_call_template = lambda self, a, k: _f(self, a, k)\n")
    done = subprocess.run([sys.executable, "-c", patched], capture_output=True, text=True, cwd=tmp_path,
                          timeout=900)
    assert done.returncode == 0, done.stderr[-3000:]
    changed = json.loads(done.stdout.strip().splitlines()[-1])["changed"]
    assert any(c.startswith("numba.core.dispatcher.Dispatcher.get_call_template") for c in changed), changed
