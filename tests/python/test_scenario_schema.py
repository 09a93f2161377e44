"""scenario.schema.json against the declarations and the shipped scenarios.

Usage: test_scenario_schema.py COUPLER REPOSITORY_ROOT WORK_DIR

1. The committed scenario.schema.json is what `coupler schema` generates from
   the declarations (regenerate: ./vc schema), and a valid draft 2020-12 schema.
2. Every shipped scenario (scenarios/, tests/e2e/scenarios/), as the coupler
   reads it (`coupler expand`: includes resolved, one document per variant),
   validates with an independent validator (Debian's python3-jsonschema);
   so do the same files as written (as an editor checks them) and the
   scenarios in the code blocks of README.md and docs/*.md.
3. Each server section of each shipped scenario passes the server's own
   parser (`dem_server --check-config`, `fdm_server --check-config`): a parser
   that reads a key its declaration lacks fails there (std::logic_error, exit 1).
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


def dotted(parts):
    path = ""
    for part in parts:
        path += f"[{part}]" if isinstance(part, int) else (("." if path else "") + part)
    return path


def deepest_error_paths(document):
    """The key paths of the deepest schema errors, dotted as the coupler writes them; empty if valid.

    A key given under a wrong name is both an unknown key and a missing
    required one at the same depth: the schema reports both, the coupler the
    first it meets, so the test asks that the coupler's path be among them."""
    paths = []
    for error in validator.iter_errors(document):
        parts = list(error.absolute_path)
        # Unknown keys are reported at their object; the coupler names the key
        # itself. (Where a variant's keys fail, e.g. one missing, the validator
        # drops that variant's annotations and lists its valid keys here too.)
        if error.validator == "unevaluatedProperties":
            keys = re.findall(r"'([^']+)'", error.message.split("were unexpected")[0].split("was unexpected")[0])
            paths += [parts + [key] for key in keys]
            continue
        # A missing key is reported at its object; the coupler names the key.
        if error.validator == "required":
            parts += re.findall(r"'([^']+)' is a required property", error.message)[:1]
        paths.append(parts)
    if not paths:
        return set()
    depth = max(len(p) for p in paths)
    return {dotted(p) for p in paths if len(p) == depth}


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
        if where := deepest_error_paths(document):
            fail(f"{os.path.relpath(path, ROOT)} ({document['name']}): schema error at {where}")
print(f"{len(documents)} scenario documents from {len(files)} files validated")

# 2b. The same files as written, as an editor sees them: an object that
# includes a file may leave its required keys to it, and null removes a key
# of the included file (JSON Merge Patch), e.g. "variants": null.
for path in files:
    with open(path) as f:
        document = json.load(f)
    if where := deepest_error_paths(document):
        fail(f"{os.path.relpath(path, ROOT)} as written: schema error at {where}")
print(f"{len(files)} scenario files validated as written")


def documented_scenarios():
    """(where, text) of each scenario in a code block of README.md and docs/*.md.

    A block is a scenario when its text is one JSON object (it starts with '{')
    and it is fenced as json, or when it parses as an object with a key only a
    scenario's top level has ("schema_version", "participants", "include",
    "variants"), whatever its fence. Fragments of a section ("walls": [...])
    are not objects; an outline with elided sections is fenced as text, not
    json, since it is not JSON. A calibration file (tools/calibrate.py: a
    "law" and "targets" at its top level, docs/calibration_automatic.md) is
    not a scenario; python.calibration checks those."""
    fence = re.compile(r"^([ \t]*)```(\w*)[ \t]*\n(.*?)^\1```", re.S | re.M)
    for page in [os.path.join(ROOT, "README.md")] + sorted(glob.glob(os.path.join(ROOT, "docs", "*.md"))):
        with open(page) as f:
            text = f.read()
        for block in fence.finditer(text):
            language, body = block.group(2), block.group(3)
            where = f"{os.path.relpath(page, ROOT)}:{text.count(chr(10), 0, block.start()) + 1}"
            try:
                value = json.loads(body)
            except ValueError:
                value = None
            if isinstance(value, dict) and {"law", "targets"} <= value.keys():
                continue
            if language == "json" and body.lstrip().startswith("{"):
                yield where, value
            elif isinstance(value, dict) and value.keys() & {"schema_version", "participants", "include", "variants"}:
                yield where, value


documented = 0
for where, document in documented_scenarios():
    documented += 1
    if document is None:
        fail(f"{where}: a json block that opens an object is not JSON (fence an outline as text)")
    elif paths := deepest_error_paths(document):
        fail(f"{where}: schema error at {paths}")
if documented < 1:
    fail("no scenario found in the code blocks of README.md and docs/")
print(f"{documented} scenarios in the docs' code blocks validated as written")

