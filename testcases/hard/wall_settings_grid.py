#!/usr/bin/env python3
"""Issue 12's grid of settings on sdnd122's wall, through the aster-nl binary.

    python3 testcases/hard/wall_settings_grid.py [--bin target/release/aster-nl] [--quick]
        [--approx SERIE|PADE] [--resolution "KEY=VALUE, ..."]

One DOF (m = 1, k = 10, JEU = 0.01, PLAN stop RIGI_NOR = 50 = 5 k), started from the linear
mode, DIR_EVOLUTION = -1, NB_PAS_MAN = 1, NB_BRANCHE = 400 and ENER_MAX = 5 E_c (E_c = k JEU^2/2,
the first-contact energy), every other keyword at its catalog default, over
PREC_MAN x COEF_AMPL x PARA_REGUL x (NB_HARM_LINE, NB_HARM_NONL). Each run is one .comm file
written to a temporary directory and run with `aster-nl run`; the table MNL is read back from
its database.

Verdict of a run:
- right: exit 0, the last row at or past 5 E_c, and every row's FREQUENCE within BOUND of the
  exact frequency of the regularised law at its ENERGIE (computed here, independently of the
  engine, by quadrature of the period integral with the law's potential in closed form);
  the regularisation's own departure from the nonsmooth (penalty) frequency of docs/ehman.md
  section 5 is that of PARA_REGUL, not of the run, and is printed beside it (5.0e-3 at
  grazing for PARA_REGUL 1e-3, 1.9e-4 for 1e-5, 3.7e-6 for 1e-7);
- stopped: exit 2 with an error (its keyword printed);
- WRONG: exit 0 but a row off the exact curve, or 5 E_c not reached.
BOUND = 2e-3 relative: the truncation to NB_HARM_LINE harmonics (measured on main 302d4fb,
H 10/30: worst error of the right runs 2.8e-4; the wrong families are off by 8e-2 to
1.9e-1).
"""

import argparse
import math
import os
import shutil
import sqlite3
import subprocess
import sys
import tempfile
import time

HERE = os.path.dirname(os.path.abspath(__file__))
M, K, G, ALPHA = 1.0, 10.0, 0.01, 50.0
E_C = 0.5 * K * G * G
BOUND = 2e-3

TEMPLATE = """DEBUT(CODE=_F(NIV_PUB_WEB='INTERNET'), IGNORE_ALARM=('MODE_NON_LINE_1',))
MAIL = LIRE_MAILLAGE(FORMAT='ASTER', UNITE=20)
MODELE = AFFE_MODELE(MAILLAGE=MAIL,
                     AFFE=_F(GROUP_MA=('M1', 'P2'), PHENOMENE='MECANIQUE',
                             MODELISATION='DIS_T'))
CARA = AFFE_CARA_ELEM(MODELE=MODELE,
                      DISCRET=(_F(CARA='M_T_D_N', GROUP_MA='P2', VALE=1.0),
                               _F(CARA='K_T_D_N', GROUP_MA='P2', VALE=(0., 0., 0.)),
                               _F(CARA='K_T_D_L', GROUP_MA='M1', VALE=(10., 0., 0.),
                                  REPERE='GLOBAL'),))
CL = AFFE_CHAR_CINE(MODELE=MODELE,
                    MECA_IMPO=(_F(GROUP_NO='N1', DX=0., DY=0., DZ=0.),
                               _F(GROUP_NO='N2', DY=0., DZ=0.),))
ASSEMBLAGE(MODELE=MODELE, CARA_ELEM=CARA, CHAR_CINE=CL, NUME_DDL=CO('NUMEDDL'),
           MATR_ASSE=(_F(MATRICE=CO('RIGIDITE'), OPTION='RIGI_MECA'),
                      _F(MATRICE=CO('MASSE'), OPTION='MASS_MECA'),),)
MODES = CALC_MODES(MATR_RIGI=RIGIDITE, MATR_MASS=MASSE, OPTION='PLUS_PETITE',
                   CALC_FREQ=_F(NMAX_FREQ=1))
MNL = MODE_NON_LINE(MATR_RIGI=RIGIDITE, MATR_MASS=MASSE,
                    ETAT_INIT=_F(MODE_LINE=MODES, NUME_ORDRE=1, DIR_EVOLUTION=-1,
                                 COEF_AMPL={coef}),
                    CHOC=_F(OBSTACLE='PLAN', GROUP_NO='N2', NOM_CMP='DX', JEU=0.01,
                            RIGI_NOR=50., PARA_REGUL={regul}),
                    RESOLUTION=_F(METHODE='EHMAN', NB_HARM_LINE={hl}, NB_HARM_NONL={hn},
                                  PREC_MAN={prec}, NB_BRANCHE=400, NB_PAS_MAN=1,
                                  ENER_MAX={emax}, APPROX_MAN='{approx}'{extra}),
                    INFO=1)
FIN()
"""


