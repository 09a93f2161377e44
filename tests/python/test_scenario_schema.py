"""scenario.schema.json against the declarations and the shipped scenarios.

Usage: test_scenario_schema.py COUPLER REPOSITORY_ROOT WORK_DIR

1. The committed scenario.schema.json is what `coupler schema` generates from
   the declarations (regenerate: ./vc schema), and a valid draft 2020-12 schema.
2. Every shipped scenario (scenarios/, tests/e2e/scenarios/), as the coupler
   reads it (`coupler expand`: includes resolved, one document per variant),
   validates with an independent validator (Debian's python3-jsonschema).
3. Each declared server section of each shipped scenario passes the server's
   own parser (`coupler check` of a scenario with that participant alone): a
   parser that reads a key its declaration lacks fails there (std::logic_error,
   exit 1).
4. Broken scenarios fail the schema at the key path `coupler check` reports.

Exit code 77 (CTest SKIP_RETURN_CODE) when python3-jsonschema is missing.
"""
import copy
import glob
import json
import os
import re
import subprocess
import sys

from dfc_test_support import require_modules

require_modules("jsonschema")
from jsonschema import Draft202012Validator  # noqa: E402

COUPLER, ROOT, WORK = sys.argv[1], sys.argv[2], sys.argv[3]
os.makedirs(WORK, exist_ok=True)
failures = []


def fail(message):
    failures.append(message)
    print("FAIL:", message)


def run(*args, timeout=300):
    return subprocess.run([COUPLER, *args], capture_output=True, text=True, timeout=timeout)


# 1. The committed schema is the generated one.
generated = json.loads(run("schema").stdout)
with open(os.path.join(ROOT, "scenario.schema.json")) as f:
    committed = json.load(f)
if generated != committed:
    fail("scenario.schema.json differs from `coupler schema` (the declarations); regenerate it with ./vc schema")
Draft202012Validator.check_schema(generated)
validator = Draft202012Validator(generated)


def deepest_error_path(document):
    """The key path of the deepest schema error, dotted as the coupler writes it; None if valid."""
    paths = []
    for error in validator.iter_errors(document):
        parts = list(error.absolute_path)
        # An unknown key is reported at its object; the coupler names the key itself.
        if error.validator == "unevaluatedProperties":
            parts += re.findall(r"'([^']+)'", error.message.split("were unexpected")[0].split("was unexpected")[0])[:1]
        # A missing key is reported at its object; the coupler names the key.
        if error.validator == "required":
            parts += re.findall(r"'([^']+)' is a required property", error.message)[:1]
        paths.append(parts)
    if not paths:
        return None
    path = ""
    for part in max(paths, key=len):
        path += f"[{part}]" if isinstance(part, int) else (("." if path else "") + part)
    return path


# 2. Every shipped scenario validates.
files = sorted(glob.glob(os.path.join(ROOT, "scenarios", "*.json"))) + sorted(glob.glob(os.path.join(ROOT, "tests", "e2e", "scenarios", "*.json")))
documents = []
for path in files:
    result = run("expand", path)
    if result.returncode != 0:
        fail(f"coupler expand {path}: {result.stderr.strip()}")
        continue
    for document in json.loads(result.stdout):
        documents.append((path, document))
        if (where := deepest_error_path(document)) is not None:
            fail(f"{os.path.relpath(path, ROOT)} ({document['name']}): schema error at {where}")
print(f"{len(documents)} scenario documents from {len(files)} files validated")

# 3. Declared server sections pass their parsers (coupler check, one participant alone).
declared_programs = {"fdm_server"}
checked = set()
for path, document in documents:
    for slot, participant in document["participants"].items():
        program = os.path.basename(participant.get("program", ""))
        if program not in declared_programs:
            continue
        config = json.dumps(participant["config"], sort_keys=True)
        if config in checked:
            continue
        checked.add(config)
        alone = {"schema_version": 1, "name": "declared_parser_check", "gravity": document.get("gravity", {}),
                 "participants": {slot: participant}, "run": {"exchanges": 1}}
        scenario_file = os.path.join(WORK, f"alone_{len(checked)}.json")
        with open(scenario_file, "w") as f:
            json.dump(alone, f)
        result = run("check", scenario_file)
        if result.returncode != 0:
            fail(f"{os.path.relpath(path, ROOT)}: {slot} section fails its parser: {(result.stderr or result.stdout).strip()[-400:]}")
print(f"{len(checked)} distinct declared server sections parsed")


# 4. A broken scenario: the schema and the coupler name the same key.
base_path = os.path.join(ROOT, "tests", "e2e", "scenarios", "open_pile_small.json")
base = json.loads(run("expand", base_path).stdout)[0]


def continuum(d):
    return d["participants"]["continuum"]["config"]


breakages = {
    "run.exchangs": lambda d: d["run"].__setitem__("exchangs", 3),
    "run.deadline_s": lambda d: d["run"].__setitem__("deadline_s", -1),
    "coupling.exchange_interval": lambda d: d["coupling"].__setitem__("exchange_interval", 0),
    "gravity.g_level": lambda d: d["gravity"].__setitem__("g_level", "high"),
    "participants.continuum.config.mesh.zones_radial": lambda d: continuum(d)["mesh"].__setitem__("zones_radial", 0),
    "participants.continuum.config.material.rho_t": lambda d: continuum(d)["material"].__setitem__("rho_t", "x"),
    "participants.continuum.config.damping.local": lambda d: continuum(d).__setitem__("damping", {"local": 2}),
    "participants.continuum.config.boundaries[0].condition": lambda d: continuum(d)["boundaries"][0].__setitem__("condition", "glued"),
}
for expected, breakage in breakages.items():
    broken = copy.deepcopy(base)
    breakage(broken)
    schema_path = deepest_error_path(broken)
    broken_file = os.path.join(WORK, "broken.json")
    with open(broken_file, "w") as f:
        json.dump(broken, f)
    result = run("check", broken_file)
    match = re.search(r"scenario error at (\S+):", result.stderr)
    coupler_path = match.group(1) if match else None
    if result.returncode != 2 or coupler_path != expected or schema_path != expected:
        fail(f"breaking {expected}: coupler exit {result.returncode} at {coupler_path}, schema at {schema_path}")
print(f"{len(breakages)} broken scenarios: schema and coupler name the same key")

# 5. The e2e suite's broken scenarios (tests/e2e/broken/, each naming the key the
# coupler reports in "_expect"): where the schema can see the defect (not a
# missing file or program, a relation between keys, or the DEM section), it
# names the same key.
seen = 0
for path in sorted(glob.glob(os.path.join(ROOT, "tests", "e2e", "broken", "*.json"))):
    try:
        with open(path) as f:
            broken = json.load(f)
    except ValueError:
        continue  # not JSON: nothing for a schema
    expected = broken.get("_expect")
    schema_path = deepest_error_path(broken)
    if expected is None or schema_path is None:
        continue
    seen += 1
    if schema_path != expected:
        fail(f"{os.path.relpath(path, ROOT)}: the coupler names {expected}, the schema {schema_path}")
if seen < 8:
    fail(f"only {seen} of the e2e broken scenarios have a defect the schema sees; expected at least 8")
print(f"{seen} e2e broken scenarios: schema and coupler name the same key")

if failures:
    print(f"{len(failures)} failure(s)")
    sys.exit(1)
print("OK")
