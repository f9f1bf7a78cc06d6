#!/usr/bin/python3
"""The layered 1D strip (prm/layered_1d.prm, case (b)) at t = 240: the naive
flux against the interface-aware one, and the work-precision chart.

    contrib/layered_study.py BUILD_DIR OUT_DIR REFERENCE_MODES_CSV [--quick]

Configurations: naive = local Lax-Friedrichs on (eps, m) with the
componentwise minmod limiter (the direct implementation of section 2.1 of the
central-upwind paper on layered elasticity);
aware = the impedance (linearised Godunov) flux with the minmod limiter on
the flux variables (sigma, u) in every cell; aware-indicator = the same
limiter in the cells the modal-energy indicator flags (Limiter/indicator =
modal_energy, as prm/layered_1d.prm ships); aware-nolim = the impedance flux
without a limiter. Degrees 1-3 on 2, 4, 8, 16, 32 cells per layer (p times cells per
layer at most 32, the reference's resolution), CFL 0.8/(2p+1) (SSP-RK3
DG is stable to about 1/(2p+1)).
For every run: the L1 error of the strain against the reference (a
modes-NNNN.csv of a finer run, e.g. P3 with 32 cells per layer), the largest
stress jump across a material interface, the position of the leading stress
peak against the reference's, and the CPU time of the time loop. Writes
OUT_DIR/layered-study.csv and OUT_DIR/layered-work-precision.png.

    --only aware-indicator --rows-from doc/figures/layered_study.csv

runs one configuration and takes the others' rows from an earlier study.
"""
import argparse
import csv
import glob
import json
import os
import subprocess

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np

# name: (numerical flux, limiter, troubled-cell indicator)
CONFIGS = {
    "aware": ("impedance", "flux_variables", "everywhere"),
    "aware-indicator": ("impedance", "flux_variables", "modal_energy"),
    "aware-nolim": ("impedance", "none", "everywhere"),
    "naive": ("local_lax_friedrichs", "componentwise", "everywhere"),
}


def leading_peak(directory):
    """x of the largest stress maximum in the leading 40 length units."""
    path = sorted(glob.glob(os.path.join(directory, "profile-*.csv")))[-1]
    with open(path) as f:
        f.readline()
        header = f.readline().strip().split(",")
    d = np.loadtxt(path, delimiter=",", skiprows=2, ndmin=2)
    x, s = d[:, 0], d[:, header.index("stress")]
    front = x[np.nonzero(np.abs(s) > 1e-3 * np.max(np.abs(s)))[0][-1]]
    near = x > front - 40
    return x[near][np.argmax(s[near])]


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("build")
    p.add_argument("out")
    p.add_argument("reference")
    p.add_argument("--quick", action="store_true", help="degree 2, 4 and 8 cells per layer only")
    p.add_argument("--only", help="comma-separated configurations to run (default: all)")
    p.add_argument("--rows-from", help="an earlier layered-study.csv: the rows of the configurations not run")
    a = p.parse_args()
    run = a.only.split(",") if a.only else list(CONFIGS)
    for name in run:
        if name not in CONFIGS:
            p.error("--only: unknown configuration '%s' (allowed: %s)" % (name, ", ".join(CONFIGS)))
    here = os.path.dirname(os.path.abspath(__file__))
    prm = os.path.join(here, "..", "prm", "layered_1d.prm")
    ref_dir = os.path.dirname(os.path.abspath(a.reference))
    x_ref = leading_peak(ref_dir)
    degrees = (2,) if a.quick else (1, 2, 3)
    resolutions = (4, 8) if a.quick else (2, 4, 8, 16, 32)
    rows = []
    if a.rows_from:
        with open(a.rows_from) as f:
            rows = [{k: v if k in ("config", "flux", "limiter", "indicator") else
                     int(v) if k in ("degree", "cells_per_layer", "n_dofs") else float(v) for k, v in r.items()}
                    for r in csv.DictReader(f) if r["config"] not in run]
        for r in rows:
            r.setdefault("indicator", "everywhere")
    for name in run:
        flux, limiter, indicator = CONFIGS[name]
        for degree in degrees:
            for per_layer in resolutions:
                if degree * per_layer > 32:
                    continue  # as fine as the reference (P3 at 32 cells per layer) or finer
                d = os.path.join(a.out, "%s-p%d-%d" % (name, degree, per_layer))
                if not os.path.exists(os.path.join(d, "summary.json")):
                    subprocess.run([os.path.join(a.build, "granular_dg"), prm,
                                    "--set", "Output/directory=" + d, "--set", "Output/overwrite=true",
                                    "--set", "Output/output times=", "--set", "Output/write vtu=false",
                                    "--set", "Output/progress interval=0",
                                    "--set", "Mesh/cells x=%d" % (300 * per_layer),
                                    "--set", "Discretization/degree=%d" % degree,
                                    "--set", "Discretization/numerical flux=" + flux,
                                    "--set", "Limiter/scheme=" + limiter,
                                    "--set", "Limiter/indicator=" + indicator,
                                    "--set", "Time stepping/CFL number=%g" % (0.8 / (2 * degree + 1)),
                                    "--set", "Exact solution/reference file=" + os.path.abspath(a.reference)],
                                   check=True, stdout=subprocess.DEVNULL)
                with open(os.path.join(d, "summary.json")) as f:
                    s = json.load(f)
                rows.append({"config": name, "flux": flux, "limiter": limiter,
                             "indicator": indicator, "degree": degree,
                             "cells_per_layer": per_layer, "n_dofs": s["n_dofs"],
                             "l1_strain_error": s["errors"]["component_0_l1_l2_linf"][0],
                             "interface_stress_jump_max": s["diagnostics"]["interface_stress_jump_max"],
                             "min_strain": s["diagnostics"]["min_strain"],
                             "leading_peak_shift": leading_peak(d) - x_ref,
                             "time_loop_cpu_s": s["time_loop_cpu_s"],
                             "dof_updates_per_cpu_s": s["dof_updates_per_cpu_s_per_rank"]})
                print(rows[-1], flush=True)
    os.makedirs(a.out, exist_ok=True)
    with open(os.path.join(a.out, "layered-study.csv"), "w") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[-1].keys()))
        w.writeheader()
        w.writerows(rows)

    fig, ax = plt.subplots(figsize=(7, 5))
    styles = {"naive": "s--", "aware": "o-", "aware-indicator": "D-.", "aware-nolim": "^:"}
    for name in CONFIGS:
        for degree in degrees:
            sel = [r for r in rows if r["config"] == name and r["degree"] == degree and
                   r["l1_strain_error"] > 0]
            if sel:
                ax.loglog([r["time_loop_cpu_s"] for r in sel], [r["l1_strain_error"] for r in sel],
                          styles[name], label="%s P%d" % (name, degree))
    # Clawpack's second-order f-wave finite volumes on the same case (doc/layered.md)
    ax.loglog([1, 5], [0.09, 0.04], "k*", ms=12, label="Clawpack f-wave")
    ax.set_xlabel("CPU time of the time loop [s]")
    ax.set_ylabel("L1 error of the strain at t = 240")
    ax.set_title("layered 1D strip: error against the reference vs CPU time")
    ax.grid(alpha=0.3, which="both")
    ax.legend(fontsize=7, ncol=2)
    fig.tight_layout()
    fig.savefig(os.path.join(a.out, "layered-work-precision.png"), dpi=110)


if __name__ == "__main__":
    main()
