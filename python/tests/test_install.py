# cmake --install puts the package where the docs say, and it imports and renders from there.
import os
import subprocess
import sys

import pytest

strahl = pytest.importorskip("strahl")


def test_installed_package_imports_and_renders(tmp_path):
    build, cmake = os.environ.get("STRAHL_BUILD_DIR"), os.environ.get("CMAKE_COMMAND")
    relative = os.environ.get("STRAHL_PYTHON_INSTALL_DIR")
    if not (build and cmake and relative):
        pytest.skip("run through ctest (STRAHL_BUILD_DIR, CMAKE_COMMAND, STRAHL_PYTHON_INSTALL_DIR)")
    prefix = tmp_path / "prefix"
    subprocess.run([cmake, "--install", build, "--prefix", prefix, "--component", "python"], check=True,
                   capture_output=True, timeout=120)
    site = prefix / relative
    assert sorted(p.name.split(".")[0] for p in (site / "strahl").iterdir()) == ["__init__", "_strahl"]
    code = ("import strahl, sys; assert strahl.__file__.startswith(sys.argv[1]), strahl.__file__; "
            "print(strahl.render(strahl.lecture_scene(), width=8, height=6).shape)")
    env = dict(os.environ, PYTHONPATH=str(site))
    result = subprocess.run([sys.executable, "-c", code, str(site)], env=env, cwd=tmp_path, capture_output=True,
                            text=True, timeout=120)
    assert result.returncode == 0, result.stderr
    assert result.stdout.strip() == "(6, 8, 3)"
