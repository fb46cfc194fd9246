"""scripts/mpi_launch.run_each: every command runs exactly once over an
`mpirun -n 4` job (more ranks than this machine's cores), more than one rank
takes some, and a failing command comes back with its status and stderr.
Skipped where mpirun is absent."""
import os
import shutil
import sys

import pytest

sys.path.insert(0, os.path.join(os.environ.get("TOUCHCLOUD_SOURCE_DIR", os.getcwd()), "scripts"))
from mpi_launch import run_each  # noqa: E402

needs_mpirun = pytest.mark.skipif(shutil.which("mpirun") is None,
                                  reason="needs mpirun (apt-get install openmpi-bin; scripts/install-deps.sh)")

# Appends the rank it ran on to FILE, after 0.3 s (so that the other ranks take the next ones).
APPEND_RANK = ("import os, sys, time; time.sleep(0.3); "
               "open(sys.argv[1], 'a').write(os.environ['OMPI_COMM_WORLD_RANK'] + '\\n')")


@needs_mpirun
def test_each_command_runs_once_and_failures_come_back(tmp_path):
    outputs = [tmp_path / f"run{i}.txt" for i in range(8)]
    commands = [[sys.executable, "-c", APPEND_RANK, str(out)] for out in outputs]
    failing = ["sh", "-c", "echo 'no such press' >&2; exit 3"]
    commands.insert(5, failing)
    failed = run_each(commands, 4, str(tmp_path / "jobs"))

    assert failed == [(failing, 3, "no such press\n")]
    ranks = set()
    for out in outputs:
        lines = out.read_text().splitlines()
        assert len(lines) == 1, f"{out.name} ran {len(lines)} times, on ranks {lines}"
        ranks.add(int(lines[0]))
    assert len(ranks) > 1 and ranks <= {0, 1, 2, 3}, ranks
    assert os.listdir(tmp_path / "jobs") == [], "the job's bookkeeping is removed"


@needs_mpirun
def test_the_command_line_runs_a_json_list_and_names_what_failed(tmp_path):
    import json
    import subprocess
    outputs = [tmp_path / f"run{i}.txt" for i in range(3)]
    commands = [[sys.executable, "-c", APPEND_RANK, str(out)] for out in outputs]
    (tmp_path / "commands.json").write_text(json.dumps(commands))
    launcher = os.path.join(os.path.dirname(sys.modules["mpi_launch"].__file__), "mpi_launch.py")
    done = subprocess.run([sys.executable, launcher, "--ranks", "2", str(tmp_path / "commands.json")],
                          capture_output=True, text=True)
    assert done.returncode == 0, done.stderr
    assert all(len(out.read_text().splitlines()) == 1 for out in outputs)

    commands.append(["sh", "-c", "echo 'no such press' >&2; exit 3"])
    (tmp_path / "commands.json").write_text(json.dumps(commands))
    done = subprocess.run([sys.executable, launcher, "--ranks", "2", str(tmp_path / "commands.json")],
                          capture_output=True, text=True)
    assert done.returncode == 1
    assert "exit 3" in done.stderr and "failed (3)" in done.stderr and "no such press" in done.stderr
    assert sorted(os.listdir(tmp_path)) == ["commands.json"] + [out.name for out in outputs], "bookkeeping removed"
