"""How the benchmark scripts start work on several MPI ranks (Open MPI's
mpirun on this machine; under Slurm, start the script with srun instead).

Run as `python3 mpi_launch.py FOLDER` on every rank of an mpirun job (what
run_each does), it runs the commands of FOLDER/commands.json: each rank takes
the next command no rank has taken yet (an exclusive file in FOLDER, which
every rank must see) and records each one's exit status and stderr in
FOLDER/result-I.json.

`python3 mpi_launch.py --ranks N COMMANDS.json` is run_each for programs
that are not Python (a JSON list of commands, each a list of arguments; the
job's folder beside the file): it prints each failure's command, status and
stderr, and exits 1 if any failed."""
import json
import os
import subprocess
import sys
import tempfile


def mpirun_command(ranks):
    """The mpirun prefix for `ranks` ranks on this machine: more ranks than
    cores allowed, no pinning (each run's own threads decide), root allowed."""
    root = ["--allow-run-as-root"] if os.geteuid() == 0 else []
    return ["mpirun", "-n", str(ranks), "--oversubscribe", "--bind-to", "none", *root]


def launched_ranks():
    """(rank, size) as mpirun (Open MPI) or srun (PMIx) tell it; (0, 1) alone."""
    for rank, size in (("OMPI_COMM_WORLD_RANK", "OMPI_COMM_WORLD_SIZE"), ("PMIX_RANK", "SLURM_NTASKS")):
        if rank in os.environ and size in os.environ:
            return int(os.environ[rank]), int(os.environ[size])
    return 0, 1


def run_each(commands, ranks, parent):
    """Runs every command (a list of arguments) once, spread over one
    `mpirun -n RANKS` job; a new folder in PARENT (which every rank must see)
    holds the job's bookkeeping and is removed after. Returns the failures
    as (command, exit status, stderr), in the commands' order."""
    os.makedirs(parent, exist_ok=True)
    folder = tempfile.mkdtemp(prefix="mpi-each-", dir=parent)
    with open(os.path.join(folder, "commands.json"), "w") as f:
        json.dump(commands, f)
    job = subprocess.run(mpirun_command(ranks) + [sys.executable, os.path.abspath(__file__), folder],
                         capture_output=True, text=True)
    failed = []
    for i, command in enumerate(commands):
        record = os.path.join(folder, f"result-{i}.json")
        if not os.path.exists(record):  # a rank died, and mpirun ended the job
            failed.append((command, job.returncode, f"not finished: the mpirun job ended ({job.returncode}):\n"
                                                    f"{job.stderr}"))
            continue
        with open(record) as f:
            status, stderr = json.load(f)
        if status != 0:
            failed.append((command, status, stderr))
    subprocess.run(["rm", "-rf", folder], check=True)
    return failed


def run_all(commands, ranks, parent, noun="runs", keep_going=False):
    """Runs every command: one after the other (counting them on stderr), or
    spread over one `mpirun -n RANKS` job (run_each) when ranks > 1; the
    results do not depend on which. RuntimeError naming the first failure,
    or with keep_going every command runs and the failures are returned as
    run_each returns them."""
    if ranks > 1:
        failed = run_each(commands, ranks, parent)
    else:
        failed = []
        for i, cmd in enumerate(commands, 1):
            done = subprocess.run(cmd, capture_output=True, text=True)
            if done.returncode != 0:
                if not keep_going:
                    raise RuntimeError(f"{' '.join(cmd)} failed ({done.returncode}):\n{done.stderr}")
                failed.append((cmd, done.returncode, done.stderr))
            print(f"\r{i}/{len(commands)} {noun}", end="", file=sys.stderr, flush=True)
        print(file=sys.stderr)
    if failed and not keep_going:
        cmd, status, stderr = failed[0]
        raise RuntimeError(f"{len(failed)} {noun} failed; {' '.join(cmd)} ({status}):\n{stderr}")
    return failed


def _run_claimed(folder):
    rank, _ = launched_ranks()
    with open(os.path.join(folder, "commands.json")) as f:
        commands = json.load(f)
    for i, command in enumerate(commands):
        try:
            os.close(os.open(os.path.join(folder, f"claim-{i}"), os.O_CREAT | os.O_EXCL))
        except FileExistsError:
            continue
        done = subprocess.run(command, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
        tmp = os.path.join(folder, f"result-{i}.tmp{rank}")
        with open(tmp, "w") as f:
            json.dump([done.returncode, done.stderr], f)
        os.rename(tmp, os.path.join(folder, f"result-{i}.json"))


def _main(argv):
    if len(argv) == 3 and argv[0] == "--ranks":
        with open(argv[2]) as f:
            commands = json.load(f)
        failed = run_each(commands, int(argv[1]), os.path.dirname(os.path.abspath(argv[2])))
        for command, status, stderr in failed:
            print(f"mpi_launch: {' '.join(command)} failed ({status}):\n{stderr}", file=sys.stderr)
        return 1 if failed else 0
    if len(argv) == 1:
        _run_claimed(argv[0])
        return 0
    print("usage: mpi_launch.py --ranks N COMMANDS.json | mpi_launch.py FOLDER (on each rank)", file=sys.stderr)
    return 2


if __name__ == "__main__":
    sys.exit(_main(sys.argv[1:]))
