"""python/dfc_results installs as a package (issue 42, part 6).

Usage: test_package_install.py REPOSITORY_ROOT WORK_DIR

Makes a fresh virtual environment in WORK_DIR that sees Debian's packages
(--system-site-packages: numpy, h5py, setuptools), installs python/ into it
with pip, offline (--no-index: no PyPI; --no-build-isolation: Debian's
setuptools builds it; --no-deps: Debian registers its h5py under the name
"h5py._debian_h5py_serial", so pip would look for "h5py" on an index), and
imports dfc_results, numpy and h5py from outside the source tree: the module
must come from the environment's site-packages, and its metadata must name
numpy and h5py as dependencies.

Exit code 77 (CTest SKIP_RETURN_CODE) when venv, pip or setuptools is missing.
"""
import os
import shutil
import subprocess
import sys

from dfc_test_support import require_modules

require_modules("numpy", "h5py", "setuptools", "venv", "pip")

ROOT, WORK = sys.argv[1], sys.argv[2]
shutil.rmtree(WORK, ignore_errors=True)
os.makedirs(WORK)
# A copy of python/: pip builds in the folder it installs from (build/,
# *.egg-info), which must not land in the source tree.
source = os.path.join(WORK, "python")
shutil.copytree(os.path.join(ROOT, "python"), source, ignore=shutil.ignore_patterns("__pycache__", "build", "*.egg-info"))
venv = os.path.join(WORK, "venv")
subprocess.run([sys.executable, "-m", "venv", "--system-site-packages", venv], check=True)
python = os.path.join(venv, "bin", "python")
environment = dict(os.environ, PIP_NO_INDEX="1", PIP_DISABLE_PIP_VERSION_CHECK="1")
environment.pop("PYTHONPATH", None)
subprocess.run([python, "-m", "pip", "install", "--no-index", "--no-build-isolation", "--no-deps", source], check=True, env=environment, timeout=300)

probe = """
import importlib.metadata, json, numpy, h5py, dfc_results
print(json.dumps({"file": dfc_results.__file__, "open_results": callable(dfc_results.open_results),
                  "requires": importlib.metadata.requires("dfc-results") or []}))
"""
result = subprocess.run([python, "-c", probe], cwd=WORK, env=environment, capture_output=True, text=True, timeout=120)
print(result.stdout, result.stderr)
if result.returncode != 0:
    sys.exit("importing the installed dfc_results failed")
import json  # noqa: E402

found = json.loads(result.stdout.strip().splitlines()[-1])
failures = []
site = os.path.realpath(venv)
if not os.path.realpath(found["file"]).startswith(site + os.sep):
    failures.append(f"dfc_results came from {found['file']}, not from the environment's site-packages under {site}")
if not found["open_results"]:
    failures.append("dfc_results.open_results is not callable")
names = {r.split(";")[0].strip().split(" ")[0].split(">")[0].split("=")[0].split("<")[0] for r in found["requires"]}
for needed in ("numpy", "h5py"):
    if needed not in names:
        failures.append(f"the package's metadata does not require {needed} (requires: {found['requires']})")
for failure in failures:
    print("FAIL:", failure)
sys.exit(1 if failures else 0)
