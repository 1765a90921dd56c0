"""Runs the ```console blocks of Markdown documents and compares what each command prints
with what the document shows, so that a documented output or error message stays true.

    /usr/bin/python3 tests/docs/run_doc_console.py docs/formats.md
    /usr/bin/python3 tests/docs/run_doc_console.py docs/analyze.md \
        --setup 'pedesis run SRC/examples/course_1_relaxation.toml --out runs/demo'

A console block is a transcript:

    $ pedesis run bad.toml
    pedesis: error: bad.toml:3:1: ...
    [exit 2]

* A line beginning with `$ ` is a command, run by bash (`set -o pipefail`) in a fresh
  directory outside the source tree, shared by every block of the document, in order.
  Each command is its own shell: `cd` and variables do not carry over. A command ending
  in `\\` continues on the next line; a here-document (`<<'EOF'` … `EOF`) takes the
  lines up to its terminator, so a block can write the config it runs.
* `pedesis` and `build/pedesis` mean $PEDESIS_BIN, `python3` the interpreter running
  this script; `examples/` is the source tree's
  (linked into the directory, read only by the commands).
* The lines after a command, up to the next `$ ` or the block's end, are its expected
  output, stdout and stderr together as a terminal shows them, compared line by line
  exactly (trailing spaces ignored), with two wildcards:
    - a line `...` matches any number of lines (none included);
    - `[...]` inside a line matches any text within that line (timings, rates).
* The command must exit 0, unless the output ends with the line `[exit N]`: then it
  must exit with N.

Blocks that are only illustrations stay ```sh or ```text and are not run.
--setup runs a shell command in the directory first (the runs a document takes as
made); SRC in it is the source tree, and `pedesis` is $PEDESIS_BIN.
"""
import os
import pathlib
import re
import subprocess
import sys
import tempfile

BLOCK = re.compile(r"^```console\n(.*?)^```", re.S | re.M)
HEREDOC = re.compile(r"<<-?\s*(['\"]?)(\w+)\1")
EXIT = re.compile(r"^\[exit (\d+)\]$")
SOURCE = pathlib.Path(__file__).resolve().parents[2]


def transcripts(text):
    """(line in the document, command, expected lines) for every command of every block."""
    for match in BLOCK.finditer(text):
        first = text.count("\n", 0, match.start()) + 2
        lines = match.group(1).splitlines()
        k = 0
        while k < len(lines):
            if not lines[k].startswith("$ "):
                raise ValueError(f"line {first + k}: output before any command: {lines[k]!r}")
            start = k
            command = [lines[k][2:]]
            while command[-1].endswith("\\") and k + 1 < len(lines):
                k += 1
                command.append(lines[k])
            heredoc = HEREDOC.search(command[0])
            if heredoc:
                end = heredoc.group(2)
                while k + 1 < len(lines) and lines[k].strip() != end:
                    k += 1
                    command.append(lines[k])
                if lines[k].strip() != end:
                    raise ValueError(f"line {first + start}: here-document without {end}")
            k += 1
            expected = []
            while k < len(lines) and not lines[k].startswith("$ "):
                expected.append(lines[k])
                k += 1
            yield first + start, "\n".join(command), expected


def line_matches(pattern, line):
    if "[...]" not in pattern:
        return pattern.rstrip() == line.rstrip()
    parts = [re.escape(p) for p in pattern.rstrip().split("[...]")]
    return re.fullmatch(".*".join(parts), line.rstrip(), re.S) is not None


def output_matches(expected, actual):
    """Whether the lines actual fit the pattern lines expected (`...` any lines)."""
    if not expected:
        return not actual
    if expected[0] == "...":
        return any(output_matches(expected[1:], actual[k:]) for k in range(len(actual) + 1))
    return bool(actual) and line_matches(expected[0], actual[0]) and \
        output_matches(expected[1:], actual[1:])


def run(command, where, env):
    command = re.sub(r"(?<![\w/.])build/pedesis\b", "pedesis", command)
    done = subprocess.run(["bash", "-o", "pipefail", "-c", command], cwd=where, env=env,
                          stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True,
                          timeout=600)
    return done.returncode, done.stdout.splitlines()


def environment(scratch):
    binary = os.environ.get("PEDESIS_BIN")
    if not binary:
        raise SystemExit("PEDESIS_BIN must name the pedesis binary")
    tools = pathlib.Path(scratch) / ".bin"
    tools.mkdir()
    (tools / "pedesis").symlink_to(pathlib.Path(binary).resolve())
    # (the interpreter running this, Debian's with python3-gsd, for blocks that read files)
    (tools / "python3").symlink_to(sys.executable)
    env = dict(os.environ)
    env["PATH"] = f"{tools}{os.pathsep}{env.get('PATH', '')}"
    return env


def check(doc, setup):
    text = pathlib.Path(doc).read_text(encoding="utf-8")
    found = list(transcripts(text))
    if not found:
        print(f"{doc}: no console blocks", file=sys.stderr)
        return 1
    failures = 0
    with tempfile.TemporaryDirectory(prefix="pedesis_console_") as scratch:
        work = pathlib.Path(scratch) / "work"
        work.mkdir()
        (work / "examples").symlink_to(SOURCE / "examples")
        env = environment(scratch)
        for command in setup:
            code, out = run(command.replace("SRC", str(SOURCE)), work, env)
            if code != 0:
                print(f"setup {command!r} failed ({code}):\n" + "\n".join(out), file=sys.stderr)
                return 1
        for line, command, expected in found:
            want = 0
            if expected and EXIT.match(expected[-1]):
                want = int(EXIT.match(expected[-1]).group(1))
                expected = expected[:-1]
            code, out = run(command, work, env)
            if code == want and output_matches(expected, out):
                print(f"{doc}:{line}: ok  $ {command.splitlines()[0]}")
                continue
            failures += 1
            print(f"{doc}:{line}: FAILED  $ {command}\n  exit {code} (expected {want})\n"
                  "  --- the document shows\n" + "".join(f"  |{e}\n" for e in expected) +
                  "  --- the command printed\n" + "".join(f"  |{o}\n" for o in out),
                  file=sys.stderr)
    return 1 if failures else 0


if __name__ == "__main__":
    from run_doc_snippets import command_line
    arguments = command_line("Run a document's console blocks.")
    sys.exit(max(check(d, arguments.setup) for d in arguments.documents))
