"""Device selection and the device profile: the module chooses and configures its one GL context as
the CLI does (docs/gpu.md "Device selection", "Device profile"; docs/python.md "Contexts")."""
import json
import os
import subprocess
import sys

import pytest

import bounce
from conftest import cli_message


def python(code, **env):
    """Runs `code` in a fresh interpreter (a process whose context is not made yet) with `env` added."""
    return subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                          env={**os.environ, **{k: str(v) for k, v in env.items()}})


def test_select_gpu_checks_the_index_as_the_cli(gl, cli):
    # Past the EGL device enumeration: the CLI's one line (naming the device count), from select_gpu.
    expected = cli_message(cli("--gpu", 99, "info"), "info").replace("--gpu", "select_gpu")
    done = python("import bounce\ntry:\n    bounce.select_gpu(99)\nexcept bounce.Error as e:\n    print(e)")
    assert done.returncode == 0 and done.stdout.strip() == expected, done.stdout + done.stderr
    # Once this process's context exists, it cannot move.
    with pytest.raises(bounce.Error, match="exists already"):
        bounce.select_gpu(0)


def test_bad_egl_device_in_the_environment_is_an_error(gl):
    done = python("import bounce\ntry:\n    bounce.gl_info()\nexcept bounce.Error as e:\n    print('Error:', e)",
                  BOUNCE_EGL_DEVICE="many")
    assert done.returncode == 0 and done.stdout.startswith("Error:") and "BOUNCE_EGL_DEVICE" in done.stdout, done.stdout + done.stderr


@pytest.mark.parametrize("profile", [None, "gpu"])
def test_profile_defaults_under_the_settings_as_the_cli(gl, tmp_path, profile):
    """rsm.vplBatch has a per-profile default: a renderer starts from its context's profile's value, as
    `bounce render --stats` records it, and settings= still wins."""
    env = {} if profile is None else {"BOUNCE_PROFILE": profile}
    code = ("import bounce, json\n"
            "r = bounce.Renderer('cornell-box', 'rsm', 8)\n"
            "s = bounce.Renderer('cornell-box', 'rsm', 8, settings={'vplBatch': 3})\n"
            "print(json.dumps([bounce.gl_info()['profile'], r.settings['technique']['vplBatch'],"
            " s.settings['technique']['vplBatch']]))")
    done = python(code, **env)
    assert done.returncode == 0, done.stderr
    got_profile, batch, given = json.loads(done.stdout)
    stats = tmp_path / "r.json"
    rendered = subprocess.run([os.environ["BOUNCE"], "render", "--scene", "cornell-box", "--technique", "rsm", "--size", "8x8",
                               "--out", tmp_path / "r.exr", "--stats", stats], capture_output=True, text=True,
                              env={**os.environ, **env})
    assert rendered.returncode == 0, rendered.stderr
    record = json.loads(stats.read_text())
    assert got_profile == record["gpu"]["profile"] == (profile or got_profile)
    assert batch == record["settings"]["vplBatch"] and given == 3
    grid = next(s for s in bounce.technique("rsm")["settings"] if s["name"] == "vplBatch")
    assert f"{got_profile} {batch}" in grid["profile_defaults"], grid
