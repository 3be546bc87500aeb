"""Faults (issue 17): what a crash, a full disk, a read-only directory or a damaged file does to a
run.  Womersley flow on a coarse pipe (5231 dofs), 2 ranks, 100 steps of 5 ms, a checkpoint
every 25.
1. SIGKILL of one rank mid-run: the job stops (non-zero exit, no summary), the last checkpoint is
   intact, and resuming from it reproduces the uninterrupted run (to 1e-12).
2. A full disk (a 512 KiB tmpfs; skipped, saying so, where mount is not permitted: a file-size
   limit is no substitute, it kills mpirun's own shared-memory setup) while writing a checkpoint: exit 5, one 'fsi_app: error: output failed:' line naming the file, the previous
   checkpoint byte-for-byte intact, no partial file left, monitor.csv left as .partial.
3. A full disk while writing fields: exit 5, the line names fields.h5; the checkpoint left is
   readable and the run resumes from it (elsewhere) to the uninterrupted answer.
4. The output directory made read-only mid-run (as an unprivileged user: root ignores modes):
   the next checkpoint fails with exit 5, the previous one intact; resuming gives the answer.
5. A truncated checkpoint (0 bytes, 1 KiB, half, all but 100 bytes): restart refuses with
   exit 2 and one line naming the file and -restart, no summary.json."""
import hashlib
import h5py
import os
import shutil
import signal
import subprocess
import tempfile
import time
from fsitest import APP, ENV, SRC, check, finish, preset, run, scene
from state_compare import compare

COARSE = ["-mesh_params", "R=0.005,L=0.01,ncirc=16", "-mesh_h", "0.003", "-ts_dt", "0.005",
          "-ts_max_steps", "100", "-checkpoint_every", "25"]
CACHE = os.path.join(SRC, "build", "mesh_cache")


def cmd(outdir, extra=()):
    return ["mpirun", "-n", "2", APP, "-options_file", scene("womersley"), "-options_file",
            preset("direct"), "-mesh_cache_dir", CACHE] + COARSE + ["-out_dir", outdir] + list(extra)


def app(outdir, extra=()):
    """Run to the end; returns (exit code, output)."""
    c = cmd(outdir, extra)
    t0 = time.time()
    p = subprocess.run(c, cwd=SRC, env=ENV, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                       text=True, timeout=600)
    print(f"$ ({time.time() - t0:.1f} s)", " ".join(c))
    print("\n".join(l for l in p.stdout.splitlines() if l.startswith("fsi_app: e")) or
          p.stdout.strip().splitlines()[-1])
    return p.returncode, p.stdout


def md5(path):
    return hashlib.md5(open(path, "rb").read()).hexdigest()


def rows(path):
    return sum(1 for _ in open(path)) - 1 if os.path.exists(path) else 0


def error_lines(out):
    return [l for l in out.splitlines() if l.startswith("fsi_app: error:")]


def clean_output_failure(code, out, d, what, names):
    lines = error_lines(out)
    check(code == 5, f"{what}: exit 5 ({code})")
    check(len(lines) == 1 and "output failed" in lines[0] and names in lines[0],
          f"{what}: one error line naming {names}: {lines}")
    check("Traceback" not in out and "PETSC ERROR" not in out and "core dumped" not in out,
          f"{what}: no backtrace, no PETSc trace")
    check(not os.path.exists(os.path.join(d, "summary.json")), f"{what}: no summary.json")
    check(not os.path.exists(os.path.join(d, "monitor.csv")),
          f"{what}: monitor left as monitor.csv.partial, not passed off as whole")
    check(not os.path.exists(os.path.join(d, "checkpoint.h5.partial")),
          f"{what}: no partial checkpoint left")


def resume_matches(ck, what):
    """Resume from checkpoint ck in a fresh directory; the end state equals the reference's."""
    d = tempfile.mkdtemp(prefix="fsi_test_")
    code, _ = app(d, ["-restart", ck])
    check(code == 0, f"{what}: resumed from the checkpoint left")
    if code == 0:
        compare(REF, os.path.join(d, "checkpoint.h5"), f"{what}: resumed vs uninterrupted")


class SmallDisk:
    """A directory on a tmpfs of `size` bytes (mounted: False where mount is not permitted)."""

    def __init__(self, size):
        self.dir = tempfile.mkdtemp(prefix="fsi_test_disk_")
        self.mounted = subprocess.run(["mount", "-t", "tmpfs", "-o", f"size={size}", "tmpfs",
                                       self.dir], capture_output=True).returncode == 0
        print(f"small disk {self.dir}: " + ("tmpfs" if self.mounted else
                                            "SKIPPED: mount not permitted here"))

    def close(self):
        if self.mounted:
            subprocess.run(["umount", self.dir])


# The uninterrupted reference.
R = run(scene("womersley"), np=2, extra=COARSE)
check(R.code == 0, "reference run (100 steps) succeeds")
REF = os.path.join(R.dir, "checkpoint.h5")

