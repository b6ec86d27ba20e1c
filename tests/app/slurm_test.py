#!/usr/bin/python3
"""sweep --slurm --submit on a real one-node Slurm (issue 17): Debian's munge,
slurmctld and slurmd (installed by scripts/setup.sh --test-deps) started by
this test without systemd (a munge key it makes, munged as the munge user, a
minimal slurm.conf in a temporary directory, both Slurm daemons in the
foreground as its children), a small sweep submitted, a bounded wait for the
merge job, the merged CSV compared with a one-machine --jobs run of the same
sweep (every column but the timing ones), the sweep written again to see it
resume with nothing left to run, and the daemons stopped by their pids. When
the daemons cannot start here, the test says why and exits 77 (skipped), never
0.

Usage: slurm_test.py FLAG_SIM"""
import csv
import os
import shutil
import signal
import socket
import subprocess
import sys
import tempfile
import time

flag_sim = os.path.abspath(sys.argv[1])
SKIP = 77
failures = []


def check(condition, what):
    if not condition:
        failures.append(what)


def skip(why):
    print(f"SKIPPED: {why}")
    sys.exit(SKIP)


def running(pid):
    try:
        with open(f"/proc/{pid}/stat") as f:
            return f.read().split()[2] not in ("Z", "X")
    except OSError:
        return False


def wait_until(condition, seconds):
    deadline = time.time() + seconds
    while time.time() < deadline:
        if condition():
            return True
        time.sleep(0.2)
    return condition()


def timing_free(path):
    with open(path) as f:
        rows = list(csv.DictReader(f))
    for row in rows:
        for key in ("ms_per_frame", "physics_ms", "infill_ms"):
            row.pop(key)
    return rows


tools = ["munged", "slurmctld", "slurmd", "sbatch", "scontrol", "sinfo", "squeue", "runuser"]
missing = [t for t in tools if shutil.which(t) is None]
if missing:
    skip(f"not installed: {', '.join(missing)} (scripts/setup.sh --test-deps installs them)")
if os.geteuid() != 0:
    skip("the daemons are started as root (SlurmUser=root, munged as the munge user)")

