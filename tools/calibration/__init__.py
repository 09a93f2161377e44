"""./vc calibrate: find the contact parameters of a bonded law that give a rock's
measured strengths and stiffness (issue 43; docs/calibration_automatic.md).

One concept per module:
  calibration_file    reading and checking CALIBRATION.json (errors name the key and the fix)
  law_parameters      the laws' declared parameters, units and bounds (from scenario.schema.json)
  experiments         the scenario of one experiment on one packing, and what is read back from it
  evaluation_cache    every DEM run's measured values on disk, keyed by what was run (resume)
  evaluation          one parameter set: every experiment on every packing, averaged
  scaling             the dimensionless scaling step (moduli and strengths) from a first evaluation
  search              Nelder-Mead on the rest, in log-parameter space
  sensitivity         log-derivatives of each target to each parameter at the optimum
  outputs             the material file, summary, history and sensitivity (JSON, tables, plots)
"""
