"""The parameters each contact law declares, with unit and bounds.

Read from scenario.schema.json, which `./vc schema` generates from the C++
declarations (common/src/sections/, the DEM's law registry) and the test
python.scenario_schema keeps current: the calibrator knows the same names and
bounds as `build/bin/dem_server --help`, without a second copy of them.
"""
import json
import math
import os
from dataclasses import dataclass

from .calibration_file import CalibrationError

ROOT = os.path.abspath(os.path.join(os.path.dirname(os.path.abspath(__file__)), os.pardir, os.pardir))
SCHEMA = os.path.join(ROOT, "scenario.schema.json")

# The bonded laws a calibration may name (dem_bond_laws.md).
BONDED_LAWS = ("soft_bond", "damage_bond", "linear_pbond")


@dataclass(frozen=True)
class Parameter:
    name: str
    unit: str
    lower: float        # inclusive or exclusive, see lower_open
    lower_open: bool
    upper: float
    description: str

    def admits(self, value):
        if math.isnan(value):
            return False
        above = value > self.lower if self.lower_open else value >= self.lower
        return above and value <= self.upper

    def bounds_text(self):
        low = ("(" if self.lower_open else "[") + f"{self.lower:g}"
        return f"{low}, {self.upper:g}]" + ("" if self.unit == "-" else f" {self.unit}")


def declared_laws(schema_path=SCHEMA):
    """{law: {name: Parameter}} of every contact law in the schema."""
    with open(schema_path) as f:
        schema = json.load(f)
    contact = schema["$defs"]["dem.contact"]["else"]
    laws = {}
    for condition in contact["allOf"]:
        law = condition["if"]["properties"].get("law", {}).get("const")
        if law is None:
            continue
        parameters = {}
        for name, p in condition["then"]["properties"].items():
            lower_open = "exclusiveMinimum" in p
            lower = p.get("exclusiveMinimum", p.get("minimum", -math.inf))
            parameters[name] = Parameter(name, p.get("x-unit", "-"), float(lower), lower_open,
                                         float(p.get("maximum", math.inf)), p.get("description", ""))
        laws[law] = parameters
    return laws


def law_parameters(law, schema_path=SCHEMA):
    """{name: Parameter} of one bonded law; a CalibrationError names the laws there are."""
    laws = declared_laws(schema_path)
    if law not in BONDED_LAWS or law not in laws:
        raise CalibrationError("law", f"unknown bonded law '{law}'",
                               f"use one of {', '.join(BONDED_LAWS)} (build/bin/dem_server --help lists them)")
    return laws[law]
