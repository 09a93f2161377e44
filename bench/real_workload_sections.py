#!/usr/bin/python3
"""The real workload's DEM sections, as the coupler sends them to dem_server.

    real_workload_sections.py WORK EXPANDED_SCENARIO_JSON

From `coupler expand scenarios/open_pile_chalk.json` (packing p1): writes
WORK/paper.json (the paper-resolution model, 549 635 spheres), WORK/medium.json
(the same generation, zones and pile in a core 10.5 mm in radius and 9 mm
deep: about 60 000 spheres) and WORK/run.txt (the paper run's penetration,
pile speed and DEM steps besides the jacking's). Used by bench/paper_model.sh
and bench/mpi_scaling.sh.
"""
import json, math, sys
work = sys.argv[1]
scenario = json.load(open(sys.argv[2]))[0]  # packing p1 (REV seed 7)
g = scenario["gravity"]
direction = g.get("direction", [0, 0, -1])
norm = math.sqrt(sum(c * c for c in direction))
section = scenario["participants"]["dem"]["config"]
section["gravity_m_s2"] = [g.get("g_m_s2", 9.81) * g.get("g_level", 1) * c / norm for c in direction]
json.dump(section, open(f"{work}/paper.json", "w"))
# The run's DEM steps besides the jacking's: the ramp and the generation's
# equilibrium before the pile starts (about 1 900 steps in the paper-geometry
# model, docs/dem_generation.md §6); the jacking's own follow from dt.
pile = section["pile"]
speed = math.sqrt(sum(c * c for c in pile["velocity_m_s"]))
with open(f"{work}/run.txt", "w") as out:
    print(scenario["run"]["stop_when"]["at_least"], speed, pile.get("ramp_steps", 0) + 1900, file=out)
# The medium body: the same generation, zones and pile, in a core 10.5 mm in
# radius and 9 mm deep (the fine zone and the next, 63 000 spheres).
section["particles"]["region"].update({"radius_m": 0.0105, "z_min_m": 0.111})
json.dump(section, open(f"{work}/medium.json", "w"))
