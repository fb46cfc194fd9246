#!/usr/bin/env python3
"""Runs or checks every shell command and YAML pipeline the guide shows
(docs/**/*.md fenced code blocks), so the guide cannot drift from the code
(ctest docs.commands).

A block is handled by its language tag and, optionally, an HTML comment on
the line just before its opening fence:

    <!-- docs-test: MODE -->

A block without a language tag is an error: tag commands sh and output
text (or the file's format: csv, json; console for a session with its
output). Shell blocks (sh, bash, shell), one command a line (a trailing
backslash continues it; `#` starts a comment):
  run (the default)  every `touchcloud` command runs and must exit 0
  validate           `touchcloud run|sweep|score|report` get --dry-run: the
                     command line and the pipeline with its overrides are
                     checked, nothing runs (for commands that take minutes);
                     an input file missing only because it lies in the --out
                     folder of an earlier command of the block is accepted
  elsewhere TEST     the ctest test TEST runs what the block shows (installs,
                     builds); the test must exist
  output             not a command: printed output or a file's content
In run and validate blocks, a command under mpirun, mpiexec or srun is
checked without the launcher; other programs (scripts/*.sh, cmake, the
benchmarks) are never run, only a path to one must exist.

YAML blocks (yaml, yml):
  validate (the default)  a whole pipeline: `touchcloud validate` (its
                          relative paths as from a file in pipelines/)
  fragment                part of a pipeline or a scene, not checked alone
  file NAME               written as NAME for the page's commands, which
                          check it

Other tags (cpp, cmake, json, python, text, csv, ...) are not commands and
are skipped. Each page runs in its own scratch folder that mirrors the
repository (its folders' entries linked, build/ the build folder), so a
command writes nothing into the source tree; commands of a page run in order
(a report after its run). Exit 1 when a block fails, naming page and line.

Usage: docs_commands.py --cli BUILD/bin/touchcloud --build BUILD [--ctest CTEST] [--docs DIR] [PAGE.md ...]
"""
import argparse
import os
import re
import shlex
import subprocess
import sys
import tempfile
import time
from pathlib import Path

SHELL_TAGS = {"sh", "bash", "shell"}
YAML_TAGS = {"yaml", "yml"}
LAUNCHERS = {"mpirun", "mpiexec", "srun"}
DRY_RUN_VERBS = {"run", "sweep", "score", "report"}
FENCE = re.compile(r"^(\s*)```\s*([\w+-]*)\s*$")
ANNOTATION = re.compile(r"^\s*<!--\s*docs-test:\s*(.*?)\s*-->\s*$")
COMMAND_TIMEOUT_S = 300


class Block:
    def __init__(self, page, line, tag, annotation, text):
        self.page, self.line, self.tag, self.text = page, line, tag, text
        words = annotation.split(None, 1) if annotation else []
        self.mode = words[0] if words else None
        self.argument = words[1] if len(words) > 1 else ""

    def where(self):
        return f"{self.page}:{self.line}"


def read_blocks(page, shown_as):
    lines = page.read_text().split("\n")
    blocks, i = [], 0
    while i < len(lines):
        m = FENCE.match(lines[i])
        if not m:
            i += 1
            continue
        j = i + 1
        while j < len(lines) and not re.match(r"^\s*```\s*$", lines[j]):
            j += 1
        if j == len(lines):
            raise SystemExit(f"{shown_as}:{i + 1}: a code block that never closes")
        k = i - 1
        while k >= 0 and not lines[k].strip():
            k -= 1
        a = ANNOTATION.match(lines[k]) if k >= 0 else None
        indent = len(m.group(1))
        body = "\n".join(l[indent:] if l[:indent].isspace() else l for l in lines[i + 1:j])
        blocks.append(Block(shown_as, i + 1, m.group(2).lower(), a.group(1) if a else None, body))
        i = j + 1
    return blocks


def commands_of(text):
    """Lines joined at trailing backslashes; blank and comment-only lines dropped."""
    out, pending = [], ""
    for line in text.split("\n"):
        if line.rstrip().endswith("\\"):
            pending += line.rstrip()[:-1] + " "
            continue
        line = pending + line
        pending = ""
        if line.strip() and not line.strip().startswith("#"):
            out.append(line)
    if pending.strip():
        out.append(pending)
    return out