def period_plan(e):
    """Exact period of the penalty stop (eta -> 0, all harmonics) at total energy e."""
    w0 = math.sqrt(K / M)
    b = math.sqrt(2.0 * e / K)
    if b <= G:
        return 2.0 * math.pi / w0
    w1 = math.sqrt((K + ALPHA) / M)
    uc = ALPHA * G / (K + ALPHA)
    disc = (ALPHA * G) ** 2 - (K + ALPHA) * (ALPHA * G * G - 2.0 * e)
    a = (ALPHA * G + math.sqrt(disc)) / (K + ALPHA)
    return 2.0 * (math.pi - math.acos(G / b)) / w0 + 2.0 * math.acos((G - uc) / (a - uc)) / w1


def regularised_potential(u, eta):
    """k u^2/2 plus the work of the PLAN law's physical root f = (a d + sqrt(a^2 d^2 + 4 a eta))/2,
    d = u - JEU, a = RIGI_NOR (f^2 - a f d - a eta = 0, docs/ehman.md section 2), from 0 to u."""
    b = 4.0 * ALPHA * eta

    def p(d):
        q = math.sqrt(ALPHA * ALPHA * d * d + b)
        return ALPHA * d * d / 4.0 + 0.5 * (0.5 * d * q + b / (2.0 * ALPHA) * math.asinh(ALPHA * d / math.sqrt(b)))

    return 0.5 * K * u * u + p(u - G) - p(-G)


def bisect(fun, a, b):
    fa = fun(a)
    for _ in range(200):
        m = 0.5 * (a + b)
        fm = fun(m)
        if (fm > 0) == (fa > 0):
            a, fa = m, fm
        else:
            b = m
    return 0.5 * (a + b)


def period_regularised(e, regul, n=2000):
    """Exact period of the regularised law (all harmonics) at total energy e: 2 x the integral
    of du / sqrt(2 (e - V(u)) / m) between the turning points, u = u_min + (u_max - u_min)
    (1 - cos th) / 2 (midpoints in th: the endpoint singularities vanish). eta =
    PARA_REGUL k_ref JEU^2 (docs/nnm.md), k_ref = k here. Agrees with period_plan to 1e-9 at
    PARA_REGUL 1e-9 (measured)."""
    eta = regul * K * G * G
    umax = bisect(lambda u: regularised_potential(u, eta) - e, 0.0, 10.0 * G)
    umin = bisect(lambda u: regularised_potential(u, eta) - e, -10.0 * G, 0.0)
    tot = 0.0
    for i in range(n):
        th = (i + 0.5) * math.pi / n
        u = umin + (umax - umin) * (1.0 - math.cos(th)) / 2.0
        du = (umax - umin) * math.sin(th) / 2.0
        tot += du / math.sqrt(max(2.0 * (e - regularised_potential(u, eta)) / M, 1e-300))
    return 2.0 * tot * math.pi / n


