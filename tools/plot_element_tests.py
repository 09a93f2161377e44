#!/usr/bin/env python3
"""Plot the FDM constitutive models' element tests (the CSVs of fdm_element_tests).

    plot_element_tests.py CSV_DIR --out DIR

Writes, for each model (mohr_coulomb, chalk_snw), <model>_element_tests.png with
four panels: deviatoric stress q against axial strain (drained triaxial),
volumetric strain against axial strain (compression positive), the stress
paths in q-p' (triaxial and oedometer), and the oedometer's axial and lateral
stresses against axial strain. Prints the path of every file written.

Regenerate docs/figures/: build/bin/fdm_element_tests --out build/element_tests &&
    /usr/bin/python3 tools/plot_element_tests.py build/element_tests --out docs/figures
"""
import argparse
import glob
import os
import sys

try:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    import numpy as np
except ImportError as missing:  # pragma: no cover - depends on the machine
    sys.exit(f"plot_element_tests.py needs numpy and matplotlib: {missing}")

TITLES = {"mohr_coulomb": "Mohr-Coulomb (E = 100 MPa, c = 20 kPa, phi = 30 deg, psi = 10 deg)",
          "chalk_snw": "Structured Cam Clay, preset chalk_snw (Ciantia et al. 2024 Table 2)"}


def read(path):
    return np.genfromtxt(path, delimiter=",", names=True)


def plot_model(model, files, out_dir):
    figure, ((q_axes, v_axes), (path_axes, oedo_axes)) = plt.subplots(2, 2, figsize=(10, 7.5))
    for path in sorted(files):
        data = read(path)
        name = os.path.basename(path)[len(model) + 1:-4]
        strain = 100 * data["axial_strain"]
        if name.startswith("triaxial"):
            label = "triaxial, sigma3 = " + name.split("_")[1].replace("kpa", " kPa")
            q_axes.plot(strain, data["q_pa"] / 1e3, label=label)
            v_axes.plot(strain, 100 * data["volumetric_strain"], label=label)
            path_axes.plot(data["p_pa"] / 1e3, data["q_pa"] / 1e3, label=label)
        else:
            path_axes.plot(data["p_pa"] / 1e3, data["q_pa"] / 1e3, "k--", label="oedometer")
            oedo_axes.plot(strain, data["sigma_axial_pa"] / 1e3, label="axial stress")
            oedo_axes.plot(strain, data["sigma_lateral_pa"] / 1e3, label="lateral stress")
    q_axes.set(xlabel="axial strain [%]", ylabel="q [kPa]", title="drained triaxial")
    v_axes.set(xlabel="axial strain [%]", ylabel="volumetric strain [%] (compression +)", title="drained triaxial")
    path_axes.set(xlabel="p' [kPa]", ylabel="q [kPa]", title="stress paths")
    oedo_axes.set(xlabel="axial strain [%]", ylabel="stress [kPa] (compression +)", title="oedometer")
    for axes in (q_axes, v_axes, path_axes, oedo_axes):
        axes.grid(True, alpha=0.3)
        axes.legend(fontsize=8)
    figure.suptitle(TITLES.get(model, model))
    figure.tight_layout()
    out = os.path.join(out_dir, f"{model}_element_tests.png")
    figure.savefig(out, dpi=110)
    plt.close(figure)
    print(out)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("csv_dir")
    parser.add_argument("--out", required=True)
    args = parser.parse_args()
    os.makedirs(args.out, exist_ok=True)
    for model in TITLES:
        files = glob.glob(os.path.join(args.csv_dir, f"{model}_*.csv"))
        if not files:
            sys.exit(f"no {model}_*.csv in {args.csv_dir}; run fdm_element_tests --out {args.csv_dir} first")
        plot_model(model, files, args.out)


if __name__ == "__main__":
    main()
