"""A one-node Slurm cluster on this machine, for tests and measurements: munged, slurmctld and
slurmd from Debian's `munge` and `slurm-wlm`, started as root in a temporary folder with a
slurm.conf of their own (ports chosen free on 127.0.0.1 and bound there only; no cgroups, no
accounting), and stopped again by their pids, whatever happens.

    with LocalSlurm() as slurm:          # raises Unavailable(reason) when Slurm cannot start here
        subprocess.run(["sbatch", ...], env=slurm.env)

`slurm.env` is the environment every Slurm command needs (SLURM_CONF, and no SLURM_* or SBATCH_*
variables from an enclosing job). Leaving the block cancels every job still queued and stops the
daemons by their pids: SIGTERM, then SIGKILL after 10 s. Then whatever else this cluster started
(job steps, which slurmd runs detached from itself, and their jobs) is killed: every process whose
environment names this cluster's slurm.conf. A watchdog does the same when the process that started
the cluster ends without leaving the block (killed outright, as by ctest's time-out), so nothing
is left behind.
"""
import ctypes
import os
import shutil
import signal
import socket
import subprocess
import tempfile
import time

DAEMONS = ("munged", "slurmctld", "slurmd")
CLIENTS = ("sbatch", "squeue", "scancel", "sinfo", "scontrol")


class Unavailable(Exception):
    """Slurm cannot run on this machine; the message says why."""


def _die_with_parent():
    # Runs in the child between fork and exec: SIGTERM when the starting thread ends.
    ctypes.CDLL(None, use_errno=True).prctl(1, signal.SIGTERM)  # PR_SET_PDEATHSIG


def _processes_of(conf):
    """The pids of every process whose environment has SLURM_CONF=conf: this cluster's daemons, job
    steps and jobs (the jobs inherit the submitter's environment)."""
    marker = b"SLURM_CONF=" + conf.encode()
    found = []
    for entry in os.listdir("/proc"):
        if not entry.isdigit() or int(entry) == os.getpid():
            continue
        try:
            with open(f"/proc/{entry}/environ", "rb") as f:
                if marker in f.read().split(b"\0"):
                    found.append(int(entry))
        except OSError:
            continue
    return found


def _kill_all_of(conf):
    for _ in range(5):  # a step may fork while we look
        pids = _processes_of(conf)
        if not pids:
            return
        for pid in pids:
            try:
                os.kill(pid, signal.SIGKILL)
            except OSError:
                pass
        time.sleep(0.2)


def _watchdog(conf, root):
    """A process outside the caller's process tree that waits for the caller's end (the pipe's write
    end closes however it ends) and then kills what the cluster left and removes its folder. Returns
    the write end, to be closed once the cluster is stopped."""
    read_end, write_end = os.pipe()
    pid = os.fork()
    if pid == 0:
        try:
            os.setsid()
            if os.fork() > 0:
                os._exit(0)
            null = os.open(os.devnull, os.O_RDWR)
            for fd in (0, 1, 2):
                os.dup2(null, fd)
            os.closerange(3, read_end)
            os.closerange(read_end + 1, 65536)
            while os.read(read_end, 1):
                pass
            _kill_all_of(conf)
            if not os.environ.get("CURVEMESH_KEEP_SLURM"):
                shutil.rmtree(root, ignore_errors=True)
        finally:
            os._exit(0)
    os.waitpid(pid, 0)
    os.close(read_end)
    return write_end


def _free_ports(n):
    sockets = [socket.socket(socket.AF_INET, socket.SOCK_STREAM) for _ in range(n)]
    try:
        for s in sockets:
            s.bind(("127.0.0.1", 0))
        return [s.getsockname()[1] for s in sockets]
    finally:
        for s in sockets:
            s.close()


def _tail(path, lines=15):
    try:
        with open(path, errors="replace") as f:
            return "".join(f.readlines()[-lines:])
    except OSError:
        return ""


def _program(name):
    for folder in ("/usr/sbin", "/usr/bin", "/sbin", "/bin"):
        path = os.path.join(folder, name)
        if os.access(path, os.X_OK):
            return path
    return shutil.which(name)