def run_one(binary, work, hl, hn, regul, prec, coef, approx, extra=""):
    name = f"h{hl}_{hn}_r{regul:.0e}_p{prec:.0e}_c{coef}"
    comm = os.path.join(work, name + ".comm")
    shutil.copy(os.path.join(HERE, "wall_onset.mail"), os.path.join(work, name + ".mail"))
    with open(comm, "w") as f:
        f.write(TEMPLATE.format(coef=coef, regul=regul, hl=hl, hn=hn, prec=prec, emax=5.0 * E_C,
                                approx=approx, extra=(", " + extra) if extra else ""))
    db = os.path.join(work, name + ".db")
    t0 = time.time()
    p = subprocess.run([binary, "run", comm, "--db", db], capture_output=True, text=True)
    wall = time.time() - t0
    out = p.stdout + p.stderr
    rows = []
    try:
        con = sqlite3.connect(db)
        rows = con.execute(
            "SELECT ENERGIE, FREQUENCE, NB_REPRISE_PAS FROM MNL ORDER BY NUME_ORDRE"
        ).fetchall()
        con.close()
    except sqlite3.Error:
        pass
    err = max((abs(f * period_plan(e) - 1.0) for e, f, _ in rows), default=float("nan"))
    err_reg = max((abs(f * period_regularised(e, regul) - 1.0) for e, f, _ in rows),
                  default=float("nan"))
    e_end = rows[-1][0] / E_C if rows else 0.0
    retries = sum(r or 0 for _, _, r in rows)
    keyword = ""
    for line in out.splitlines():
        if line.strip().startswith("×"):
            keyword = line.strip()[1:].split(":")[0].strip()
            break
    if p.returncode == 0:
        verdict = "right" if err_reg <= BOUND and e_end >= 5.0 * (1 - 1e-12) else "WRONG"
    else:
        verdict = "stopped"
    return dict(hl=hl, hn=hn, regul=regul, prec=prec, coef=coef, rc=p.returncode,
                rows=len(rows), e_end=e_end, err=err, err_reg=err_reg, retries=retries, wall=wall,
                verdict=verdict, keyword=keyword)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--bin", default=os.path.join(HERE, "..", "..", "target", "release", "aster-nl"))
    ap.add_argument("--quick", action="store_true", help="H 10/30 only")
    ap.add_argument("--keep", help="directory for the runs (kept)")
    ap.add_argument("--approx", default="SERIE", choices=["SERIE", "PADE"],
                    help="RESOLUTION/APPROX_MAN")
    ap.add_argument("--resolution", default="",
                    help="more RESOLUTION keywords, e.g. \"SAUT_RACINE_MAXI=0., "
                         "RAPPORT_CORRECTION_MAXI=0.\" (the jump checks off)")
    a = ap.parse_args()
    harms = [(10, 30)] if a.quick else [(10, 30), (20, 60), (40, 120), (60, 180)]
    work = a.keep or tempfile.mkdtemp(prefix="wall_grid_")
    os.makedirs(work, exist_ok=True)
    print("| H_l/H_nl | PARA_REGUL | PREC_MAN | COEF_AMPL | exit | rows | E_end/E_c | retries "
          "| worst freq. error, nonsmooth | worst, regularised | verdict | wall |")
    print("|---|---|---|---|---|---|---|---|---|---|---|---|")
    counts = {}
    worst_right = 0.0
    for hl, hn in harms:
        for regul in (1e-3, 1e-4, 1e-5, 1e-6, 1e-7):
            for prec in (1e-4, 1e-6, 1e-9):
                for coef in (0.5, 0.8, 1.0):
                    r = run_one(os.path.abspath(a.bin), work, hl, hn, regul, prec, coef, a.approx,
                                a.resolution)
                    counts[r["verdict"]] = counts.get(r["verdict"], 0) + 1
                    if r["verdict"] == "right":
                        worst_right = max(worst_right, r["err_reg"])
                    v = r["verdict"] + (f" ({r['keyword']})" if r["keyword"] else "")
                    print(f"| {hl}/{hn} | {regul:.0e} | {prec:.0e} | {coef} | {r['rc']} | {r['rows']} "
                          f"| {r['e_end']:.3f} | {r['retries']} | {r['err']:.2e} | {r['err_reg']:.2e} | {v} "
                          f"| {r['wall']:.2f} s |",
                          flush=True)
    print()
    print("totals:", ", ".join(f"{k} {v}" for k, v in sorted(counts.items())),
          f"; worst error of the right runs against the regularised law {worst_right:.2e} "
          f"(bound {BOUND:.0e})")
    if not a.keep:
        shutil.rmtree(work)
    sys.exit(1 if counts.get("WRONG") else 0)


if __name__ == "__main__":
    main()
