"""Every interruption is logged and leaves no partial output: SIGTERM (a batch system, `timeout`)
is handled like Ctrl-C — the interrupted stage's temporary folder is removed, run.log says so,
the exit code is 143 (128 + SIGTERM) — and bad numeric options are messages, not tracebacks
(docs/reliability.md)."""

from __future__ import annotations

import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest
from typer.testing import CliRunner

from bearingsim.pipeline.cli.commands import app

runner = CliRunner()


def test_sigterm_during_simulate_is_logged_and_leaves_no_temporary(tmp_path):
    out = tmp_path / "run"
    # as users start it: `python -m bearingsim` runs what the console script runs (test_packaging)
    proc = subprocess.Popen([sys.executable, "-m", "bearingsim",
                             "simulate", "helicopter-b-given-hinge", "--out", str(out),
                             "--set", "solver.duration=0.8", "--set", "output.figures=false"],
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    try:
        deadline = time.monotonic() + 300
        while not list(out.glob(".simulate.*.tmp")) and proc.poll() is None and time.monotonic() < deadline:
            time.sleep(0.2)
        assert proc.poll() is None, proc.communicate()[1][-3000:]
        time.sleep(1.0)  # inside the time loop
        proc.send_signal(signal.SIGTERM)
        _, err = proc.communicate(timeout=120)
    finally:
        proc.kill()
    assert proc.returncode == 143, err[-3000:]
    assert "interrupted (SIGTERM)" in err and "Traceback" not in err
    assert "interrupted (SIGTERM)" in (out / "run.log").read_text()
    assert not list(out.glob(".*.tmp")) and not (out / "simulate").exists()
    assert (out / "quasistatic" / "stage.json").is_file()  # finished stages are kept


@pytest.mark.parametrize("option, value", [("--window", "0"), ("--window", "nan"), ("--window", "-1"),
                                           ("--wall-budget", "inf")])
def test_stability_options_out_of_range_are_messages(option, value, tmp_path):
    result = runner.invoke(app, ["stability", "high-moment", option, value, "--out", str(tmp_path / "s")])
    assert result.exit_code == 2, result.output[-2000:]
    assert f"{option}: is " in result.stderr and "positive finite time in seconds" in result.stderr


def test_ctrl_c_during_a_sweep_says_how_to_continue(tmp_path, monkeypatch):
    import bearingsim.pipeline.sweep.driver as driver

    def interrupted(*args, **kwargs):
        raise KeyboardInterrupt

    def interrupted_while_a_point_ran(plan, *args, **kwargs):
        (Path(plan.requests[0].run_dir) / ".simulate.k1ll3d.tmp").mkdir(parents=True)
        raise KeyboardInterrupt

    monkeypatch.setattr(driver, "run_sweep", interrupted_while_a_point_ran)
    result = runner.invoke(app, ["sweep", "helicopter-b-given-hinge", "--set", "solver.duration=0.002",
                                 "--vary", "load.moment=1,2", "--out", str(tmp_path / "s"), "--workers", "1"])
    assert result.exit_code == 130, result.output[-2000:]
    assert "interrupted (Ctrl-C)" in result.stderr and "run the same command again" in result.stderr
    assert not list((tmp_path / "s").rglob(".*.tmp"))  # the killed point's temporary is gone


@pytest.mark.slow
def test_ctrl_c_of_a_real_sweep_is_one_message(tmp_path):
    """Ctrl-C reaches the whole process group, the workers included: one message, no traceback."""
    out = tmp_path / "s"
    proc = subprocess.Popen([sys.executable, "-m", "bearingsim",
                             "sweep", "helicopter-b-given-hinge", "--set", "solver.duration=0.3",
                             "--set", "output.figures=false", "--vary", "load.moment=100,200,300,400",
                             "--out", str(out)], stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                            start_new_session=True, preexec_fn=lambda: signal.signal(signal.SIGINT, signal.SIG_DFL))
    try:
        deadline = time.monotonic() + 300
        while not list(out.glob("points/*/.simulate.*.tmp")) and time.monotonic() < deadline:
            time.sleep(0.2)
        os.killpg(proc.pid, signal.SIGINT)
        _, err = proc.communicate(timeout=120)
    finally:
        proc.kill()
    assert proc.returncode == 130, err[-3000:]
    assert "interrupted (Ctrl-C)" in err and "Traceback" not in err and "killing" not in err
    assert not list(out.rglob(".*.tmp"))


@pytest.fixture(autouse=True)
def python_sigint_handler():
    """Python's own SIGINT handler during each test, as in an interactive shell: a job started in
    the background of a non-interactive shell inherits SIGINT ignored, which `quiet_interrupt`
    rightly keeps."""
    outside = signal.signal(signal.SIGINT, signal.default_int_handler)
    yield
    signal.signal(signal.SIGINT, outside)


def _interrupt_handler_name():
    return getattr(signal.getsignal(signal.SIGINT), "__qualname__", "")


def test_a_sweep_and_its_workers_go_down_quietly_on_ctrl_c():
    """A local cluster's workers take the same Ctrl-C as the sweep; each process silences its
    Dask logging before its own handler goes on (pipeline/sweep/quiet_interrupt.py)."""
    pytest.importorskip("distributed")
    from bearingsim.pipeline.sweep.driver import dask_client

    before = signal.getsignal(signal.SIGINT)
    with dask_client(workers=1) as client:
        assert _interrupt_handler_name() == "silence_then.<locals>.on_interrupt"
        names = client.run(_interrupt_handler_name)
    assert list(names.values()) == ["silence_then.<locals>.on_interrupt"]
    assert signal.getsignal(signal.SIGINT) is before


@pytest.fixture
def dask_log_levels():
    """The levels of the loggers a Ctrl-C silences, read after the test; restored afterwards."""
    import logging

    from bearingsim.pipeline.sweep.quiet_interrupt import QUIET_ON_INTERRUPT

    before = {name: logging.getLogger(name).level for name in QUIET_ON_INTERRUPT}
    yield lambda: {logging.getLogger(name).level for name in QUIET_ON_INTERRUPT}
    for name, level in before.items():
        logging.getLogger(name).setLevel(level)


def test_ctrl_c_silences_dask_then_raises_as_before(dask_log_levels):
    import logging

    from bearingsim.pipeline.sweep.quiet_interrupt import quiet_on_interrupt

    with pytest.raises(KeyboardInterrupt), quiet_on_interrupt():
        signal.getsignal(signal.SIGINT)(signal.SIGINT, None)
    assert dask_log_levels() == {logging.CRITICAL}
    assert signal.getsignal(signal.SIGINT) is signal.default_int_handler


def test_a_worker_silences_dask_then_hands_on(dask_log_levels):
    import logging

    from bearingsim.pipeline.sweep.quiet_interrupt import silence_then

    seen = []
    silence_then(lambda signum, frame: seen.append(signum))(signal.SIGINT, None)
    assert dask_log_levels() == {logging.CRITICAL}
    assert seen == [signal.SIGINT]


def test_the_quiet_handler_keeps_the_default_action():
    """Without a Python handler before it, the process ends by the signal, as it would have."""
    code = ("import signal; from bearingsim.pipeline.sweep.quiet_interrupt import silence_then; "
            "silence_then(signal.SIG_DFL)(signal.SIGINT, None); print('still running')")
    result = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=60)
    assert result.returncode == -signal.SIGINT and "still running" not in result.stdout


def test_a_workers_handler_mutes_its_standard_error_first():
    """A worker ended by KeyboardInterrupt gets a traceback from multiprocessing, which is no
    log; the worker's handler sends its standard error to the null device before handing on."""
    code = ("import signal, sys; from bearingsim.pipeline.sweep.quiet_interrupt import silence_then\n"
            "def raise_(*a): raise KeyboardInterrupt\n"
            "print('before', file=sys.stderr, flush=True)\n"
            "try:\n    silence_then(raise_, mute_stderr=True)(signal.SIGINT, None)\n"
            "except KeyboardInterrupt:\n    print('after', file=sys.stderr, flush=True)\n")
    result = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=60)
    assert "before" in result.stderr and "after" not in result.stderr


def test_a_worker_that_ignores_ctrl_c_keeps_ignoring_it():
    from bearingsim.pipeline.sweep.quiet_interrupt import dask_setup

    before = signal.signal(signal.SIGINT, signal.SIG_IGN)
    try:
        dask_setup(None)
        assert signal.getsignal(signal.SIGINT) == signal.SIG_IGN
    finally:
        signal.signal(signal.SIGINT, before)
