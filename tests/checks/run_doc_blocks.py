#!/usr/bin/env python3
"""Runs the code blocks of Markdown files, so that their samples cannot go stale.

  run_doc_blocks.py --source SRC --build BUILD [--python-path DIR] [--python EXE] FILE.md|DIR...
  run_doc_blocks.py --self-test      (the transcript matcher's own checks)

Each file's blocks run in order in one fresh temporary folder (later blocks may use what earlier
ones wrote, as a reader following the page would), which holds links to the source tree's
folders, a copy of reference_images/ (tools/bless.sh writes there), `build` linked to BUILD, and
is HOME; `softtrace` is BUILD's. A block must not configure `build` (`cmake -S . -B build`
would point BUILD at the temporary folder): such blocks are norun. By the fence's info string:

  ```sh, ```bash   a script: run with bash -e; it must exit 0.
  ```console       a transcript: each "$ command" line runs (in one shell, so `echo $?` works),
                   and its output (stdout and stderr) must be the lines below it. In those lines
                   "..." stands for any text, and a line that is only "..." for any lines.
  ```python        run with --python (PYTHONPATH: --python-path); it must exit 0. Without
                   --python-path (a build without the module) they are counted as skipped.
  ```sh norun      not run: kept for commands that need a cluster or a long time, or that install
                   into the reader's environment (a venv, pip).

Other blocks (```json, ```cpp, plain ``` synopses) are not run, but a plain block with a line
starting "$ " is an error: a transcript must say ```console to be checked. Exit status 0 when
every block passed, 1 otherwise (each failure is printed with FILE:LINE), 2 on bad usage.
"""
import argparse
import os
import re
import shutil
import subprocess
import sys
import tempfile

RUN_LANGUAGES = {"sh", "bash", "console", "python"}
LINKED = ["scenes", "tests", "tools", "examples", "docs", "python", "fieldlib", "renderer",
          "cmake", "CMakeLists.txt", "README.md"]
TIMEOUT = 300


def blocks(path):
    """(line, language, flags, text) of every fenced block of a Markdown file."""
    out, current = [], None
    with open(path, encoding="utf-8") as f:
        for number, line in enumerate(f, 1):
            if current is None:
                m = re.match(r"^```(\S*)\s*(.*)$", line.rstrip("\n"))
                if m:
                    current = (number, m.group(1), m.group(2).split(), [])
            elif line.startswith("```"):
                out.append((current[0], current[1], current[2], "".join(current[3])))
                current = None
            else:
                current[3].append(line)
    if current is not None:
        raise SystemExit(f"{path}:{current[0]}: a code block is not closed")
    return out


def transcript_matches(expected, actual):
    """Whether `actual` lines match `expected` lines ("..." wildcards)."""
    def line_ok(e, a):
        pattern = ".*".join(re.escape(part) for part in e.split("..."))
        return re.fullmatch(pattern, a) is not None

    def match(i, j):
        if i == len(expected):
            return j == len(actual)
        if expected[i] == "...":
            return any(match(i + 1, k) for k in range(j, len(actual) + 1))
        return j < len(actual) and line_ok(expected[i], actual[j]) and match(i + 1, j + 1)

    return match(0, 0)


def run_console(text, env, cwd):
    """Runs a transcript; returns (ok, report)."""
    commands, expected = [], []
    for line in text.splitlines():
        if line.startswith("$ "):
            commands.append(line[2:])
            expected.append([])
        elif commands:
            expected[-1].append(line)
        elif line.strip():
            return False, "text before the first '$ ' line: " + line
    marker = "@@doc-block-output@@"
    script = "status=0\n"
    for c in commands:
        script += f"echo {marker}; (exit $status); {{ {c}\n}} 2>&1; status=$?\n"
    r = subprocess.run(["bash", "-c", script], cwd=cwd, env=env, capture_output=True,
                       text=True, timeout=TIMEOUT, stdin=subprocess.DEVNULL)
    outputs = r.stdout.split(marker + "\n")[1:]
    if len(outputs) != len(commands):
        return False, f"the transcript did not run through:\n{r.stdout}{r.stderr}"
    report, ok = [], True
    for c, e, a in zip(commands, expected, outputs):
        lines = a.splitlines()
        if not transcript_matches(e, lines):
            ok = False
            report.append(f"$ {c}\n  expected:\n" + "".join(f"    {x}\n" for x in e) +
                          "  got:\n" + "".join(f"    {x}\n" for x in lines))
    return ok, "".join(report)


