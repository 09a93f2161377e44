#!/usr/bin/env python3
"""A stand-in for build/bin/coupler in tests/python/test_calibration.py: `run
SCENARIO --out DIR --no-progress` writes DIR/results.h5 with a closed-form
compression curve instead of running the DEM, so the calibrator's search,
cache, resume and outputs are tested in seconds.

The curve (tests/python/test_report.py's write_curve): Young's modulus
0.5 sb_emod_pa, peak 1.1 sb_coh_pa^0.95 (sb_emod_pa / 1e9)^0.05 times a
packing factor 1 + 0.02 (seed - 4), so the scaling step lands close but not
on the target and the search has the rest to do. FAKE_COUPLER_COUNT names a
file that counts the runs; FAKE_COUPLER_FAIL_AFTER=N makes every run after the
N-th fail (a killed calibration).
"""
import json
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from test_report import write_curve  # noqa: E402


def main(argv):
    scenario_path, out = argv[2], argv[argv.index("--out") + 1]
    counter = os.environ.get("FAKE_COUPLER_COUNT")
    count = 0
    if counter and os.path.exists(counter):
        with open(counter) as f:
            count = int(f.read())
    limit = os.environ.get("FAKE_COUPLER_FAIL_AFTER")
    if limit is not None and count >= int(limit):
        print("fake coupler: killed", file=sys.stderr)
        return 3
    with open(scenario_path) as f:
        dem = json.load(f)["participants"]["dem"]["config"]
    contact, seed = dem["contact"], dem["particles"]["seed"]
    packing = 1.0 + 0.02 * (seed - 4)
    peak = 1.1 * contact["sb_coh_pa"] ** 0.95 * (contact["sb_emod_pa"] / 1e9) ** 0.05 * packing
    write_curve(os.path.join(out, "results.h5"), peak, 0.5 * contact["sb_emod_pa"])
    if counter:
        with open(counter, "w") as f:
            f.write(str(count + 1))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
