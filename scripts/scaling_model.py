#!/usr/bin/python3
"""docs/scaling_model.md's table: seconds per step of the paper-size and the 10x valve meshes on
P ranks, from per-rank costs measured on the 2-core machine (inputs below, docs/performance.md) and the
stated assumptions.  A model, not a measurement.  Run: /usr/bin/python3 scripts/scaling_model.py"""
import math

# Measured (2 ranks, paper-size tube, schur_bilu_fast; docs/performance.md)
R_JAC = 145e3        # Jacobian, P2 tets/s per rank
R_RES = 726e3        # residual, tets/s per rank
JAC_PER_STEP = 1.0   # -snes_lag_jacobian 2: one per step
RES_PER_STEP = 2.2   # one per Newton iteration + the step's first (1.18 Newton/step)
KRYLOV_PER_STEP = 22.0           # 1.18 Newton x 19 GMRES iterations
KRYLOV_US_PER_DOF = 15.6e-3 / (210e3 / 2) * 1e6  # 15.6 ms per iteration, 210k dofs on 2 ranks
SETUP_S_PER_DOF = 0.28 / (210e3 / 2)             # one rebuild (block ILU + Sp), every 10 Jacobians
SP_VCYCLE_S = 4.7e-3  # one BoomerAMG V-cycle on Sp, 9 116 unknowns, 2 ranks: measured overhead
# Assumed
KRYLOV_GROWTH = 0.1   # k(P) = k(2) (P/2)^0.1: one ILU block per rank (measured 1->2: +1.7 %)
BETA = 0.5            # share of a core's memory bandwidth a rank keeps when 8+ share a socket
LATENCY = 5e-6        # one allreduce / message, s
DOFS_PER_CELL = 4.7   # the valve meshes (CI mesh: 8.1k cells, 38.5k dofs)


def step_seconds(cells, ranks, sp="ilu"):
    dofs = cells * DOFS_PER_CELL
    beta = 1.0 if ranks <= 2 else BETA
    k = KRYLOV_PER_STEP * (ranks / 2) ** KRYLOV_GROWTH
    jac = JAC_PER_STEP * cells / (ranks * R_JAC)
    res = RES_PER_STEP * cells / (ranks * R_RES) / beta
    krylov = k * KRYLOV_US_PER_DOF * 1e-6 * dofs / ranks / beta
    # GMRES: ~7 allreduces per iteration (orthogonalisation, norms), 2 halo exchanges.
    comm = k * (7 * LATENCY * math.log2(max(ranks, 2)) + 2 * LATENCY)
    if sp == "amg":  # a V-cycle per iteration: measured overhead, kept constant in P
        comm += k * SP_VCYCLE_S
    setup = SETUP_S_PER_DOF * dofs / ranks / beta / 10
    total = jac + res + krylov + comm + setup
    return dofs, jac, res, krylov, comm, total


if __name__ == "__main__":
    print(f"inputs: Jacobian {R_JAC/1e3:.0f}k, residual {R_RES/1e3:.0f}k tets/s per rank; "
          f"Krylov {KRYLOV_US_PER_DOF:.3f} us per dof per rank per iteration, "
          f"{KRYLOV_PER_STEP:.0f} per step at 2 ranks")
    for sp in ("ilu", "amg"):
        print(f"\nSp preconditioner: {'block-Jacobi ILU(0)' if sp == 'ilu' else 'BoomerAMG (4.7 ms per V-cycle)'}")
        print("| mesh | ranks | dofs/rank | Jacobian | residuals | Krylov compute | communication | s/step | comm share |")
        print("|---|---|---|---|---|---|---|---|---|")
        for name, cells, ranks in (("paper valve, 630k", 134e3, (2, 16, 32, 64, 128)),
                                   ("10x valve, 6.3M", 1.34e6, (16, 32, 64, 128))):
            for i, p in enumerate(ranks):
                dofs, jac, res, kry, comm, tot = step_seconds(cells, p, sp)
                label = name if i == 0 else ""
                print(f"| {label} | {p} | {dofs / p / 1e3:.1f}k | {jac:.2f} | {res:.2f} | {kry:.2f} | "
                      f"{comm:.3f} | {tot:.2f} | {100 * comm / tot:.0f} % |")