def run_file(path, args):
    folder = tempfile.mkdtemp(prefix="doc-blocks-")
    try:
        for name in LINKED:
            if os.path.exists(os.path.join(args.source, name)):
                os.symlink(os.path.join(args.source, name), os.path.join(folder, name))
        shutil.copytree(os.path.join(args.source, "reference_images"),
                        os.path.join(folder, "reference_images"))
        os.symlink(args.build, os.path.join(folder, "build"))
        env = dict(os.environ, HOME=folder, PATH=args.build + os.pathsep + os.environ["PATH"],
                   BUILD_DIR=args.build)
        if args.python_path:
            env["PYTHONPATH"] = args.python_path
        ran = failed = skipped = 0
        for line, language, flags, text in blocks(path):
            where = f"{path}:{line}"
            if language not in RUN_LANGUAGES:
                if language == "" and re.search(r"^\$ ", text, re.M):
                    print(f"{where}: a transcript ('$ ' lines) in a plain block: mark it ```console")
                    failed += 1
                continue
            if "norun" in flags or (language == "python" and not args.python_path):
                skipped += 1
                continue
            ran += 1
            try:
                if language == "console":
                    ok, report = run_console(text, env, folder)
                else:
                    command = [args.python, "-c", text] if language == "python" else \
                        ["bash", "-e", "-c", text]
                    r = subprocess.run(command, cwd=folder, env=env, capture_output=True,
                                       text=True, timeout=TIMEOUT, stdin=subprocess.DEVNULL)
                    ok = r.returncode == 0
                    report = f"exit status {r.returncode}\n{r.stdout}{r.stderr}"
            except subprocess.TimeoutExpired:
                ok, report = False, f"took more than {TIMEOUT} s (mark it norun if it must)"
            if not ok:
                failed += 1
                print(f"{where}: the ```{language} block fails:\n{report}")
        return ran, failed, skipped
    finally:
        shutil.rmtree(folder, ignore_errors=True)


def self_test():
    """The runner's own checks: a transcript that differs fails, wildcards match what they say."""
    assert transcript_matches(["a", "b"], ["a", "b"])
    assert not transcript_matches(["a", "b"], ["a", "c"])
    assert not transcript_matches(["a"], ["a", "b"])
    assert not transcript_matches(["a", "b"], ["a"])
    assert transcript_matches(["in ... s (3.8 evaluations/ray)"], ["in 0.02 s (3.8 evaluations/ray)"])
    assert not transcript_matches(["in ... s (3.8 evaluations/ray)"], ["in 0.02 s (25.1 evaluations/ray)"])
    assert transcript_matches(["x", "...", "y"], ["x", "1", "2", "y"])
    assert transcript_matches(["x", "...", "y"], ["x", "y"])
    assert not transcript_matches(["x", "...", "y"], ["x", "1"])
    assert transcript_matches(["a (b) [c]*"], ["a (b) [c]*"])  # regex characters are literal
    env = dict(os.environ)
    ok, _ = run_console("$ echo one\none\n$ false\n$ echo $?\n1\n", env, tempfile.gettempdir())
    assert ok
    ok, report = run_console("$ echo one\ntwo\n", env, tempfile.gettempdir())
    assert not ok and "expected" in report
    print("run_doc_blocks: self-test passed")
    return 0


def main():
    if sys.argv[1:] == ["--self-test"]:
        return self_test()
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--source", required=True)
    parser.add_argument("--build", required=True)
    parser.add_argument("--python-path", default="")
    parser.add_argument("--python", default="python3", help="the interpreter of ```python blocks")
    parser.add_argument("files", nargs="+", help="Markdown files, or folders: their *.md")
    args = parser.parse_args()
    args.source, args.build = os.path.abspath(args.source), os.path.abspath(args.build)
    files = []
    for path in args.files:
        if os.path.isdir(path):
            files += sorted(os.path.join(path, f) for f in os.listdir(path) if f.endswith(".md"))
        else:
            files.append(path)
    total_ran = total_failed = total_skipped = 0
    for path in files:
        ran, failed, skipped = run_file(os.path.abspath(path), args)
        print(f"{os.path.relpath(path, args.source)}: {ran} blocks run, {failed} failed, "
              f"{skipped} not run (norun, or Python without the module)")
        total_ran, total_failed, total_skipped = (total_ran + ran, total_failed + failed,
                                                  total_skipped + skipped)
    if total_ran == 0:
        print("run_doc_blocks: no block ran")
        return 1
    return 1 if total_failed else 0


if __name__ == "__main__":
    sys.exit(main())