def only_missing_under(stderr, folders):
    """Whether every problem reported is an input file that does not exist
    inside one of the folders (what an earlier, unrun command would write)."""
    problems = [l for l in stderr.strip().split("\n") if not l.startswith("touchcloud: error: ") or "input file" in l]
    if not problems or not folders:
        return False
    for line in problems:
        m = re.search(r"input file (\S+) does not exist", line)
        if not m or not any(Path(m.group(1)).resolve().is_relative_to(f) for f in folders):
            return False
    return True


def mirror(source, build, into):
    """A folder that looks like the repository: each top-level folder a real
    folder of links to its entries (new files land in the scratch folder),
    each file a link, build/ the build folder."""
    for entry in sorted(source.iterdir()):
        if entry.name in {"build", "out", ".git"} or entry.name.startswith("."):
            continue
        if entry.is_dir():
            (into / entry.name).mkdir()
            for child in entry.iterdir():
                (into / entry.name / child.name).symlink_to(child)
        else:
            (into / entry.name).symlink_to(entry)
    (into / "build").symlink_to(build)


class Checker:
    def __init__(self, args):
        self.cli = str(Path(args.cli).resolve())
        self.build = Path(args.build).resolve()
        self.ctest = args.ctest
        self.source = Path(__file__).resolve().parent.parent
        self._tests = None

    def ctest_names(self):
        if self._tests is None:
            listed = subprocess.run([self.ctest, "--test-dir", str(self.build), "-N"], capture_output=True,
                                    text=True, check=True).stdout
            self._tests = set(re.findall(r"Test\s+#\d+:\s+(\S+)", listed))
        return self._tests

    def shell_command(self, line, scratch, mode, earlier_outs):
        """Runs or checks one command line; returns an error or None.
        earlier_outs gathers the --out folders of the block's commands."""
        try:
            words = shlex.split(line, comments=True)
        except ValueError as e:
            return f"cannot split '{line.strip()}': {e}"
        if any(w in {"|", "&&", "||", ";", ">", "<"} or w.startswith("(") for w in words):
            return f"'{line.strip()}' is shell syntax, not one command: mark the block elsewhere or output"
        env = dict(os.environ, PWD=str(scratch))
        while words and re.match(r"^[A-Za-z_][A-Za-z0-9_]*=", words[0]):
            name, value = words.pop(0).split("=", 1)
            env[name] = os.path.expandvars(value.replace("$PWD", str(scratch)))
        if words and words[0] in LAUNCHERS:
            inner = [i for i, w in enumerate(words) if os.path.basename(w) == "touchcloud"]
            if not inner:
                return f"'{line.strip()}': no touchcloud command under {words[0]}"
            words = words[inner[0]:]
        if not words:
            return None
        program = words[0]
        if os.path.basename(program) != "touchcloud":
            if "/" in program and not (scratch / program).exists():
                return f"'{line.strip()}': {program} does not exist"
            return None
        if "..." in words:
            return f"'{line.strip()}': '...' is not an argument; show a whole command"
        argv = [self.cli] + words[1:]
        if mode == "validate" and len(argv) > 1 and argv[1] in DRY_RUN_VERBS:
            argv.insert(2, "--dry-run")
        r = subprocess.run(argv, cwd=scratch, env=env, capture_output=True, text=True, timeout=COMMAND_TIMEOUT_S)
        if mode == "validate" and r.returncode == 2 and only_missing_under(r.stderr, earlier_outs):
            r.returncode = 0
        if "--out" in argv[:-1]:
            earlier_outs.append((scratch / argv[argv.index("--out") + 1]).resolve())
        if r.returncode != 0:
            tail = "\n    ".join((r.stderr or r.stdout).strip().split("\n")[-6:])
            return f"'{' '.join(['touchcloud'] + argv[1:])}' exited {r.returncode}:\n    {tail}"
        return None

    def check(self, block, scratch):
        """Returns (what was done, errors)."""
        mode = block.mode
        if not block.tag:
            return mode or "untagged", ["a block without a language tag: sh for commands, text for output"]
        if block.tag in SHELL_TAGS:
            mode = mode or "run"
            if mode == "output":
                return "output", []
            if mode == "elsewhere":
                if not block.argument:
                    return mode, ["elsewhere needs the ctest test that runs the block"]
                if block.argument not in self.ctest_names():
                    return mode, [f"no ctest test named '{block.argument}'"]
                return f"elsewhere ({block.argument})", []
            if mode not in {"run", "validate"}:
                return mode, [f"'{mode}' is not a mode of a shell block (run, validate, elsewhere TEST, output)"]
            outs = []
            errors = [e for e in (self.shell_command(l, scratch, mode, outs) for l in commands_of(block.text)) if e]
            return mode, errors
        if block.tag in YAML_TAGS:
            mode = mode or "validate"
            if mode == "fragment":
                return mode, []
            if mode == "file":
                name = block.argument
                if not name or name.startswith("/") or ".." in Path(name).parts:
                    return mode, [f"file needs a relative name, got '{name}'"]
                (scratch / name).parent.mkdir(parents=True, exist_ok=True)
                (scratch / name).write_text(block.text + "\n")
                return f"file {name}", []
            if mode != "validate":
                return mode, [f"'{mode}' is not a mode of a YAML block (validate, fragment, file NAME)"]
            folder = scratch / "docs_pipelines"
            folder.mkdir(exist_ok=True)
            path = folder / f"line_{block.line}.yaml"
            path.write_text(block.text + "\n")
            r = subprocess.run([self.cli, "validate", str(path)], cwd=scratch, capture_output=True, text=True,
                               timeout=COMMAND_TIMEOUT_S)
            if r.returncode != 0:
                text = r.stderr.strip().replace(str(path), "the block")
                return mode, [f"touchcloud validate exited {r.returncode}:\n    " + text.replace("\n", "\n    ")]
            return mode, []
        if mode is not None:
            return mode, [f"a '{block.tag}' block is not checked; remove its docs-test annotation"]
        return "skipped", []


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--cli", required=True)
    ap.add_argument("--build", required=True)
    ap.add_argument("--ctest", default="ctest")
    ap.add_argument("--docs", default=None, help="the guide's folder (default: docs/ of this repository)")
    ap.add_argument("pages", nargs="*", help="pages to check (default: every page)")
    args = ap.parse_args()
    checker = Checker(args)
    docs = Path(args.docs).resolve() if args.docs else checker.source / "docs"
    pages = [Path(p).resolve() for p in args.pages] or sorted(docs.rglob("*.md"))
    failures, blocks_seen, started = 0, 0, time.monotonic()
    for page in pages:
        try:
            shown = str(page.relative_to(checker.source))
        except ValueError:
            shown = str(page)
        blocks = read_blocks(page, shown)
        if not any(b.tag in SHELL_TAGS | YAML_TAGS | {""} for b in blocks):
            continue
        with tempfile.TemporaryDirectory(prefix="docs_commands_") as tmp:
            scratch = Path(tmp)
            mirror(checker.source, checker.build, scratch)
            # A page's file blocks exist before its first command.
            ordered = sorted(blocks, key=lambda b: b.mode != "file")
            for block in ordered:
                t0 = time.monotonic()
                try:
                    done, errors = checker.check(block, scratch)
                except subprocess.TimeoutExpired as e:
                    done, errors = block.mode or "run", [f"'{' '.join(e.cmd)}' took over {COMMAND_TIMEOUT_S} s"]
                if done == "skipped":
                    continue
                blocks_seen += 1
                if errors:
                    failures += 1
                    print(f"{block.where()}: error: [{done}] " + "\n  ".join(errors), flush=True)
                else:
                    print(f"{block.where()}: ok [{done}] {time.monotonic() - t0:.1f} s", flush=True)
    print(f"docs_commands: {blocks_seen} blocks, {failures} failed, {time.monotonic() - started:.0f} s")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
