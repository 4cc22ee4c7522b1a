#!/usr/bin/env python3
"""Re-run the commands whose output README.md and docs/*.md show, and write their output back.

Two kinds of marked text (tests/cli/test_docs.c re-runs the quick ones and fails when the text
and the program disagree):

  <!-- output: CMD -->                 the text up to <!-- end:output --> is CMD's output,
  <!-- output quick-check: CMD -->     verbatim; CMD is a shell command run in the source
  ...                                  directory with the build directory first on PATH (so
  <!-- end:output -->                  `geomint` is the built program), e.g. a pipe into sed that
                                       keeps a table. "quick-check": it runs in about 2 s or less.

  <!-- quick-check -->                 a fenced block of `$ geomint ...` lines and excerpts of
  ```                                  their output; each excerpt line is rewritten from the
  $ geomint ...                        output line of the same shape (the same words, numbers
  ...                                  anywhere); a `~` stays (a timing, not compared).
  ```

usage: docs_regen.py GEOMINT [--quick] [--count] FILE.md...
  --quick  re-run only the quick-check text (what the test checks)
  --count  change nothing; print per page how many numbers are checked by the test, regenerated
           only by this script, or in neither (hand-written prose and tables)
"""
import os
import re
import subprocess
import sys

OUTPUT = re.compile(r"<!-- output( quick-check)?: (.*?) -->\n(.*?)<!-- end:output -->", re.S)
FENCED = re.compile(r"<!-- quick-check -->\n```[^\n]*\n(.*?)\n```", re.S)
GENERATED = re.compile(r"<!-- generated:([a-z]+) -->\n(.*?)<!-- end:\1 -->", re.S)
# a measured number: a decimal fraction or a power of ten (counts, section and seed numbers and
# integer parameters are left out of the count)
NUMBER = re.compile(r"(?<![\w.])[-+−]?(?:\d+\.\d+(?:e[-+−]?\d+)?|\d+e[-+−]?\d+)(?![\w])")


def run(cmd, env, any_status=False):
    p = subprocess.run(["sh", "-c", cmd], env=env, capture_output=True, text=True)
    if p.returncode != 0 and not any_status:
        sys.exit(f"docs_regen: `{cmd}` exited {p.returncode}:\n{p.stderr}")
    return p.stdout


def shape(line):
    return [("#" if re.search(r"\d", t) or t == "~" else t) for t in line.split()]


def tokens_match(doc, out):
    d, o = doc.split(), out.split()
    if d and d[-1] == "...":  # the rest of the line
        d, o = d[:-1], o[: len(d) - 1]
    return len(d) == len(o) and all(a == "~" or a == b for a, b in zip(d, o))


def rewrite(doc, out):
    """The output line, with the doc's `~` tokens kept (a timing) and its `...` end."""
    d = doc.split()
    spans = list(re.finditer(r"\S+", out))
    if d and d[-1] == "...":
        out = out[: spans[len(d) - 2].end()] + " ..." if len(d) > 1 else "..."
        spans = spans[: len(d) - 1]
    for k in reversed(range(len(spans))):
        if d[k] == "~":
            m = spans[k]
            out = out[: m.start()] + "~".rjust(m.end() - m.start()) + out[m.end():]
    return out


def regen_fenced(body, env, where):
    lines = body.split("\n")
    out_lines = []
    for line in lines:
        if line.startswith("$ geomint "):
            out_lines += run("geomint " + line[10:] + " 2>&1", env, True).split("\n")
    pos, result = 0, []
    for line in lines:
        t = line.strip()
        if line.startswith("$ ") or t in ("", "..."):
            result.append(line)
            continue
        found = next((k for k in range(pos, len(out_lines)) if tokens_match(line, out_lines[k])),
                     None)
        if found is None:  # a changed line: the one of the same shape with most words in common
            want = shape(line)
            cut = len(want) - 1 if want and want[-1] == "..." else len(want)
            best = -1
            for k in range(pos, len(out_lines)):
                got = shape(out_lines[k])
                if got[:cut] == want[:cut] and (cut < len(want) or len(got) == cut):
                    same = sum(a == b for a, b in zip(line.split(), out_lines[k].split()))
                    if same > best:
                        found, best = k, same
        if found is None:
            sys.exit(f"docs_regen: {where}: no output line has the shape of\n{line}")
        result.append(line if tokens_match(line, out_lines[found]) else rewrite(line, out_lines[found]))
        pos = found + 1
    return "\n".join(result)


def count_numbers(text):
    return len(NUMBER.findall(text))


def main():
    args = sys.argv[1:]
    geomint = os.path.abspath(args.pop(0))
    quick = "--quick" in args
    count = "--count" in args
    files = [a for a in args if not a.startswith("--")]
    env = dict(os.environ, PATH=os.path.dirname(geomint) + os.pathsep + os.environ["PATH"],
               OPENBLAS_NUM_THREADS="1")
    totals = [0, 0, 0]
    for path in files:
        text = open(path).read()
        if count:
            checked = regen = 0
            rest = text
            for m in OUTPUT.finditer(text):
                n = count_numbers(m.group(3))
                if m.group(1):
                    checked += n
                else:
                    regen += n
            for m in FENCED.finditer(text):
                checked += count_numbers("\n".join(
                    l for l in m.group(1).split("\n") if not l.startswith("$ ")))
            for m in GENERATED.finditer(text):
                checked += count_numbers(m.group(2))
            rest = GENERATED.sub("", FENCED.sub("", OUTPUT.sub("", text)))
            # headings, links, file names and command lines are not results
            rest = "\n".join(l for l in rest.split("\n") if not l.startswith("#"))
            rest = re.sub(r"`[^`\n]*`|\]\([^)]*\)|!\[[^\]]*\]", "", rest)
            unchecked = count_numbers(rest)
            totals = [totals[0] + checked, totals[1] + regen, totals[2] + unchecked]
            print(f"{path:28s} checked {checked:5d}  regenerated {regen:5d}  unchecked {unchecked:5d}")
            continue

        def output(m):
            if quick and not m.group(1):
                return m.group(0)
            print(f"docs_regen: {path}: {m.group(2)}", file=sys.stderr)
            got = run(m.group(2), env)
            if got and not got.endswith("\n"):
                got += "\n"
            return f"<!-- output{m.group(1) or ''}: {m.group(2)} -->\n{got}<!-- end:output -->"

        def fenced(m):
            head = m.group(0)[: m.start(1) - m.start(0)]
            return head + regen_fenced(m.group(1), env, path) + "\n```"

        new = FENCED.sub(fenced, OUTPUT.sub(output, text))
        if new != text:
            open(path, "w").write(new)
            print(f"docs_regen: {path} updated", file=sys.stderr)
    if count:
        print(f"{'total':28s} checked {totals[0]:5d}  regenerated {totals[1]:5d}  unchecked {totals[2]:5d}")


if __name__ == "__main__":
    main()
