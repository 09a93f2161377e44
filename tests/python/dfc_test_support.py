"""Shared start of the dfc_results tests: python/ on the import path, and exit
code 77 (CTest SKIP_RETURN_CODE) when numpy or h5py are missing."""
import importlib.util
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), os.pardir, os.pardir, "python"))


def require_modules(*names):
    missing = [m for m in names if importlib.util.find_spec(m) is None]
    if missing:
        print(f"SKIPPED: python modules missing: {', '.join(missing)} (install python3-numpy python3-h5py)")
        sys.exit(77)


def require_pvbatch(display):
    """The command that starts ParaView's pvbatch here (in xvfb-run where it
    must draw and there is no $DISPLAY), or exit code 77 with the reason:
    pvbatch not on PATH (Debian's paraview package is large and not a
    dependency), no X display to draw into, or a pvbatch that does not start
    at all (a machine whose ParaView or X is broken is not the tests' subject).
    display: whether the script renders (Debian's ParaView renders through X;
    reading a file needs no display)."""
    import subprocess
    import tempfile

    sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), os.pardir, os.pardir, "tools"))
    import render

    if render.PVBATCH is None:
        print("SKIPPED: pvbatch (ParaView's Python) is not on PATH; tools/render.py uses its matplotlib path here")
        sys.exit(77)
    command = [render.PVBATCH]
    if display:
        if render.virtual_display_missing():
            print(f"SKIPPED: Debian's pvbatch renders through X: {render.virtual_display_missing()}")
            sys.exit(77)
        command = render.in_virtual_display(command)
    with tempfile.NamedTemporaryFile("w", suffix=".py", delete=False) as probe:
        probe.write("print('pvbatch runs')\n")
    started = subprocess.run(command + [probe.name], capture_output=True, text=True)
    os.unlink(probe.name)
    if started.returncode != 0 or "pvbatch runs" not in started.stdout:
        print(f"SKIPPED: pvbatch does not start here (exit status {started.returncode}): {started.stderr.strip()[-2000:]}")
        sys.exit(77)
    return command


def bonded_pile_scenario(source, out, name):
    """The small bonded pile of the run-view tests (python.run_view,
    python.xdmf_pvbatch; tools/looking_at_a_run_figures.sh runs it too):
    tests/e2e/scenarios/pile_bonded_restart.json for 120 exchanges with a
    snapshot every 40 and every optional snapshot array, contacts included.
    Writes it into the fresh folder `out`; returns its path."""
    import json
    import shutil

    shutil.rmtree(out, ignore_errors=True)
    os.makedirs(out)
    with open(os.path.join(source, "tests/e2e/scenarios/pile_bonded_restart.json")) as f:
        scenario = json.load(f)
    scenario["name"] = name
    scenario["run"].update({"exchanges": 120, "snapshot_every": 40, "deadline_s": 300})
    scenario["participants"]["dem"]["config"]["snapshot"] = {"contents": ["particle_stress", "bonds", "contacts", "walls"]}
    path = os.path.join(out, name + ".json")
    with open(path, "w") as f:
        json.dump(scenario, f, indent=1)
    return path
