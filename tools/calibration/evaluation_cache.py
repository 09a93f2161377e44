"""Every DEM run of a calibration, cached on disk by what was run.

The key is a hash of the complete scenario of the run (contact parameters,
packing seed, confinement, everything else the sample holds), so a killed
calibration that starts again finds its finished runs and reruns none of
them, and a changed sample or parameter can never be mistaken for a cached
one. Nelder-Mead is deterministic, so the resumed search asks for the same
points in the same order and walks through the cache to where it stopped.

One file per run, <cache>/<key>.json: {"key", "scenario", "measured", "wall_s"},
written atomically (a run killed while writing leaves no half entry).
"""
import hashlib
import json
import os
import threading


def run_key(scenario):
    """16 hex digits of the SHA-256 of the scenario in canonical JSON (sorted keys,
    floats as repr: two parameter values that differ in any bit differ in key)."""
    text = json.dumps(scenario, sort_keys=True, separators=(",", ":"))
    return hashlib.sha256(text.encode()).hexdigest()[:16]


class EvaluationCache:
    def __init__(self, folder):
        self.folder = folder
        os.makedirs(folder, exist_ok=True)
        self.hits = 0
        self.misses = 0
        self.lock = threading.Lock()   # the counters, when runs go side by side

    def path(self, key):
        return os.path.join(self.folder, key + ".json")

    def get(self, scenario):
        """The cached entry of this scenario, or None."""
        path = self.path(run_key(scenario))
        if not os.path.exists(path):
            return None
        with open(path) as f:
            entry = json.load(f)
        with self.lock:
            self.hits += 1
        return entry

    def put(self, scenario, measured, wall_s):
        key = run_key(scenario)
        entry = {"key": key, "scenario": scenario, "measured": measured, "wall_s": wall_s}
        tmp = self.path(key) + ".tmp"
        with open(tmp, "w") as f:
            json.dump(entry, f, indent=1)
        os.replace(tmp, self.path(key))
        with self.lock:
            self.misses += 1
        return entry

    def entries(self):
        """Every cached entry (for the total DEM runs and wall time of a calibration)."""
        for name in sorted(os.listdir(self.folder)):
            if name.endswith(".json"):
                with open(os.path.join(self.folder, name)) as f:
                    yield json.load(f)
