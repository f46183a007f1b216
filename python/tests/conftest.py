"""Shared fixtures of the `import bounce` tests (ctest python_tests; docs/python.md "Tests").

The module comes from PYTHONPATH (build/python under ctest); BOUNCE names the `bounce` executable the
tests hold the module against. Tests that need OpenGL take the `gl` fixture: without a context they
are skipped, or fail under CI=true, as the C++ GPU tests (tests/gpu/GpuTestSupport.h).
"""
import os
import subprocess

import pytest

import bounce


@pytest.fixture(scope="session")
def gl():
    try:
        return bounce.gl_info()
    except bounce.Error as e:
        if os.environ.get("CI") == "true":
            pytest.fail(f"CI=true and no OpenGL 4.5 context: {e}")
        pytest.skip(f"no OpenGL 4.5 context: {e}")


@pytest.fixture(scope="session")
def cli():
    """Runs the `bounce` executable: cli("render", ...) -> CompletedProcess (text)."""
    exe = os.environ.get("BOUNCE")
    if not exe or not os.path.exists(exe):
        if os.environ.get("CI") == "true":
            pytest.fail("CI=true and BOUNCE does not name the bounce executable")
        pytest.skip("BOUNCE does not name the bounce executable")

    def run(*args):
        return subprocess.run([exe, *map(str, args)], capture_output=True, text=True)

    return run


def cli_message(completed, command):
    """The one-line message of a failed `bounce COMMAND` (stderr without 'bounce COMMAND: ')."""
    assert completed.returncode != 0, completed.stdout
    lines = [l for l in completed.stderr.splitlines() if l.startswith(f"bounce {command}: ")]
    assert len(lines) == 1, completed.stderr
    return lines[0][len(f"bounce {command}: "):]
