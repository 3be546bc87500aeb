"""Checkpoint and exact restart (issue 5).
1. Womersley (fluid, wall-shear accumulators over the period): 2N steps on 2 ranks equal N steps +
   restart + N steps, resumed on 2 ranks and on 1 rank, to 1e-12 of each field's scale; the
   period's OSI/TAWSS maps equal too.
2. The FSI tube (solid displacement, mesh motion history): the same, 2 -> 2 and 2 -> 1 ranks.
3. A run killed (SIGKILL) while writing its 2nd checkpoint leaves the 1st usable: restarting from
   it in the same directory finishes the run with the uninterrupted answer, monitor.csv whole.
4. SIGTERM to mpirun: the app writes a checkpoint, a summary saying why it stopped, exits
   non-zero; resuming from that checkpoint gives the uninterrupted answer."""
import os
import signal
import subprocess
import time
import h5py
import numpy as np
from fsitest import APP, ENV, SRC, check, finish, preset, run, scene
from state_compare import compare, state


wom = [scene("womersley")]
# A coarse pipe (5231 dofs, 16 elements around): restart is exact or not on any mesh, and each
# run costs a third of the scene's own (28369 dofs).
coarse = ["-mesh_params", "R=0.005,L=0.01,ncirc=16", "-mesh_h", "0.003"]
hemo = coarse + ["-hemo_surfaces", "wall", "-hemo_window", "1.0"]
A = run(wom, np=2, extra=hemo + ["-checkpoint_every", "20"])
B = run(wom, np=2, extra=hemo + ["-checkpoint_every", "20", "-ts_max_steps", "20"])
check(A.code == 0 and B.code == 0, "Womersley 40-step and 20-step runs succeed")
ck = os.path.join(B.dir, "checkpoint.h5")
for np_ in (2, 1):
    C = run(wom, np=np_, extra=hemo + ["-checkpoint_every", "20", "-restart", ck])
    check(C.code == 0 and "resumed from" in C.out, f"Womersley resumed on {np_} rank(s)")
    compare(os.path.join(A.dir, "checkpoint.h5"), os.path.join(C.dir, "checkpoint.h5"),
            f"Womersley 40 steps vs 20 + restart on {np_} rank(s) + 20")
    with h5py.File(os.path.join(A.dir, "hemo.h5")) as fa, \
            h5py.File(os.path.join(C.dir, "hemo_restart.h5")) as fc:
        d = max(np.abs(fa[f"wall/window_0/{k}"][()] - fc[f"wall/window_0/{k}"][()]).max()
                for k in ("tawss", "wss_magnitude_mean", "osi"))
        scale = fa["wall/window_0/wss_magnitude_mean"][()].max()
    check(d < 1e-12 * scale,
          f"period's OSI/TAWSS maps equal after the restart on {np_} rank(s) ({d / scale:.1e})")
    check(C.summary["restarted_from"]["step"] == 20, "summary records the restart")

# The mesh-motion solve is iterative: its stopping test may fall one CG iteration apart under
# the parallel LU's 1e-14 noise, so it is converged to round-off here (rtol 1e-14).
tube = [os.path.join(SRC, "examples", "tube", "tube.opts")]
# (h 3 mm: the tube's coarsest mesh that still resolves its wall, as in the rebuild test.)
tight = ["-ale_ksp_rtol", "1e-14", "-mesh_h", "0.003"]
T = run(tube, np=2, extra=tight + ["-ts_max_steps", "8", "-checkpoint_every", "4"])
U = run(tube, np=2, extra=tight + ["-ts_max_steps", "4", "-checkpoint_every", "4"])
check(T.code == 0 and U.code == 0, "tube 8-step and 4-step runs succeed")
for np_ in (2, 1):
    V = run(tube, np=np_, extra=tight + ["-ts_max_steps", "8", "-checkpoint_every", "4", "-restart",
                                 os.path.join(U.dir, "checkpoint.h5")])
    check(V.code == 0, f"tube resumed on {np_} rank(s)")
    compare(os.path.join(T.dir, "checkpoint.h5"), os.path.join(V.dir, "checkpoint.h5"),
            f"FSI tube 8 steps vs 4 + restart on {np_} rank(s) + 4", solid_radius=0.005)
    a, b = T.monitor[-1]["solid_probe0_ux"], V.monitor[-1]["solid_probe0_ux"]
    scale = np.abs(state(os.path.join(T.dir, "checkpoint.h5"))[0]["dofs/state"][:, 2]).max()
    check(abs(a - b) < 1e-12 * scale, f"tube: point M displacement {a:.15e} vs {b:.15e}")

