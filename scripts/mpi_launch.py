"""How the benchmark scripts start work on several MPI ranks (Open MPI's
mpirun on this machine; under Slurm, start the script with srun instead)."""
import os


def mpirun_command(ranks):
    """The mpirun prefix for `ranks` ranks on this machine: more ranks than
    cores allowed, no pinning (each run's own threads decide), root allowed."""
    root = ["--allow-run-as-root"] if os.geteuid() == 0 else []
    return ["mpirun", "-n", str(ranks), "--oversubscribe", "--bind-to", "none", *root]
