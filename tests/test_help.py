"""fsi_app -help (issue 13): exits 0 without a scene and documents every option the sources read
(each with a default and a unit), whether the scene switches its physics on or not, and every
registered boundary-condition type; a failing PETSc call reports PETSc's own message."""
import os
import re
import subprocess
from fsitest import APP, ENV, SRC, check, finish, run, scene

p = subprocess.run(["mpirun", "-n", "1", APP, "-help"], cwd="/tmp", env=ENV, text=True,
                   stdout=subprocess.PIPE, stderr=subprocess.STDOUT, timeout=120)
check(p.returncode == 0, f"-help without a scene exits 0 (got {p.returncode})")
lines = [l for l in p.stdout.splitlines() if l.startswith("  -")]
documented = {}
for l in lines:
    m = re.match(r"  -(\S+)\s+<([^>]*)> \[([^\]]+)\] (.+)", l)
    if m:
        for name in m.group(1).split(","):
            documented[name.strip().lstrip("-")] = m.groups()[1:]
check(len(documented) > 80, f"-help lists {len(documented)} options with default, unit and meaning")

# Every option name in the sources: opt::<reader>("name" ...) and per-boundary "bc_<b>_" + "name".
read = set()
for root, _, files in os.walk(os.path.join(SRC, "src")):
    for f in files:
        text = open(os.path.join(root, f)).read()
        read |= set(re.findall(r'opt::[a-z_]+\("([a-z_0-9]+)"', text))
        read |= {"bc_<b>_" + n for n in re.findall(r'opt::[a-z_]+\((?:pre_?|prefix) \+ "([a-z_0-9]+)"', text)}
        read |= set(re.findall(r'parse_points\("([a-z_0-9]+)"', text))
# Solver options the app inspects to configure its preconditioners belong to PETSc.
petsc = {"pc_type", "pc_fieldsplit_schur_precondition"}
missing = sorted(n for n in read - petsc if n not in documented)
print(f"{len(read)} option names read by the sources; undocumented: {missing}")
check(not missing, "every option the sources read is in -help")
for t in ("noslip", "velocity", "flow_rate", "pressure", "traction_exact", "clamped", "displacement",
          "traction", "follower_pressure"):
    check(re.search(rf"^  {t}\s+\((fluid|solid)\)", p.stdout, re.M) is not None,
          f"boundary type '{t}' listed")

# A PETSc error keeps PETSc's words (here: an unknown solver type, caught at solver setup).
r = run(scene("ethier_steinman"), extra=["-mesh_h", "1", "-snes_type", "no_such_snes"])
last = r.out.strip().splitlines()
# (PETSc's "[0]PETSC ERROR: " on stderr may land in front of our stdout line: look inside lines)
msg = [l[l.index("fsi_app: failure:"):] for l in last if "fsi_app: failure:" in l]
print(msg)
check(r.code != 0 and msg and "no_such_snes" in msg[0],
      "a failing PETSc call reports PETSc's message, naming the bad value")
finish()
