#!/usr/bin/python3
"""Run the examples of the documentation as written.

usage: test_docs.py SOURCE-DIR MFSTAB-DIR [FILE.md ...]

The examples are the indented code blocks of README.md and docs/*.md that
call mfstab (a line starting with `mfstab `, `$ mfstab ` or a `for` loop).
They run with MFSTAB-DIR first on PATH, in a temporary directory that holds
links to the source tree's analysis/ and notebooks-data/ (so scene paths as
written resolve), under bash with -e and pipefail:

  * a block whose lines start with `$ ` is a transcript: each command (a
    line ending in a backslash continues it) must print exactly the lines
    shown under it, standard output and standard error together; its exit
    code is not checked (a transcript may show a refusal);
  * any other block must exit 0.

Every relative link, and every path of the tree named in backquotes
(`docs/errata.md`, `lib/core/mfs_kernel.h`), must exist; every library name
in backquotes (`mfs_eig_max()`) must be declared in a header of lib/.

A block is skipped when the line before it is `<!-- not run -->` or when it
is a synopsis (holds `[options]`).  One line per failed block; the last line
counts them; exit 1 on any failure.
"""
import os
import re
import subprocess
import sys
import tempfile

CALLS = re.compile(r"^(\$ )?(mfstab |for )")


def blocks(path):
    """(line number, lines) of each indented code block of a markdown file."""
    lines = open(path, encoding="utf-8").read().split("\n")
    out, i = [], 0
    fence = False
    while i < len(lines):
        if lines[i].startswith("```"):
            fence = not fence
            i += 1
            continue
        prev_blank = i == 0 or lines[i - 1].strip() == "" or lines[i - 1].startswith("<!--")
        if not fence and lines[i].startswith("    ") and prev_blank:
            marker = ""
            j = i - 1
            while j >= 0 and lines[j].strip() == "":
                j -= 1
            if j >= 0:
                marker = lines[j].strip()
            start, body = i, []
            while i < len(lines) and (lines[i].startswith("    ") or
                                      (lines[i].strip() == "" and i + 1 < len(lines) and
                                       lines[i + 1].startswith("    "))):
                body.append(lines[i][4:])
                i += 1
            out.append((start + 1, body, marker))
            continue
        i += 1
    return out


def transcript(body):
    """[(command, expected lines)] of a block of `$ ` lines."""
    steps, k = [], 0
    while k < len(body):
        if not body[k].startswith("$ "):
            return None
        cmd = body[k][2:]
        k += 1
        while cmd.endswith("\\") and k < len(body):
            cmd = cmd[:-1] + " " + body[k].strip()
            k += 1
        want = []
        while k < len(body) and not body[k].startswith("$ "):
            want.append(body[k])
            k += 1
        while want and want[-1].strip() == "":
            want.pop()
        steps.append((cmd, want))
    return steps


def main():
    src, bindir = os.path.abspath(sys.argv[1]), os.path.abspath(sys.argv[2])
    files = sys.argv[3:] or [os.path.join(src, "README.md")] + sorted(
        os.path.join(src, "docs", f) for f in os.listdir(os.path.join(src, "docs")) if f.endswith(".md"))
    env = dict(os.environ, PATH=bindir + os.pathsep + os.environ.get("PATH", ""))
    headers = set()
    for root, _, fs in os.walk(os.path.join(src, "lib")):
        for f in fs:
            if f.endswith(".h") or f == "meson.build":
                headers |= set(re.findall(r"\bmfs_[a-z0-9_]+", open(os.path.join(root, f)).read()))
    passed = failed = 0
    for path in files:
        rel = os.path.relpath(path, src)
        for line, body, marker in blocks(path):
            text = "\n".join(body)
            if marker == "<!-- not run -->" or "[options]" in text:
                continue
            if not any(CALLS.match(b) for b in body):
                continue
            with tempfile.TemporaryDirectory() as tmp:
                for d in ("analysis", "notebooks-data"):
                    os.symlink(os.path.join(src, d), os.path.join(tmp, d))
                steps = transcript(body)
                problems = []
                if steps is None:
                    r = subprocess.run(["bash", "-e", "-o", "pipefail", "-c", text], cwd=tmp, env=env,
                                       capture_output=True, text=True, timeout=300)
                    if r.returncode != 0:
                        problems.append("exit %d: %s" % (r.returncode, (r.stderr or r.stdout).strip()[:300]))
                else:
                    for cmd, want in steps:
                        r = subprocess.run(["bash", "-o", "pipefail", "-c", cmd + " 2>&1"], cwd=tmp, env=env,
                                           capture_output=True, text=True, timeout=300)
                        got = r.stdout.rstrip("\n").split("\n") if r.stdout.strip() else []
                        if [g.rstrip() for g in got] != [w.rstrip() for w in want]:
                            diff = next((k for k in range(max(len(got), len(want)))
                                         if k >= len(got) or k >= len(want) or got[k].rstrip() != want[k].rstrip()), 0)
                            problems.append("`%s`: line %d printed %r, the doc shows %r" % (
                                cmd, diff + 1, got[diff] if diff < len(got) else "(nothing)",
                                want[diff] if diff < len(want) else "(nothing)"))
            if problems:
                failed += 1
                print("FAIL: %s:%d: %s" % (rel, line, "; ".join(problems)))
            else:
                passed += 1
        # every relative link and every path named in backquotes that looks like a
        # file of the tree (docs/x.md, lib/..., tests/...) exists
        text = open(path, encoding="utf-8").read()
        targets = [(m, os.path.dirname(path)) for m in re.findall(r"\]\(([^)#:\s]+)[^)]*\)", text)]
        targets += [(m, src) for m in re.findall(r"`((?:docs|lib|tools|tests|analysis|scripts|examples|notebooks)/[\w./-]+\.\w+)`", text)]
        missing = sorted({t for t, base in targets if not os.path.exists(os.path.join(base, t))})
        # every library name in backquotes (`mfs_eig_max()`, `mfs_disc`) is declared in a header
        names = set(re.findall(r"`[^`]*?\b(mfs_[a-z0-9_]+)", text))
        missing += sorted(n + " (not in lib/)" for n in names if n not in headers and
                          not (n.endswith("_") and any(h.startswith(n) for h in headers)))
        if missing:
            failed += 1
            print("FAIL: %s: links to files that do not exist: %s" % (rel, ", ".join(missing)))
        else:
            passed += 1
    print("test_docs: %d passed, %d failed" % (passed, failed))
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
