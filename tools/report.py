#!/usr/bin/python3
"""Report PNGs of a crashlink result (called by `crashlink report RESULT.h5 --out DIR`).

    report.py RESULT.h5 OUTDIR [--head HEAD.csv --hic HIC --t1 T1_MS --t2 T2_MS --probe NAME]
                               [--contacts CONTACTS.csv]

HEAD.csv (time_ms,accel_g) is the head's resultant after CFC 1000, written by the C++ side
(solver/signal/head_metrics.h: one filter implementation); HIC, T1, T2 its HIC15 and window.
CONTACTS.csv (contact,filter,time_ms,force_kN) is each contact's resultant force after CFC 180
per axis, also written by the C++ side (apps/contact_force_csv.h).
Writes, each only when the file holds the data:
  head_acceleration.png  acceleration (g) against time (ms), HIC15 window shaded, value written
  energy.png             glstat energies (J), each interface's contact energy in a panel of
                         its own (/history/contacts/<name>/energy, J; below zero: energy the
                         contact created; files before 2026-11-26 have none) and the energy
                         balance error (%)
  interface_drift.png    /coupling/<interface>/displacement_gap (m) and velocity_jump (m/s)
  contact_forces.png     |force| (kN) of every /history/contacts/<name>: after CFC 180 from
                         CONTACTS.csv (the raw samples faint behind), unfiltered without it
and prints the path of each file written. Needs python3-matplotlib and python3-h5py (Debian).
"""
import argparse
import csv
import os
import sys

import h5py
import matplotlib
import numpy as np

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def name_of(group, default):
    """A group's user name (attribute "name", written by crashlink), else its link name."""
    label = group.attrs.get("name", default)
    return label.decode() if isinstance(label, bytes) else str(label)


def save(fig, path):
    fig.tight_layout()
    fig.savefig(path, dpi=120)
    plt.close(fig)
    print(path)


def head_plot(args, out, title):
    data = np.loadtxt(args.head, delimiter=",", skiprows=1, ndmin=2)
    t, a = data[:, 0], data[:, 1]
    fig, ax = plt.subplots(figsize=(8, 4.5))
    ax.plot(t, a, lw=1.2, label=f"probe '{args.probe}', CFC 1000")
    if args.t2 > args.t1:
        ax.axvspan(args.t1, args.t2, color="tab:orange", alpha=0.25,
                   label=f"HIC15 window {args.t1:.2f}-{args.t2:.2f} ms")
    ax.set_xlabel("time [ms]")
    ax.set_ylabel("resultant acceleration [g]")
    ax.set_title(f"{title}: HIC15 = {args.hic:.1f}, peak {a.max():.1f} g")
    ax.grid(alpha=0.3)
    ax.legend()
    save(fig, os.path.join(out, "head_acceleration.png"))


def interface_energies(f):
    """[(label, time_ms, energy_J)] of every /history/contacts/<name>/energy (none in files
    written before the dataset existed)."""
    out = []
    for name, c in contacts_of(f).items():
        if "energy" not in c or "time" not in c:
            continue
        k = min(len(c["time"]), len(c["energy"]))
        if k > 0:
            out.append((name_of(c, name), c["time"][:k] * 1e3, c["energy"][:k]))
    return out


def energy_plot(f, out, title):
    g = f["history/glstat"]
    t = g["time"][:] * 1e3
    interfaces = interface_energies(f)
    # Each interface's own contact energy (sleout) gets a panel of its own: a few J beside a
    # model's hundreds would not show; below zero, the contact created energy.
    rows = 3 if interfaces else 2
    fig, axes = plt.subplots(rows, 1, figsize=(8, 8.5 if interfaces else 6.5), sharex=True,
                             gridspec_kw={"height_ratios": [3, 1.6, 1] if interfaces else [3, 1]})
    ax, bx = axes[0], axes[-1]
    for key in ("kinetic_energy", "internal_energy", "hourglass_energy", "contact_energy",
                "external_work", "coupling_work", "total_energy"):
        if key in g:
            ax.plot(t, g[key][:], lw=1.8 if key == "total_energy" else 1.0,
                    label=key.replace("_", " "))
    created = []
    if interfaces:
        cx = axes[1]
        cx.axhline(0.0, color="k", lw=0.6)
        for label, tc, e in interfaces:
            text = f"'{label}'"
            if e[-1] < 0.0:
                created.append(f"'{label}' created {-e[-1]:.3g} J")
                text += f", created {-e[-1]:.3g} J"
            cx.plot(tc, e, lw=1.0, label=text)
        cx.set_ylabel("contact energy\nper interface [J]")
        cx.grid(alpha=0.3)
        cx.legend(fontsize=8)
    ax.set_ylabel("energy [J]")
    ax.set_title(f"{title}: energy balance" +
                 (f"\ncontact {', '.join(created)} (below zero: energy the contact created)"
                  if created else ""), fontsize=10 if created else None)
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8)
    bx.plot(t, 100.0 * g["energy_balance_error"][:], color="k", lw=1.0)
    bx.set_ylabel("balance error [%]")
    bx.set_xlabel("time [ms]")
    bx.grid(alpha=0.3)
    save(fig, os.path.join(out, "energy.png"))