# More numerical damping after a restart (the valve's diastole): the state carries over whatever
# rho_inf, so only the time scheme's radius may differ from the checkpoint's scene; it shows in
# the answer.
W = run(tube, np=2, extra=tight + ["-ts_max_steps", "8", "-ts_alpha_radius", "0", "-restart",
                             os.path.join(U.dir, "checkpoint.h5")])
check(W.code == 0 and "restart: rho_inf 0.000000 (the checkpoint's run had rho_inf "
      "0.500000)" in W.out,
      "tube resumed with -ts_alpha_radius 0 from a rho_inf 0.5 checkpoint, and says so")
c = W.monitor[-1]["solid_probe0_ux"]
check(W.code == 0 and abs(c - a) > 1e-3 * abs(a),
      f"rho_inf 0 after the restart changes point M: {c:.6e} vs {a:.6e}")

# The same damping switched by a monitor condition inside one run (-ts_alpha_radius_switch_when,
# the valve's closure): the axial velocity at the first probe passes 1.1 mm/s in step 4 (0.91 after
# step 3, 1.35 after step 4), so rho_inf is 0 from step 5, as in the restart above; a restart from
# a step-6 checkpoint keeps the switched rho_inf.
sw = ["-ts_alpha_radius_switch_when", "probe0_vz>0.0011", "-ts_alpha_radius_switch_to", "0"]
X = run(tube, np=2, extra=tight + sw + ["-ts_max_steps", "8"])
check(X.code == 0 and "(now > 0.0011) at t = 0.0004 s: generalized-alpha rho_inf 0.5 -> 0 from the "
      "next step" in X.out, "the switch fires after step 4 and says so")
x = X.monitor[-1]["solid_probe0_ux"] if X.code == 0 else float("nan")
check(abs(x - c) < 1e-12 * scale, f"switched in the run = restarted with rho_inf 0: {x:.15e} vs {c:.15e}")
X6 = run(tube, np=2, extra=tight + sw + ["-ts_max_steps", "6", "-checkpoint_every", "6"])
Y = run(tube, np=2, extra=tight + sw + ["-ts_max_steps", "8", "-restart",
                                        os.path.join(X6.dir, "checkpoint.h5")])
y = Y.monitor[-1]["solid_probe0_ux"] if Y.code == 0 else float("nan")
check(abs(y - x) < 1e-12 * scale, f"a restart after the switch keeps rho_inf 0: {y:.15e} vs {x:.15e}")
# While the condition holds only (after steps 1-3): rho_inf 0 in steps 2-4, 0.5 again from 5.
Z = run(tube, np=2, extra=tight + ["-ts_alpha_radius_switch_when", "probe0_vz<0.0011",
                                   "-ts_max_steps", "5"])
check(Z.code == 0 and "(now < 0.0011) at t = 0.0001 s: generalized-alpha rho_inf 0.5 -> 0" in Z.out
      and "(no longer < 0.0011) at t = 0.0004 s: generalized-alpha rho_inf 0 -> 0.5" in Z.out,
      "rho_inf follows the condition: switched while it holds, back when it does not")
for bad, words in ((["-ts_alpha_radius_switch_when", "no_column>1"],
                    "option -ts_alpha_radius_switch_when: the run has no monitor column 'no_column'"),
                   (["-ts_alpha_radius_switch_when", "probe0_vz>"],
                    "give a monitor column, < or >, and a number"),
                   (["-ts_alpha_radius_switch_to", "1.5"], "must be in [0, 1]")):
    B = run(tube, np=1, extra=tight + bad + ["-ts_max_steps", "1"])
    check(B.code != 0 and words in B.out and not os.path.exists(os.path.join(B.dir, "summary.json")), f"{bad}: one-line error ({words})")

