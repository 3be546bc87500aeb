"""fsi_app -help (issue 13): exits 0 without a scene and documents every option the sources read
(each with a default and a unit), whether the scene switches its physics on or not, and every
registered physics, monitor and boundary-condition type; no entry that nothing reads, literal
defaults as the readers' are; each option declared next to its reader (issue 56: in the folder
of a file that reads it); a misspelt PETSc type is one line naming the option."""
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
        read |= set(re.findall(r'(?:opt::[a-z_]+|from_option)\("([A-Za-z_0-9]+)"', text))
        read |= {"bc_<b>_" + n for n in re.findall(r'opt::[a-z_]+\((?:pre_?|prefix) \+ "([a-z_0-9]+)"', text)}
        read |= set(re.findall(r'parse_points\("([a-z_0-9]+)"', text))
# Solver options the app inspects to configure its preconditioners belong to PETSc.
petsc = {"pc_type", "pc_fieldsplit_schur_precondition"}
missing = sorted(n for n in read - petsc if n not in documented)
print(f"{len(read)} option names read by the sources; undocumented: {missing}")
check(not missing, "every option the sources read is in -help")
# ... and every entry of -help is read by some source (no entry left behind by a removed option);
# patterns (snes_*, bc_<b>_*) and PETSc's own names are not option names of ours.
ours = {n for n in documented if "*" not in n and "<" not in n and not n.startswith(("snes_", "ksp_", "pc_", "mat_"))}
bc = {n[len("bc_<b>_"):] for n in read if n.startswith("bc_<b>_")}
stale = sorted(n for n in ours if n not in read and not (n.startswith("bc_<b>_") and n[7:] in bc))
print(f"help entries nothing reads: {stale}")
check(not stale, "every -help entry is read by the sources")

# Defaults: where a reader's default is a literal, -help states the same value.
def number(t):
    try:
        return float(t)
    except ValueError:
        return None
literal = {}
for root, _, files in os.walk(os.path.join(SRC, "src")):
    for f in files:
        text = open(os.path.join(root, f)).read()
        for name, d in re.findall(r'opt::(?:real|positive|nonnegative|integer|integer_at_least|flag|string|choice)\("([A-Za-z_0-9]+)",\s*([^,)]+)', text):
            literal.setdefault(name, set()).add(d.strip())
wrong = []
for name, ds in sorted(literal.items()):
    if name not in documented or len(ds) != 1:
        continue  # read with several defaults (per mode): -help says which
    d = ds.pop()
    shown = documented[name][0].split(" ")[0].strip()
    if shown == "" or shown.startswith("(") or not re.fullmatch(r'"[^"]*"|[-+.\w]+', d):
        continue  # no default (required, or only read when given), or one computed
    if d.startswith('"'):
        ok = d.strip('"') == shown
    elif d in ("true", "false"):
        ok = d == shown
    elif number(d) is not None:
        ok = number(shown) is not None and abs(number(shown) - number(d)) <= 1e-12 * abs(number(d))
    else:
        continue  # computed from other values
    if not ok:
        wrong.append(f"-{name}: reader {d}, help {shown!r}")
print("defaults that differ:", wrong)
check(not wrong, "every literal default in -help equals its reader's")
# Declared next to the reader: an option's declaration {"name", default, unit, meaning} is in the
# folder of a file that reads it.  Folders that make one part count as one: the solver (problem,
# solver, scene: the presets), the boundary conditions and their waveforms (analytic).  The
# driver (src/main.cpp, src/run/) reads options that the parts it drives declare.
part = {"src/solver": "src/problem", "src/scene": "src/problem", "src/analytic": "src/boundary"}
folder = lambda p: part.get(os.path.dirname(p), os.path.dirname(p))
readers, declared = {}, {}
for root, _, files in os.walk(os.path.join(SRC, "src")):
    for f in files:
        path = os.path.relpath(os.path.join(root, f), SRC)
        text = open(os.path.join(root, f)).read()
        names = re.findall(r'(?:opt::[a-z_]+|from_option|parse_points)\("([A-Za-z_0-9]+)"', text)
        names += ["bc_<b>_" + n for n in re.findall(r'opt::[a-z_]+\((?:pre_?|prefix) \+ "([a-z_0-9]+)"', text)]
        for n in names:
            readers.setdefault(n, set()).add(path)
        for n in re.findall(r'\{"([A-Za-z_0-9<>]+)",\s*"[^"]*",\s*"[^"]*",', text):
            declared.setdefault(n, set()).add(folder(path))
astray = []
for n, files in sorted(readers.items()):
    if n in petsc or any(f == "src/main.cpp" or f.startswith("src/run/") for f in files):
        continue
    if not {folder(f) for f in files} & declared.get(n, set()):
        astray.append(f"-{n}: read in {sorted(files)}, declared in {sorted(declared.get(n, []))}")
print(f"options declared away from their readers: {astray}")
check(len(declared) > 80 and not astray, "every option is declared in its reader's folder")
for t in ("fluid", "solid", "contact", "gap_seal"):
    check(re.search(rf"^  {t}\s+\S", p.stdout.split("Physics (-physics")[-1], re.M) is not None,
          f"physics '{t}' listed")

for t in ("noslip", "velocity", "flow_rate", "pressure", "traction_exact", "clamped", "displacement",
          "traction", "follower_pressure"):
    check(re.search(rf"^  {t}\s+\((fluid|solid)\)", p.stdout, re.M) is not None,
          f"boundary type '{t}' listed")

# A misspelt PETSc type is bad input: one line naming the option, PETSc's words, exit 2.
r = run(scene("ethier_steinman"), extra=["-mesh_h", "1", "-snes_type", "no_such_snes"])
msg = [l for l in r.out.splitlines() if "fsi_app: error:" in l]
print(msg)
check(r.code == 2 and len(msg) == 1 and "-snes_type" in msg[0] and "no_such_snes" in msg[0]
      and "PETSC ERROR" not in r.out, "an unknown PETSc type: exit 2, one line naming the option")
finish()