class LocalSlurm:
    def __init__(self, cpus=None, start_timeout=60):
        self.cpus = cpus or os.cpu_count() or 1
        self.start_timeout = start_timeout
        self.root = self.conf = None
        self.processes = {}  # name -> Popen
        self.env = None
        self.node = None
        self.watchdog = None  # the write end of the watchdog's pipe

    # -- starting ---------------------------------------------------------------------------------
    def __enter__(self):
        try:
            self._start()
        except BaseException:
            self.stop()
            raise
        return self

    def __exit__(self, *exc):
        self.stop()
        return False

    def _start(self):
        if os.geteuid() != 0:
            raise Unavailable("the one-node Slurm needs root (slurmd starts jobs as their user)")
        missing = [p for p in DAEMONS + CLIENTS if not _program(p)]
        if missing:
            raise Unavailable("not installed: " + ", ".join(missing) + " (scripts/install-deps.sh installs them)")
        self.root = tempfile.mkdtemp(prefix="curvemesh-slurm-")
        os.chmod(self.root, 0o755)  # munged wants every folder above its socket searchable by all
        key_dir, run_dir = os.path.join(self.root, "munge"), os.path.join(self.root, "run")
        for d, mode in ((key_dir, 0o700), (run_dir, 0o755), (os.path.join(self.root, "state"), 0o700),
                        (os.path.join(self.root, "spool"), 0o755), (os.path.join(self.root, "log"), 0o755)):
            os.mkdir(d)
            os.chmod(d, mode)
        key = os.path.join(key_dir, "munge.key")
        fd = os.open(key, os.O_WRONLY | os.O_CREAT | os.O_EXCL, 0o400)
        with os.fdopen(fd, "wb") as f:
            f.write(os.urandom(1024))
        self.socket = os.path.join(run_dir, "munge.socket")

        self.env = {k: v for k, v in os.environ.items() if not k.startswith(("SLURM_", "SBATCH_", "SALLOC_", "SRUN_"))}
        self.conf = os.path.join(self.root, "slurm.conf")
        self.env["SLURM_CONF"] = self.conf
        self.watchdog = _watchdog(self.conf, self.root)
        self.node = socket.gethostname().split(".")[0]
        ctld_port, slurmd_port = _free_ports(2)
        with open("/proc/meminfo") as f:
            mem_mb = next(int(l.split()[1]) // 1024 for l in f if l.startswith("MemTotal:"))
        self.memory_mb = max(100, int(mem_mb * 0.9))
        r = self.root
        with open(self.conf, "w") as f:
            f.write(f"""# A one-node cluster for curvemesh's tests: this machine, 127.0.0.1 only, no cgroups, no accounting.
ClusterName=curvemesh-test
SlurmctldHost={self.node}(127.0.0.1)
SlurmctldPort={ctld_port}
SlurmdPort={slurmd_port}
CommunicationParameters=NoInAddrAny,NoCtldInAddrAny
AuthType=auth/munge
CredType=cred/munge
AuthInfo=socket={self.socket}
SlurmUser=root
SlurmdUser=root
StateSaveLocation={r}/state
SlurmdSpoolDir={r}/spool
SlurmctldPidFile={r}/run/slurmctld.pid
SlurmdPidFile={r}/run/slurmd.pid
SlurmctldLogFile={r}/log/slurmctld.log
SlurmdLogFile={r}/log/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
JobCompType=jobcomp/none
MpiDefault=none
SwitchType=switch/none
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
SchedulerType=sched/backfill
MailProg=/bin/true
ReturnToService=2
KillWait=5
MinJobAge=600
InactiveLimit=0
NodeName={self.node} NodeAddr=127.0.0.1 CPUs={self.cpus} RealMemory={self.memory_mb} State=UNKNOWN
PartitionName=local Nodes={self.node} Default=YES MaxTime=INFINITE State=UP
""")
        self._daemon("munged", [_program("munged"), "--foreground", f"--key-file={key}", f"--socket={self.socket}",
                                f"--pid-file={run_dir}/munged.pid", f"--log-file={self.root}/log/munged.log",
                                f"--seed-file={key_dir}/munged.seed"])
        self._wait_for(lambda: os.path.exists(self.socket), "munged's socket", "munged")
        self._daemon("slurmctld", [_program("slurmctld"), "-D", "-f", self.conf])
        self._daemon("slurmd", [_program("slurmd"), "-D", "-f", self.conf, "-N", self.node])
        self._wait_for(self._node_idle, f"node {self.node} idle", "slurmd")

    def _daemon(self, name, argv):
        with open(os.path.join(self.root, "log", name + ".out"), "wb") as out:
            self.processes[name] = subprocess.Popen(argv, stdin=subprocess.DEVNULL, stdout=out, stderr=out,
                                                    env=self.env, preexec_fn=_die_with_parent)

    def _node_idle(self):
        r = self.run(["sinfo", "-h", "-n", self.node, "-o", "%t"], check=False)
        return r.returncode == 0 and r.stdout.strip() == "idle"

    def _wait_for(self, ready, what, last):
        deadline = time.monotonic() + self.start_timeout
        while time.monotonic() < deadline:
            for name, p in self.processes.items():
                if p.poll() is not None:
                    raise Unavailable(f"{name} exited with {p.returncode} before {what}:\n" + self.logs(name))
            if ready():
                return
            time.sleep(0.2)
        raise Unavailable(f"no {what} within {self.start_timeout} s:\n" + self.logs(last))

    def logs(self, name):
        text = ""
        for f in (name + ".out", name + ".log"):
            t = _tail(os.path.join(self.root, "log", f))
            if t:
                text += f"--- {f}\n{t}"
        return text

    # -- using ------------------------------------------------------------------------------------
    def run(self, argv, check=True, timeout=60, **kwargs):
        """Runs a Slurm client (or anything) against this cluster; returns the CompletedProcess."""
        r = subprocess.run(argv, env=self.env, capture_output=True, text=True, timeout=timeout,
                           stdin=subprocess.DEVNULL, **kwargs)
        if check and r.returncode != 0:
            raise RuntimeError(f"{' '.join(argv)}: exit {r.returncode}: {r.stderr.strip()}")
        return r

    def queued(self, jobs):
        """The jobs (ids, as strings) still pending or running, array tasks included."""
        r = self.run(["squeue", "-h", "-o", "%i %T", "-j", ",".join(jobs)], check=False)
        return [l for l in r.stdout.splitlines() if l.strip()]

    def wait(self, jobs, timeout):
        """Waits until none of the jobs is queued or running; False when `timeout` s passed first."""
        deadline = time.monotonic() + timeout
        while time.monotonic() < deadline:
            if not self.queued(jobs):
                return True
            time.sleep(0.2)
        return False

    def state(self, job):
        """JobState of a job that slurmctld still knows (MinJobAge: 10 minutes), e.g. COMPLETED."""
        r = self.run(["scontrol", "-o", "show", "job", str(job)], check=False)
        for field in r.stdout.split():
            if field.startswith("JobState="):
                return field.split("=", 1)[1]
        return None

    # -- stopping ---------------------------------------------------------------------------------
    def stop(self):
        if self.processes.get("slurmctld") and self.processes["slurmctld"].poll() is None:
            # Every job of this private cluster, so that no job step outlives the daemons.
            r = self.run(["squeue", "-h", "-o", "%A"], check=False, timeout=20)
            jobs = sorted(set(r.stdout.split()))
            if jobs:
                self.run(["scancel", *jobs], check=False, timeout=20)
                self.wait(jobs, 20)
        for name in reversed(DAEMONS):
            p = self.processes.get(name)
            if p is None or p.poll() is not None:
                continue
            p.terminate()
            try:
                p.wait(timeout=10)
            except subprocess.TimeoutExpired:
                p.kill()
                p.wait(timeout=10)
        self.processes = {}
        if self.conf:
            _kill_all_of(self.conf)
        if self.watchdog is not None:
            os.close(self.watchdog)
            self.watchdog = None
        if self.root and not os.environ.get("CURVEMESH_KEEP_SLURM"):
            shutil.rmtree(self.root, ignore_errors=True)