# Killed while writing the 2nd checkpoint (step 20): the step-10 checkpoint survives.
K = run(wom, np=2, extra=hemo + ["-checkpoint_every", "10", "-checkpoint_crash_test", "2"])
ck = os.path.join(K.dir, "checkpoint.h5")
check(K.code != 0 and not os.path.exists(os.path.join(K.dir, "summary.json")),
      f"killed run: non-zero exit ({K.code}), no summary")
with h5py.File(ck) as f:
    step = f.attrs["step"]
check(step == 10, f"the checkpoint left is the previous one, intact (step {step:.0f})")
K2 = run(wom, np=2, extra=hemo + ["-checkpoint_every", "10", "-restart", ck, "-out_dir", K.dir])
check(K2.code == 0, "restart from it in the same directory succeeds")
compare(os.path.join(A.dir, "checkpoint.h5"), ck, "killed + restarted vs uninterrupted")
K2.dir = K.dir  # it wrote there (-out_dir given last wins)
steps = [int(r["step"]) for r in K2.monitor]
check(steps == list(range(1, 41)), "monitor.csv holds steps 1..40 once each")

# SIGTERM to the ranks during a 1000-step run (~8 s on the coarse pipe: 200 steps ended before
# the signal came on a loaded machine), as a batch system does when a job's time is up.
# (Through mpirun, which forwards it, the ranks get 1 s before mpirun's SIGKILL: the checkpoint
# write of this run takes 0.7 s here, more on a loaded machine, and the test was a race.)
fine = coarse + ["-ts_dt", "0.001"]
R = run(wom, np=2, extra=fine + ["-checkpoint_every", "1000"])
out = os.path.join(K.dir, "sigterm")
cmd = ["mpirun", "-n", "2", APP, "-options_file", scene("womersley"), "-options_file",
       preset("direct"), "-out_dir", out, "-mesh_cache_dir",
       os.path.join(SRC, "build", "mesh_cache")] + fine
# mpirun's default grace (1 s; the tests' ENV sets 0) between the first rank's exit and killing
# the other: the ranks leave together after the collective checkpoint.
graceful = {k: v for k, v in ENV.items() if k != "OMPI_MCA_odls_base_sigkill_timeout"}
p = subprocess.Popen(cmd, cwd=SRC, env=graceful, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                     text=True)
partial = os.path.join(out, "monitor.csv.partial")
t0 = time.time()
while time.time() - t0 < 120:
    if os.path.exists(partial) and sum(1 for _ in open(partial)) > 30:
        break
    time.sleep(0.02)
ranks = subprocess.run(["pgrep", "-P", str(p.pid)], stdout=subprocess.PIPE, text=True).stdout.split()
ranks = [int(r) for r in ranks if open(f"/proc/{r}/comm").read().strip() == "fsi_app"]
check(len(ranks) == 2, f"SIGTERM: the two ranks found ({ranks})")
for r in ranks:
    os.kill(r, signal.SIGTERM)
text, _ = p.communicate(timeout=120)
print("SIGTERM run's last line:", (text.strip().splitlines() or ["(no output)"])[-1])
s = None
if os.path.exists(os.path.join(out, "summary.json")):
    import json
    s = json.load(open(os.path.join(out, "summary.json")))
check(p.returncode != 0, f"SIGTERM: non-zero exit ({p.returncode})")
check(s is not None and s["converged"] is False and "SIGTERM" in s["reason"],
      "SIGTERM: summary says converged false, stopped by SIGTERM")
if s:
    with h5py.File(os.path.join(out, "checkpoint.h5")) as f:
        check(f.attrs["step"] == s["final_step"] and 0 < s["final_step"] < 1000,
              f"SIGTERM: checkpoint at the last step ({s['final_step']})")
    S = run(wom, np=2, extra=fine + ["-checkpoint_every", "1000", "-restart",
                                     os.path.join(out, "checkpoint.h5")])
    check(S.code == 0, "resumed after SIGTERM")
    compare(os.path.join(R.dir, "checkpoint.h5"), os.path.join(S.dir, "checkpoint.h5"),
            "SIGTERM + restart vs uninterrupted (1000 steps)")
finish()