def drift_plot(f, out, title):
    if "coupling" not in f or len(f["coupling"]) == 0:
        return
    fig, (ax, bx, cx) = plt.subplots(3, 1, figsize=(8, 8), sharex=True)
    schemes = set()
    for name, g in f["coupling"].items():
        label = name_of(g, name)
        scheme = g.attrs.get("scheme", b"layer")
        schemes.add(scheme.decode() if isinstance(scheme, bytes) else str(scheme))
        t = g["time"][:] * 1e3
        if "displacement_gap" in g:
            ax.plot(t, g["displacement_gap"][:], lw=1.0, label=label)
        if "velocity_jump" in g:
            bx.plot(t, g["velocity_jump"][:], lw=1.0, label=label)
        if "link_work" in g:
            cx.plot(t, g["link_work"][:], lw=1.0, label=f"{label}: link work")
        if "drift_work" in g:
            cx.plot(t, g["drift_work"][:], lw=1.0, ls="--", label=f"{label}: drift work")
    ax.set_ylabel("displacement gap [m]")
    # The subtitle says what the gap means for the scheme the run used (the groups' attribute).
    if schemes == {"paper"}:
        note = "paper: gap between a node's two presences"
    else:
        note = "layer: J is one set of dofs, gap 0 by construction"
    ax.set_title(f"{title}: interface drift ({note})")
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8)
    bx.set_ylabel("velocity jump [m/s]")
    bx.grid(alpha=0.3)
    cx.set_ylabel("coupling work [J]")
    cx.set_xlabel("time [ms]")
    cx.grid(alpha=0.3)
    cx.legend(fontsize=8)
    save(fig, os.path.join(out, "interface_drift.png"))


def contacts_of(f):
    """The /history/contacts groups by link name ({} if the file has none)."""
    if "history/contacts" not in f:
        return {}
    return dict(f["history/contacts"].items())


def read_contact_csv(path):
    """{contact name: (filter, time_ms[], force_kN[])} of a CONTACTS.csv."""
    rows = {}
    if not path:
        return rows
    with open(path, newline="") as fh:
        for r in csv.DictReader(fh):
            entry = rows.setdefault(r["contact"], (r["filter"], [], []))
            entry[1].append(float(r["time_ms"]))
            entry[2].append(float(r["force_kN"]))
    return rows


def contact_plot(f, out, title, contacts_csv):
    groups = contacts_of(f)
    if not groups:
        return
    filtered = read_contact_csv(contacts_csv)
    fig, ax = plt.subplots(figsize=(8, 4.5))
    filters = set()
    for name, g in groups.items():
        label = name_of(g, name)
        t_ms = g["time"][:] * 1e3
        k = min(len(t_ms), len(g["force"]))
        raw_kN = np.linalg.norm(g["force"][:k], axis=1) * 1e-3
        if label in filtered and filtered[label][0] != "none":
            how, t_f, f_kN = filtered[label]
            filters.add(how)
            line, = ax.plot(t_f, f_kN, lw=1.2, label=f"{label}, {how}")
            ax.plot(t_ms[:k], raw_kN, lw=0.6, alpha=0.25, color=line.get_color())
        else:
            filters.add("unfiltered")
            ax.plot(t_ms[:k], raw_kN, lw=1.0, label=f"{label}, unfiltered")
    if filters == {"unfiltered"}:
        how = "unfiltered (`crashlink report` filters them with CFC 180)"
    else:
        how = ("SAE J211/1 " + ", ".join(sorted(filters)) +
               " per axis (4-pole zero-phase Butterworth), resultant after; raw samples faint")
    ax.set_xlabel("time [ms]")
    ax.set_ylabel("contact force |F| on the slave side [kN]")
    ax.set_title(f"{title}: contact forces\n{how}", fontsize=10)
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8)
    save(fig, os.path.join(out, "contact_forces.png"))


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("result")
    p.add_argument("out")
    p.add_argument("--head")
    p.add_argument("--probe", default="")
    p.add_argument("--hic", type=float, default=0.0)
    p.add_argument("--t1", type=float, default=0.0)
    p.add_argument("--t2", type=float, default=0.0)
    p.add_argument("--contacts", help="CSV contact,filter,time_ms,force_kN (filtered forces)")
    args = p.parse_args()
    os.makedirs(args.out, exist_ok=True)
    with h5py.File(args.result, "r") as f:
        title = os.path.basename(os.path.dirname(os.path.abspath(args.result))) or args.result
        if args.head:
            head_plot(args, args.out, title)
        energy_plot(f, args.out, title)
        drift_plot(f, args.out, title)
        contact_plot(f, args.out, title, args.contacts)
    return 0


if __name__ == "__main__":
    sys.exit(main())
