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