# 1. SIGKILL of one rank mid-run.
d = tempfile.mkdtemp(prefix="fsi_test_")
p = subprocess.Popen(cmd(d), cwd=SRC, env=ENV, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                     text=True)
partial, t0, killed = os.path.join(d, "monitor.csv.partial"), time.time(), None
while time.time() - t0 < 120 and p.poll() is None:
    if rows(partial) > 27:  # past the step-25 checkpoint (written before row 26), well before step 50's
        ranks = [int(q) for q in os.listdir("/proc") if q.isdigit() and
                 os.path.exists(f"/proc/{q}/cmdline") and
                 open(f"/proc/{q}/cmdline", "rb").read().split(b"\0")[0].endswith(b"fsi_app") and
                 d.encode() in open(f"/proc/{q}/cmdline", "rb").read()]
        if ranks:
            killed = max(ranks)
            os.kill(killed, signal.SIGKILL)
        break
    time.sleep(0.01)
text, _ = p.communicate(timeout=120)
check(killed is not None, f"one rank (pid {killed}) killed at step {rows(partial)}")
check(p.returncode != 0 and not os.path.exists(os.path.join(d, "summary.json")),
      f"killed run: non-zero exit ({p.returncode}), no summary")
with h5py.File(os.path.join(d, "checkpoint.h5")) as f:
    check(f.attrs["step"] == 25, f"the checkpoint left is step 25's ({f.attrs['step']:.0f})")
resume_matches(os.path.join(d, "checkpoint.h5"), "rank killed")

# 2. Disk full while writing a checkpoint: 10 steps fit (checkpoint 0.3 MB), the next does not.
disk = SmallDisk(512 * 1024)
if disk.mounted:
    d = os.path.join(disk.dir, "run")
    code, _ = app(d, ["-ts_max_steps", "10", "-checkpoint_every", "10"])
    check(code == 0, "10 steps on the small disk")
    ck = os.path.join(d, "checkpoint.h5")
    before = md5(ck)
    code, out = app(d, ["-ts_max_steps", "20", "-checkpoint_every", "10", "-restart", ck])
    clean_output_failure(code, out, d, "disk full during a checkpoint", "checkpoint")
    check(md5(ck) == before, "the previous checkpoint is byte-for-byte intact")
disk.close()

# 3. Disk full while writing fields (59 KB per step): the step-8 checkpoint (0.3 MB) fits, the
# fields fill the disk at step ~12, before the next checkpoint (step 16).
disk = SmallDisk(1024 * 1024)
if disk.mounted:
    d = os.path.join(disk.dir, "run")
    code, out = app(d, ["-out_fields_every", "1", "-checkpoint_every", "8"])
    clean_output_failure(code, out, d, "disk full during field output", "fields.h5")
    keep = tempfile.mkdtemp(prefix="fsi_test_")
    shutil.copy(os.path.join(d, "checkpoint.h5"), keep)
disk.close()
if disk.mounted:
    resume_matches(os.path.join(keep, "checkpoint.h5"), "disk full during field output")

# 4. Read-only output directory mid-run, as an unprivileged user (root ignores the mode).
user = "nobody" if os.geteuid() == 0 else None
d = tempfile.mkdtemp(prefix="fsi_test_")
if user:
    shutil.chown(d, user)
c = cmd(d)
if user:
    c = ["setpriv", "--reuid=" + user, "--regid=nogroup", "--clear-groups"] + c
p = subprocess.Popen(c, cwd=SRC, env=dict(ENV, HOME=d), stdout=subprocess.PIPE,
                     stderr=subprocess.STDOUT, text=True)
partial, t0, at = os.path.join(d, "monitor.csv.partial"), time.time(), None
while time.time() - t0 < 120 and p.poll() is None:
    if rows(partial) > 27:
        at = rows(partial)
        os.chmod(d, 0o555)
        break
    time.sleep(0.01)
out, _ = p.communicate(timeout=120)
os.chmod(d, 0o755)
print("\n".join(error_lines(out)))
check(at is not None and at < 50, f"directory made read-only at step {at}")
clean_output_failure(p.returncode, out, d, "read-only directory", "checkpoint")
with h5py.File(os.path.join(d, "checkpoint.h5")) as f:
    check(f.attrs["step"] == 25, f"the checkpoint left is step 25's ({f.attrs['step']:.0f})")
resume_matches(os.path.join(d, "checkpoint.h5"), "read-only directory")

# 5. Truncated checkpoints.
size = os.path.getsize(REF)
for n in (0, 1024, size // 2, size - 100):
    d = tempfile.mkdtemp(prefix="fsi_test_")
    bad = os.path.join(d, "truncated.h5")
    with open(REF, "rb") as f, open(bad, "wb") as g:
        g.write(f.read(n))
    code, out = app(os.path.join(d, "out"), ["-restart", bad])
    lines = error_lines(out)
    check(code == 2 and len(lines) == 1 and "truncated.h5" in lines[0] and "-restart" in lines[0],
          f"checkpoint truncated to {n} of {size} B: exit 2 ({code}), one line naming it: {lines}")
    check("PETSC ERROR" not in out and not os.path.exists(os.path.join(d, "out", "summary.json")),
          f"checkpoint truncated to {n} B: no PETSc trace, no summary")
finish()
