"""pip install from a clean copy of the source tree, the way the README says: a virtual environment
over Debian's packages, `pip install --no-build-isolation .` (no package index), and `-e` for
development. Each installed package runs a scene from a clean folder with its own plugins."""
import os
import pathlib
import shutil
import subprocess
import sys

import pytest

from conftest import SOURCE

SCRIPT = ("import mechgraph, sys; s = mechgraph.Scene.load(sys.argv[1]); r = s.run(outputs=['ta_kurz.time_area']); "
          "print(mechgraph.__file__); print(mechgraph.plugins()[0]['file']); print(r['ta_kurz.time_area'])")


def clean_copy(to: pathlib.Path) -> pathlib.Path:
    """What git tracks (and new files it does not ignore), without any build output: a fresh clone's tree."""
    listed = subprocess.run(["git", "-C", str(SOURCE), "ls-files", "-z", "--cached", "--others", "--exclude-standard"],
                            capture_output=True, check=True).stdout.split(b"\0")
    for name in filter(None, listed):
        source = SOURCE / os.fsdecode(name)
        if source.is_file():
            target = to / os.fsdecode(name)
            target.parent.mkdir(parents=True, exist_ok=True)
            shutil.copy2(source, target)
    return to


def environment(tmp_path: pathlib.Path) -> dict:
    env = {k: v for k, v in os.environ.items() if k not in ("PYTHONPATH", "MECHGRAPH_PLUGIN_PATH", "PYTHONHOME")}
    env["PIP_NO_INDEX"] = "1"          # nothing to download: every requirement is Debian's
    env["PIP_DISABLE_PIP_VERSION_CHECK"] = "1"
    env["PIP_NO_CACHE_DIR"] = "1"      # pip keeps nothing in the user's home
    env["PIP_CONFIG_FILE"] = os.devnull  # nor reads its configuration from there
    return env


def venv(path: pathlib.Path, env: dict) -> pathlib.Path:
    subprocess.run(["/usr/bin/python3", "-m", "venv", "--system-site-packages", str(path)], check=True, env=env)
    return path / "bin"


def run_scene(python: pathlib.Path, cwd: pathlib.Path, env: dict) -> list:
    out = subprocess.run([str(python), "-c", SCRIPT, str(SOURCE / "scenes" / "valvetrain_cams.yaml")], cwd=cwd, env=env,
                         capture_output=True, text=True, timeout=300)
    assert out.returncode == 0, out.stderr[-3000:]
    return out.stdout.splitlines()


@pytest.mark.skipif(not pathlib.Path("/usr/bin/python3").exists() or shutil.which("git") is None,
                    reason="needs Debian's python3 and git")
def test_pip_install_and_editable_install_from_a_clean_copy(tmp_path):
    source = clean_copy(tmp_path / "src")
    env = environment(tmp_path)
    clean = tmp_path / "clean"
    clean.mkdir()

    installed = venv(tmp_path / "v", env)
    done = subprocess.run([str(installed / "pip"), "install", "--no-build-isolation", str(source)], env=env,
                          capture_output=True, text=True, timeout=1800)
    assert done.returncode == 0, done.stdout[-3000:] + done.stderr[-3000:]
    module, plugin, value = run_scene(installed / "python", clean, env)
    assert module.startswith(str(tmp_path / "v")), module   # the installed package, not the source
    assert plugin.startswith(str(tmp_path / "v")), plugin   # its own plugins, beside its libmechgraph
    assert float(value) > 0

    editable = venv(tmp_path / "e", env)
    done = subprocess.run([str(editable / "pip"), "install", "--no-build-isolation", "-e", str(source)], env=env,
                          capture_output=True, text=True, timeout=1800)
    assert done.returncode == 0, done.stdout[-3000:] + done.stderr[-3000:]
    module, plugin, again = run_scene(editable / "python", clean, env)
    assert module == str(source / "python" / "mechgraph" / "__init__.py"), module  # edits show without reinstalling
    assert plugin.startswith(str(source / "python" / "mechgraph" / "_lib")), plugin
    assert again == value
