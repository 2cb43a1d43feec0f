#!/usr/bin/python3
"""Writes the square-tube crush deck (tests/data/decks/tube/tube_crush.k).

A square steel tube 50 x 50 x 1.5 mm, 200 mm long, clamped at z = 0 and crushed at z = 200 mm by
a 50 kg *RIGIDWALL_PLANAR_MOVING at 10 m/s: *MAT_PIECEWISE_LINEAR_PLASTICITY with Cowper-Symonds
rate effects (mild steel C 40.4 1/s, P 5), Belytschko-Tsay shells, one
*CONTACT_AUTOMATIC_SINGLE_SURFACE over the tube. The mesh is that of the contact tests
(tests/integration/contact_tube.h): 5 mm around, 5 mm along the coarse part (PID 1), 2 mm along
the 60 mm fine part at the struck end (PID 2), and the same imperfection over the first fold's
half-wavelength (0.15 mm: walls 0 and 2 in, 1 and 3 out). Units mm, t, s.

    /usr/bin/python3 tools/decks/make_tube_deck.py [--end-time S] [--around MM] [--coarse MM]
        [--fine MM] > tube.k
"""
import argparse
import math
import sys


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--end-time", type=float, default=3.0e-3, help="ENDTIM, s (default 3e-3)")
    ap.add_argument("--around", type=float, default=5.0, help="element size around, mm")
    ap.add_argument("--coarse", type=float, default=5.0, help="coarse part's element length, mm")
    ap.add_argument("--fine", type=float, default=2.0, help="fine part's element length, mm")
    a = ap.parse_args()

    C, t, L, L_fine, trigger = 50.0, 1.5, 200.0, 60.0, 0.15
    per_side = round(C / a.around)
    around = 4 * per_side
    Lc = L - L_fine
    nc, nf = round(Lc / a.coarse), round(L_fine / a.fine)
    z = [Lc * k / nc for k in range(nc + 1)] + [Lc + L_fine * k / nf for k in range(1, nf + 1)]
    junction = nc
    H = 0.99 * t ** (1.0 / 3.0) * C ** (2.0 / 3.0)  # W-A half-wavelength
    corner = [(-C / 2, -C / 2), (C / 2, -C / 2), (C / 2, C / 2), (-C / 2, C / 2)]
    outward = [(0, -1), (1, 0), (0, 1), (-1, 0)]

    out = sys.stdout
    w = out.write
    w("*KEYWORD\n")
    w("$ Square tube crush: written by tools/decks/make_tube_deck.py (crashlink, MIT).\n")
    w("$ %s\n" % " ".join(sys.argv[1:]) if len(sys.argv) > 1 else "$ default mesh\n")
    w("*TITLE\nsquare tube crushed by a moving wall\n")
    w("*CONTROL_TERMINATION\n%10.3E\n" % a.end_time)
    w("*DATABASE_GLSTAT\n%10.3E\n*DATABASE_RWFORC\n%10.3E\n" % (1e-5, 1e-5))
    w("*DATABASE_BINARY_D3PLOT\n%10.3E\n" % (a.end_time / 10))
    w("*PART\ntube_coarse\n         1         1         1\n")
    w("*PART\ntube_fine\n         2         1         1\n")
    w("*SECTION_SHELL\n$#   secid    elform      shrf       nip\n"
      "         1         2    0.8333         5\n")
    w("%10.3f%10.3f%10.3f%10.3f\n" % (t, t, t, t))
    w("*MAT_PIECEWISE_LINEAR_PLASTICITY\n$#     mid        ro         e        pr      sigy      etan\n"
      "         1   7.85E-9  210000.0       0.3     200.0\n"
      "$#       c         p      lcss      lcsr        vp\n"
      "      40.4       5.0        10\n")
    w("*DEFINE_CURVE\n        10\n$# plastic strain, yield stress (MPa)\n")
    for e, s in ((0.0, 200.0), (0.1, 300.0), (0.5, 400.0)):
        w("%20.6f%20.6f\n" % (e, s))
    w("*NODE\n")
    nid = 0
    for zk in z:
        for wall in range(4):
            for j in range(per_side):
                f = j / per_side
                x = corner[wall][0] + f * (corner[(wall + 1) % 4][0] - corner[wall][0])
                y = corner[wall][1] + f * (corner[(wall + 1) % 4][1] - corner[wall][1])
                from_top = L - zk
                if from_top < H:
                    sign = -1.0 if wall % 2 == 0 else 1.0
                    amp = sign * trigger * math.sin(math.pi * f) * math.sin(math.pi * from_top / H)
                    x += amp * outward[wall][0]
                    y += amp * outward[wall][1]
                nid += 1
                w("%8d%16.9f%16.9f%16.9f\n" % (nid, x, y, zk))
    w("*ELEMENT_SHELL\n")
    eid = 0

    def node(level, j):
        return level * around + (j % around) + 1

    for k in range(len(z) - 1):
        pid = 1 if k < junction else 2
        for j in range(around):
            eid += 1
            w("%8d%8d%8d%8d%8d%8d\n" % (eid, pid, node(k, j), node(k, j + 1),
                                        node(k + 1, j + 1), node(k + 1, j)))
    w("$ the clamped end (z = 0)\n*DEFINE_BOX\n         1    -100.0     100.0    -100.0"
      "     100.0      -0.1       0.1\n")
    w("*SET_NODE_GENERAL\n         1\nBOX                1\n")
    w("*BOUNDARY_SPC_SET\n         1         0         1         1         1         1"
      "         1         1\n")
    w("$ the wall's nodes: the struck 50 mm (the fine part's, away from its junction)\n"
      "*DEFINE_BOX\n         2    -100.0     100.0    -100.0     100.0     150.0     201.0\n")
    w("*SET_NODE_GENERAL\n         2\nBOX                2\n")
    w("*RIGIDWALL_PLANAR_MOVING_ID\n         1ram\n         2\n")
    w("$#      xt        yt        zt        xh        yh        zh\n")
    w("       0.0       0.0     200.1       0.0       0.0     199.0\n")
    w("$#    mass        v0\n      0.05   10000.0\n")
    w("*CONTACT_AUTOMATIC_SINGLE_SURFACE_ID\n         1self\n")
    w("         0         0         5\n")
    w("       0.0       0.0       0.0\n")
    w("       1.0       1.0\n")
    w("*END\n")


if __name__ == "__main__":
    main()
