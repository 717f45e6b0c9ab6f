"""`cmake --install` puts a package Debian's python3 imports from a clean folder, plugins found."""
import os
import pathlib
import subprocess
import sys

from conftest import BINARY, SOURCE


def test_installed_module_imports_from_a_clean_folder(tmp_path):
    prefix = tmp_path / "prefix"
    subprocess.run(["cmake", "--install", str(BINARY), "--prefix", str(prefix)], check=True, capture_output=True)
    found = list(prefix.glob("lib*/python3*/dist-packages/mechgraph/_core*.so"))
    assert found, "no extension installed"
    site = found[0].parent.parent
    clean = tmp_path / "clean"
    clean.mkdir()
    env = {k: v for k, v in os.environ.items() if k not in ("PYTHONPATH", "MECHGRAPH_PLUGIN_PATH")}
    env["PYTHONPATH"] = str(site)
    code = ("import mechgraph, sys; s = mechgraph.Scene.load(sys.argv[1]); "
            "r = s.run(outputs=['ta_kurz.time_area']); print(mechgraph.__file__); "
            "print(mechgraph.plugins()[0]['file']); print(r['ta_kurz.time_area'])")
    out = subprocess.run([sys.executable, "-c", code, str(SOURCE / "scenes" / "valvetrain_cams.yaml")], cwd=clean,
                         env=env, capture_output=True, text=True, check=True).stdout.splitlines()
    assert out[0].startswith(str(prefix)), out  # the installed package, not the build tree
    assert out[1].startswith(str(prefix)), out  # its plugins, from the installed folder
    assert float(out[2]) > 0