# 3. Declared server sections pass their parsers (`<server> --check-config`: the
# parser alone, without building the model).
declared_programs = {"fdm_server", "dem_server"}
checked = set()
for path, document in documents:
    for slot, participant in document["participants"].items():
        program = os.path.basename(participant.get("program", ""))
        if program not in declared_programs:
            continue
        config = json.dumps(participant["config"], sort_keys=True)
        if (program, config) in checked:
            continue
        checked.add((program, config))
        section_file = os.path.join(WORK, f"section_{len(checked)}.json")
        with open(section_file, "w") as f:
            f.write(config)
        result = subprocess.run([os.path.join(os.path.dirname(COUPLER), program), "--check-config", section_file],
                                capture_output=True, text=True, timeout=120)
        if result.returncode != 0:
            fail(f"{os.path.relpath(path, ROOT)}: {slot} section fails its parser: {(result.stderr or result.stdout).strip()[-400:]}")
for program in sorted(declared_programs):
    count = sum(1 for p, _ in checked if p == program)
    print(f"{count} distinct {program} sections parsed")
    if count < 5:
        fail(f"only {count} {program} sections in the shipped scenarios; expected at least 5")


# 4. A broken scenario: the schema and the coupler name the same key.
base_path = os.path.join(ROOT, "tests", "e2e", "scenarios", "open_pile_small.json")
base = json.loads(run("expand", base_path).stdout)[0]


def continuum(d):
    return d["participants"]["continuum"]["config"]


def dem(d):
    return d["participants"]["dem"]["config"]


breakages = {
    "run.exchangs": lambda d: d["run"].__setitem__("exchangs", 3),
    "run.deadline_s": lambda d: d["run"].__setitem__("deadline_s", -1),
    "coupling.exchange_interval": lambda d: d["coupling"].__setitem__("exchange_interval", 0),
    "gravity.g_level": lambda d: d["gravity"].__setitem__("g_level", "high"),
    "participants.continuum.config.mesh.zones_radial": lambda d: continuum(d)["mesh"].__setitem__("zones_radial", 0),
    "participants.continuum.config.material.rho_t": lambda d: continuum(d)["material"].__setitem__("rho_t", "x"),
    "participants.continuum.config.damping.local": lambda d: continuum(d).__setitem__("damping", {"local": 2}),
    "participants.continuum.config.boundaries[0].condition": lambda d: continuum(d)["boundaries"][0].__setitem__("condition", "glued"),
    "participants.dem.config.particles.density_kg_m3": lambda d: dem(d)["particles"].__setitem__("density_kg_m3", -2000),
    "participants.dem.config.particles.zones[1].scale_factor": lambda d: dem(d)["particles"]["zones"][1].__setitem__("scale_factor", 0),
    "participants.dem.config.pile.sides": lambda d: dem(d)["pile"].__setitem__("sides", 2),
    "participants.dem.config.pile.radius": lambda d: dem(d)["pile"].__setitem__("radius", 0.004),
    "participants.dem.config.walls[0].type": lambda d: dem(d)["walls"][0].__setitem__("type", "sphere"),
    "participants.dem.config.contact.friction": lambda d: dem(d)["contact"].__setitem__("friction", -1),
    "participants.dem.config.damping.local": lambda d: dem(d).__setitem__("damping", {"local": 1.5}),
}
for expected, breakage in breakages.items():
    broken = copy.deepcopy(base)
    breakage(broken)
    schema_paths = deepest_error_paths(broken)
    broken_file = os.path.join(WORK, "broken.json")
    with open(broken_file, "w") as f:
        json.dump(broken, f)
    result = run("check", broken_file)
    match = re.search(r"scenario error at (\S+):", result.stderr)
    coupler_path = match.group(1) if match else None
    if result.returncode != 2 or coupler_path != expected or expected not in schema_paths:
        fail(f"breaking {expected}: coupler exit {result.returncode} at {coupler_path}, schema at {sorted(schema_paths)}")
print(f"{len(breakages)} broken scenarios: schema and coupler name the same key")

# 5. The e2e suite's broken scenarios (tests/e2e/broken/, each naming the key the
# coupler reports in "_expect"): where the schema can see the defect (not a
# missing file or program, or a relation between keys), it
# names the same key.
seen = 0
for path in sorted(glob.glob(os.path.join(ROOT, "tests", "e2e", "broken", "*.json"))):
    try:
        with open(path) as f:
            broken = json.load(f)
    except ValueError:
        continue  # not JSON: nothing for a schema
    expected = broken.get("_expect")
    schema_paths = deepest_error_paths(broken)
    if expected is None or not schema_paths:
        continue
    seen += 1
    if expected not in schema_paths:
        fail(f"{os.path.relpath(path, ROOT)}: the coupler names {expected}, the schema {sorted(schema_paths)}")
if seen < 8:
    fail(f"only {seen} of the e2e broken scenarios have a defect the schema sees; expected at least 8")
print(f"{seen} e2e broken scenarios: schema and coupler name the same key")

if failures:
    print(f"{len(failures)} failure(s)")
    sys.exit(1)
print("OK")
