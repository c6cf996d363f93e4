#!/usr/bin/python3
"""`runout study --launcher slurm` against a real Slurm started on this machine.

    slurm_study.py RUNOUT_BINARY SOURCE_DIR

Starts munged, slurmctld and slurmd (Debian 12's slurm-wlm and munge, as
root) with a generated slurm.conf in a folder of its own (the recipe of
shared/BUILD.md, "A real Slurm on one machine"), runs one study of 16
coarse runs with the local launcher and the same study through Slurm,
cancels one running element of the job array (as a pre-emption would), and
asserts that the study submitted that element again, that the array states
its cores, memory and time, that the two CSVs hold the same values (all
columns but the wall time, the memory and what is derived from them), and
that the daemons are gone after it stopped them, also when an assertion
failed. Exit 77 (skipped) with the reason when the
daemons cannot be started here.
"""
import csv
import glob
import json
import os
import pwd
import shutil
import signal
import socket
import subprocess
import sys
import tempfile
import time

SKIP = 77
# Columns that measure this machine at that moment, not the run's result.
TIMING = {"wall_s", "particle_steps_per_s", "peak_memory_mib", "pareto"}
TOOLS = ("munged", "slurmctld", "slurmd", "sbatch", "sinfo", "squeue", "scancel", "runuser")
# 16 runs of case 1 at 0.8 m cells, 5 s each: seconds apiece on one core.
STUDY = ["--cells", "0.8", "--ppc", "1", "--end", "5", "--threads", "1",
         "--set", "material.clay.su0=2000,2500,3000,3500",
         "--set", "base.shear_strength=500,750,1000,1250"]


def skip(reason):
    print("SKIP: " + reason)
    sys.exit(SKIP)


def free_port():
    with socket.socket() as s:
        s.bind(("", 0))
        return s.getsockname()[1]


class Daemons:
    """munged, slurmctld and slurmd in `root`, stopped by their pid files."""

    def __init__(self, root):
        self.root = root
        self.munge = os.path.join(root, "munge")
        self.pid_files = [os.path.join(root, n) for n in ("slurmd.pid", "slurmctld.pid")]
        self.pid_files.append(os.path.join(self.munge, "munged.pid"))
        self.conf = os.path.join(root, "slurm.conf")

    def start(self):
        # munged checks its folders: the socket's must be searchable by all,
        # the key the munge user's alone.
        os.chmod(self.root, 0o755)
        os.mkdir(self.munge, 0o711)
        user = pwd.getpwnam("munge")
        key = os.path.join(self.munge, "munge.key")
        with open(key, "wb") as f:
            f.write(os.urandom(1024))
        os.chmod(key, 0o400)
        for path in (self.munge, key):
            os.chown(path, user.pw_uid, user.pw_gid)
        os.chmod(self.munge, 0o711)
        socket_path = os.path.join(self.munge, "munge.socket")
        subprocess.run(["runuser", "-u", "munge", "--", "munged", "-S", socket_path,
                        "--key-file=" + key, "--pid-file=" + self.pid_files[2],
                        "--log-file=" + os.path.join(self.munge, "munged.log"),
                        "--seed-file=" + os.path.join(self.munge, "munged.seed")],
                       check=True, capture_output=True)
        host = socket.gethostname().split(".")[0]
        for d in ("state", "spool", "log"):
            os.mkdir(os.path.join(self.root, d))
        memory_mb = os.sysconf("SC_PAGE_SIZE") * os.sysconf("SC_PHYS_PAGES") // 2**20 // 2
        with open(self.conf, "w") as f:
            f.write("\n".join([
                "ClusterName=runouttest", "SlurmctldHost=" + host,
                "SlurmctldPort=%d" % free_port(), "SlurmdPort=%d" % free_port(),
                "SlurmUser=root", "AuthType=auth/munge", "CredType=cred/munge",
                "AuthInfo=socket=" + socket_path,
                "ProctrackType=proctrack/linuxproc", "TaskPlugin=task/none",
                "SelectType=select/cons_tres", "SelectTypeParameters=CR_Core_Memory",
                "JobAcctGatherType=jobacct_gather/none", "MailProg=/bin/true",
                "StateSaveLocation=" + os.path.join(self.root, "state"),
                "SlurmdSpoolDir=" + os.path.join(self.root, "spool"),
                "SlurmctldPidFile=" + self.pid_files[1], "SlurmdPidFile=" + self.pid_files[0],
                "SlurmctldLogFile=" + os.path.join(self.root, "log", "slurmctld.log"),
                "SlurmdLogFile=" + os.path.join(self.root, "log", "slurmd.log"),
                "ReturnToService=2", "KillWait=5",
                "NodeName=%s CPUs=%d RealMemory=%d State=UNKNOWN" % (host, os.cpu_count(), memory_mb),
                "PartitionName=debug Nodes=%s Default=YES MaxTime=INFINITE State=UP" % host,
                ""]))
        os.environ["SLURM_CONF"] = self.conf
        subprocess.run(["slurmctld", "-f", self.conf], check=True, capture_output=True)
        subprocess.run(["slurmd", "-f", self.conf], check=True, capture_output=True)
        deadline = time.time() + 30
        while time.time() < deadline:
            out = subprocess.run(["sinfo", "-h", "-o", "%t"], capture_output=True, text=True)
            if out.stdout.strip() == "idle":
                return
            time.sleep(0.5)
        raise RuntimeError("the node is not idle after 30 s: " + out.stdout + out.stderr)

    def pids(self):
        pids = []
        for path in self.pid_files:
            try:
                with open(path) as f:
                    pids.append(int(f.read().split()[0]))
            except (OSError, ValueError, IndexError):
                pass
        return pids

    def stop(self):
        """Stops each daemon by its pid file; the pids still alive after it."""
        pids = self.pids()
        for pid in pids:
            try:
                os.kill(pid, signal.SIGTERM)
            except ProcessLookupError:
                pass
        deadline = time.time() + 20
        alive = pids
        while alive and time.time() < deadline:
            time.sleep(0.2)
            alive = [p for p in alive if os.path.exists("/proc/%d" % p)]
        return alive


