"""Every example scene runs as its header says (issue 56, item 7): `mpirun -n 2 fsi_app
-options_file examples/<scene>/<file>.opts` from the repository root, with no preset on the
command line (the scene names its own with -solver_preset), for its first two steps; a
-solver_preset given after the scene replaces the scene's whole preset."""
import glob
import os
import subprocess
import tempfile
from fsitest import APP, ENV, SRC, check, finish

scenes = sorted(f for f in glob.glob(os.path.join(SRC, "examples", "*", "*.opts"))
                if any(l.startswith("-scene_name") for l in open(f)))
check(len(scenes) >= 6, f"{len(scenes)} example scenes found")


def plain_run(rel, extra=()):
    out = tempfile.mkdtemp(prefix="fsi_scene_")
    cmd = ["mpirun", "-n", "2", APP, "-options_file", rel, "-ts_max_steps", "2", "-out_dir", out,
           "-mesh_cache_dir", os.path.join(SRC, "build", "mesh_cache")] + list(extra)
    p = subprocess.run(cmd, cwd=SRC, env=ENV, text=True, stdout=subprocess.PIPE,
                       stderr=subprocess.STDOUT, timeout=600)
    print("$", " ".join(cmd), "\n" + "\n".join(p.stdout.strip().splitlines()[-2:]))
    return p, out


for f in scenes:
    rel = os.path.relpath(f, SRC)
    p, _ = plain_run(rel)
    check(p.returncode == 0 and "fsi_app: done" in p.stdout, f"{rel} runs as given (exit {p.returncode})")


def solver(out):
    opts = dict(l.split(None, 1) if " " in l.strip() else (l.strip(), "")
                for l in open(os.path.join(out, "options.txt")) if l.startswith("-"))
    return opts.get("-pc_type", "").strip(), "-schur_pc_type" in opts


# The tube names schur_bilu_fast; direct on the command line replaces all of it.
p, out = plain_run("examples/tube/tube.opts", ["-solver_preset", "direct"])
pc, leftover = solver(out) if p.returncode == 0 else ("", True)
check(p.returncode == 0 and pc == "lu" and not leftover,
      f"-solver_preset direct after the tube's scene: pc_type {pc!r}, no schur_bilu option left")
p, out = plain_run("examples/tube/tube.opts", ["-options_file", "petsc_options/direct.opts"])
pc, leftover = solver(out) if p.returncode == 0 else ("", True)
check(p.returncode == 0 and pc == "lu" and not leftover,
      f"-options_file petsc_options/direct.opts after the scene: the same ({pc!r})")
finish()