host = socket.gethostname().split(".")[0]
tmp = tempfile.mkdtemp(prefix="flagsim_slurm_")
os.chmod(tmp, 0o755)  # munged (the munge user) must reach its socket directory
daemons = []
env = dict(os.environ, SLURM_CONF=os.path.join(tmp, "slurm.conf"))
try:
    # munge: a key, a socket directory the munge user owns.
    munge_dir = os.path.join(tmp, "munge")
    os.mkdir(munge_dir, 0o755)
    key = os.path.join(munge_dir, "munge.key")
    with open(key, "wb") as f:
        f.write(os.urandom(1024))
    os.chmod(key, 0o400)
    shutil.chown(munge_dir, "munge", "munge")
    shutil.chown(key, "munge", "munge")
    socket_path = os.path.join(munge_dir, "munge.socket.2")
    munged = subprocess.run(
        ["runuser", "-u", "munge", "--", "munged", f"--socket={socket_path}",
         f"--key-file={key}", f"--pid-file={munge_dir}/munged.pid",
         f"--log-file={munge_dir}/munged.log", f"--seed-file={munge_dir}/munged.seed"],
        capture_output=True, text=True, timeout=30)
    if munged.returncode != 0:
        skip(f"munged did not start: {munged.stderr.strip()}")
    munge_pid = int(open(f"{munge_dir}/munged.pid").read().split()[0])

    # slurm.conf for one node on free ports.
    ports = []
    for _ in range(2):
        with socket.socket() as s:
            s.bind(("127.0.0.1", 0))
            ports.append(s.getsockname()[1])
    for sub in ("state", "spool"):
        os.mkdir(os.path.join(tmp, sub))
    with open(env["SLURM_CONF"], "w") as f:
        f.write(f"""ClusterName=flagsim
SlurmctldHost={host}(127.0.0.1)
SlurmUser=root
SlurmdUser=root
SlurmctldPort={ports[0]}
SlurmdPort={ports[1]}
AuthType=auth/munge
AuthInfo=socket={socket_path}
StateSaveLocation={tmp}/state
SlurmdSpoolDir={tmp}/spool
SlurmctldPidFile={tmp}/slurmctld.pid
SlurmdPidFile={tmp}/slurmd.pid
SlurmctldLogFile={tmp}/slurmctld.log
SlurmdLogFile={tmp}/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
SelectType=select/cons_tres
SchedulerParameters=batch_sched_delay=0
MpiDefault=none
ReturnToService=2
JobCompType=jobcomp/none
NodeName={host} NodeAddr=127.0.0.1 CPUs=2 State=UNKNOWN
PartitionName=debug Nodes={host} Default=YES MaxTime=INFINITE State=UP
""")
    for command in (["slurmctld", "-D", "-i"], ["slurmd", "-D", "-N", host]):
        daemons.append(subprocess.Popen(command, env=env, stdout=subprocess.DEVNULL,
                                        stderr=subprocess.DEVNULL))
        time.sleep(0.3)

    def node_idle():
        r = subprocess.run(["sinfo", "-h", "-N", "-o", "%T"], env=env, capture_output=True,
                           text=True)
        return r.returncode == 0 and r.stdout.strip() == "idle"

    if not wait_until(node_idle, 30):
        logs = "".join(open(os.path.join(tmp, name)).read()[-400:]
                       for name in ("slurmctld.log", "slurmd.log")
                       if os.path.exists(os.path.join(tmp, name)))
        skip(f"the Slurm node did not come up idle in 30 s: {logs!r}")

    work = os.path.join(tmp, "work")
    os.mkdir(work)
    sweep = ["sweep", "--set", "flag.fine=[17,25]", "--frames", "10", "--coarse", "5x7,9x13"]
    r = subprocess.run([flag_sim, *sweep, "-o", "cluster.csv", "--slurm", "jobs", "--submit",
                        "--slurm-arg=--time=10"], cwd=work, env=env, capture_output=True,
                       text=True, timeout=120)
    check(r.returncode == 0, f"--submit: exit {r.returncode} {r.stderr}")
    check("submitted: reference " in r.stdout and ", points " in r.stdout and ", merge " in r.stdout,
          f"--submit prints the job ids: {r.stdout!r}")
    script = open(os.path.join(work, "jobs", "sweep.sbatch")).read()
    check("#SBATCH --array=1-2" in script and "#SBATCH --time=10" in script,
          f"sweep.sbatch: {script!r}")

    def merged():
        q = subprocess.run(["squeue", "-h"], env=env, capture_output=True, text=True)
        return os.path.exists(os.path.join(work, "cluster.csv")) and q.stdout.strip() == ""

    done = wait_until(merged, 180)
    check(done, "the jobs did not finish in 180 s: " + " ".join(
        open(os.path.join(work, "jobs", n)).read()[-300:]
        for n in sorted(os.listdir(os.path.join(work, "jobs"))) if n.endswith(".out")))
    if done:
        r = subprocess.run([flag_sim, *sweep, "-o", "local.csv", "--jobs", "2", "--quiet"],
                           cwd=work, capture_output=True, text=True, timeout=300)
        check(r.returncode == 0, f"--jobs run: {r.stderr}")
        cluster, local = timing_free(os.path.join(work, "cluster.csv")), timing_free(
            os.path.join(work, "local.csv"))
        check(len(cluster) == 3 and cluster == local,
              f"the merged CSV differs from the --jobs run:\n{cluster}\n{local}")
        # Written again: everything is done, nothing is left to run.
        r = subprocess.run([flag_sim, *sweep, "-o", "cluster.csv", "--slurm", "jobs"], cwd=work,
                           env=env, capture_output=True, text=True, timeout=60)
        check(r.returncode == 0 and "reference.sbatch (done, left out)" in r.stdout
              and "points none left" in r.stdout, f"resume: {r.stdout!r} {r.stderr!r}")
finally:
    subprocess.run(["scontrol", "shutdown"], env=env, capture_output=True, timeout=30)
    for daemon in daemons:
        try:
            daemon.wait(timeout=20)
        except subprocess.TimeoutExpired:
            daemon.kill()
            daemon.wait()
    try:
        os.kill(munge_pid, signal.SIGTERM)
        wait_until(lambda: not running(munge_pid), 10)
    except (NameError, ProcessLookupError):
        pass
    shutil.rmtree(tmp, ignore_errors=True)

for failure in failures:
    print("FAIL:", failure)
print(f"{'failed' if failures else 'passed'}: sweep on a one-node Slurm")
sys.exit(1 if failures else 0)