def study(runout, scene, out, *extra):
    return subprocess.Popen([runout, "study", scene, *STUDY, "--out", out, *extra],
                            stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)


def rows(path):
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def finished(slurm_dir, k):
    """Whether element k's run ended by itself (its summary says so)."""
    for path in glob.glob(os.path.join(slurm_dir, "runs", "*_p%d" % k, "summary.json")):
        with open(path) as f:
            return json.load(f).get("status") in ("completed", "at_rest")
    return False


def cancel_one_running_element(process, slurm_dir):
    """Cancels an element seen running (scancel, as a pre-emption would stop
    it: SIGTERM, then SIGKILL) before its run ends; its array index. A run
    takes about a second, so the one squeue shows running may end before
    the cancel reaches it: then another is tried."""
    tried = set()
    while process.poll() is None:
        running = subprocess.run(["squeue", "-h", "-t", "R", "-o", "%i"], capture_output=True,
                                 text=True).stdout.split()
        running = [j for j in running if "_" in j and int(j.split("_")[1]) not in tried]
        if running:
            job, k = running[0], int(running[0].split("_")[1])
            tried.add(k)
            subprocess.run(["scancel", job], check=True)
            deadline = time.monotonic() + 30
            while time.monotonic() < deadline and job in subprocess.run(
                    ["squeue", "-h", "-o", "%i"], capture_output=True, text=True).stdout.split():
                time.sleep(0.1)
            if not finished(slurm_dir, k):
                return k
        time.sleep(0.1)
    raise AssertionError("the study ended before an element could be cancelled while running")


def check_studies(runout, source, root):
    scene = os.path.join(source, "scenes", "case1_elongation.toml")
    local_dir, slurm_dir = os.path.join(root, "local"), os.path.join(root, "slurm")
    local = study(runout, scene, local_dir, "--jobs", "2")
    output = local.communicate()[0]
    assert local.returncode == 0, output

    on_slurm = study(runout, scene, slurm_dir, "--launcher", "slurm", "--max-resubmits", "2")
    killed = cancel_one_running_element(on_slurm, slurm_dir)
    output = on_slurm.communicate()[0]
    assert on_slurm.returncode == 0, output

    # The cancelled element went to a second submission, with none that
    # had finished.
    submissions = rows(os.path.join(slurm_dir, "slurm", "submissions.csv"))
    assert len(submissions) == 2, submissions
    assert submissions[0]["elements"] == "0-15", submissions
    assert submissions[1]["elements"] == str(killed), (killed, submissions)

    # The request states its resources: one core per run (--threads 1), the
    # memory estimate plus the process's 64 MiB, 5 minutes at least.
    with open(os.path.join(slurm_dir, "slurm", "array.sh")) as f:
        request = dict(line[len("#SBATCH "):].strip().lstrip("-").split("=", 1)
                       for line in f if line.startswith("#SBATCH ") and "=" in line)
    assert request["cpus-per-task"] == "1", request
    assert request["mem"].endswith("M") and int(request["mem"][:-1]) > 64, request
    assert int(request["time"]) >= 5, request

    a, b = rows(os.path.join(local_dir, "study.csv")), rows(os.path.join(slurm_dir, "study.csv"))
    assert len(a) == 16 and len(b) == 16, (len(a), len(b))
    for ra, rb in zip(a, b):
        assert ra["status"] == "ok", ra
        for column in ra:
            if column not in TIMING:
                assert ra[column] == rb[column], (ra["id"], column, ra[column], rb[column])
    print("local and slurm studies agree on %d rows; element %d cancelled and resubmitted"
          % (len(a), killed))


def main():
    runout, source = sys.argv[1], sys.argv[2]
    if os.geteuid() != 0:
        skip("needs root to start munged and slurmd")
    missing = [t for t in TOOLS if shutil.which(t) is None]
    if missing:
        skip("not installed: %s (scripts/install-deps installs slurm-wlm and munge)"
             % " ".join(missing))
    try:
        pwd.getpwnam("munge")
    except KeyError:
        skip("no munge user")
    root = tempfile.mkdtemp(prefix="runout_slurm_")
    daemons = Daemons(root)
    try:
        daemons.start()
    except (subprocess.CalledProcessError, RuntimeError, OSError) as e:
        daemons.stop()
        detail = (getattr(e, "stderr", b"") or b"").decode(errors="replace")
        skip("the daemons did not start: %s %s (logs in %s)" % (e, detail, root))
    passed = False
    try:
        check_studies(os.path.abspath(runout), source, root)
        passed = True
    finally:
        alive = daemons.stop()
        if alive:
            print("FAIL: daemons still running after they were stopped: %s" % alive)
        if passed and not alive:
            shutil.rmtree(root, ignore_errors=True)
        else:
            print("kept for a look: " + root)
    sys.exit(1 if alive else 0)


if __name__ == "__main__":
    main()
