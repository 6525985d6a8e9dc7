"""Scene files are read in bounded time and memory: a device, a FIFO, a socket or an oversized
file in a scene's place is refused with exit 2 before it is read (docs/reliability.md)."""

from __future__ import annotations

import os
import resource
import socket
import subprocess
import sys

import pytest

MAX_SCENE_BYTES = 1_000_000  # [B] the documented limit (docs/reliability.md)

COMMANDS = (["check"], ["quasistatic"], ["sweep", "--dry-run", "--vary", "load.moment=1,2"])


def bearingsim(*args, timeout=60):
    """The command line in a child process with 3 GB of address space at most: a reader that
    takes a device's endless bytes fails there instead of filling the machine."""
    def limit():
        resource.setrlimit(resource.RLIMIT_AS, (3 << 30, 3 << 30))

    return subprocess.run([sys.executable, "-c", "from bearingsim.pipeline.cli.commands import main; main()", *args],
                          capture_output=True, text=True, timeout=timeout, preexec_fn=limit)


def _fifo(tmp_path):
    os.mkfifo(tmp_path / "scene.toml")
    return str(tmp_path / "scene.toml")


def _device(tmp_path):
    return "/dev/zero"


def _link_to_a_device(tmp_path):
    (tmp_path / "scene.toml").symlink_to("/dev/zero")
    return str(tmp_path / "scene.toml")


def _oversized(tmp_path):
    (tmp_path / "scene.toml").write_bytes(b"# " + b"x" * MAX_SCENE_BYTES + b"\n")
    return str(tmp_path / "scene.toml")


def _socket(tmp_path):
    sock = socket.socket(socket.AF_UNIX)
    sock.bind(str(tmp_path / "s.toml"))
    return str(tmp_path / "s.toml")


SPECIAL = {"fifo": _fifo, "/dev/zero": _device, "link to /dev/zero": _link_to_a_device,
           "oversized": _oversized, "socket": _socket}


@pytest.mark.parametrize("kind", SPECIAL)
def test_check_refuses_special_and_oversized_scene_files(kind, tmp_path):
    scene = SPECIAL[kind](tmp_path)
    result = bearingsim("check", scene)
    assert result.returncode == 2, result.stderr[-2000:]
    expected = "larger than 1000 kB" if kind == "oversized" else "is not a regular file"
    assert expected in result.stderr and "Traceback" not in result.stderr


@pytest.mark.parametrize("command", COMMANDS, ids=lambda c: c[0])
def test_every_command_refuses_a_fifo_at_once(command, tmp_path):
    out = [] if command[0] == "check" else ["--out", str(tmp_path / "out")]
    result = bearingsim(command[0], _fifo(tmp_path), *command[1:], *out)
    assert result.returncode == 2 and "is not a regular file" in result.stderr
    assert not (tmp_path / "out").exists()


def test_a_scene_just_under_the_limit_is_read(tmp_path):
    from pathlib import Path

    from bearingsim.pipeline.scene.load import read_scene_table

    text = (Path(__file__).parents[1] / "pipeline" / "scenes" / "deep-groove-209.toml").read_text()
    padded = text + "#" * (MAX_SCENE_BYTES - len(text.encode()) - 1) + "\n"
    assert len(padded.encode()) == MAX_SCENE_BYTES
    (tmp_path / "scene.toml").write_text(padded)
    assert read_scene_table(tmp_path / "scene.toml")[0]["name"] == "deep-groove-209"
