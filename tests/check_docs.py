#!/usr/bin/python3
"""The documentation's links and parameter snippets (issue #51 item 7).

Usage: check_docs.py REPOSITORY EXECUTABLE WORKDIR

Links: every Markdown link [text](target) of README.md and doc/**/*.md
whose target is not a URL must name a file of the repository, and a
#fragment on a Markdown file must be one of its headings (GitHub's anchor:
lower case, punctuation dropped, spaces to hyphens, -1, -2 ... for repeats).
No link may lead outside the repository: the project documents itself.

Snippets: every indented or fenced block of README.md and doc/**/*.md that
is parameter-file text (only `set`, `subsection`, `end` and comment lines,
at least one `set`; a whole file or a fragment of one) is read by the
executable (`--print-parameters=json FILE`: deal.II's parser with the
program's declarations and checks), so a misspelled entry, a value outside
its range or an entry that no longer exists fails the test. A whole file
of a mode that answers in seconds (analytic, reduced, profile) is also run
on 2 ranks (its output directory moved into WORKDIR) and must write its
results.
"""
import os
import re
import subprocess
import sys
import unicodedata

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from checker import check, rows, run_cycloid, verdict  # noqa: E402

LINK = re.compile(r"(?<!!)\[(?:[^\]\[]|\[[^\]]*\])*\]\(([^)\s]+)(?:\s+\"[^\"]*\")?\)")
IMAGE = re.compile(r"!\[[^\]]*\]\(([^)\s]+)\)")
HEADING = re.compile(r"^(#{1,6})\s+(.*?)\s*#*\s*$")


def pages(root):
    yield os.path.join(root, "README.md")
    for base, _, files in os.walk(os.path.join(root, "doc")):
        for f in sorted(files):
            if f.endswith(".md"):
                yield os.path.join(base, f)


def slug(text):
    """GitHub's anchor of a heading."""
    text = re.sub(r"`([^`]*)`", r"\1", text)
    text = re.sub(r"\[([^\]]*)\]\([^)]*\)", r"\1", text)
    text = unicodedata.normalize("NFC", text).lower()
    text = "".join(c for c in text if c.isalnum() or c in " -_" or ord(c) > 127
                   and unicodedata.category(c)[0] in "LN")
    return text.replace(" ", "-")


def anchors(path):
    seen, result, fenced = {}, set(), False
    with open(path, encoding="utf-8") as f:
        for line in f:
            if line.lstrip().startswith("```"):
                fenced = not fenced
            m = None if fenced else HEADING.match(line)
            if m:
                s = slug(m.group(2))
                n = seen.get(s, 0)
                seen[s] = n + 1
                result.add(s if n == 0 else "%s-%d" % (s, n))
    return result


def without_code(text):
    """@p text without fenced blocks and inline code spans."""
    text = re.sub(r"```.*?```", "", text, flags=re.S)
    return re.sub(r"`[^`\n]*`", "", text)


def check_links(root):
    cache = {}
    n = 0
    for page in pages(root):
        with open(page, encoding="utf-8") as f:
            text = without_code(f.read())
        rel = os.path.relpath(page, root)
        for target in LINK.findall(text) + IMAGE.findall(text):
            if re.match(r"^[a-z]+:", target):
                continue
            n += 1
            path, _, fragment = target.partition("#")
            full = os.path.normpath(os.path.join(os.path.dirname(page), path)) if path else page
            if not check(os.path.commonpath([root, full]) == root,
                         "%s: link to %s leads outside the repository" % (rel, target)):
                continue
            if not check(os.path.exists(full), "%s: link to %s: no such file" % (rel, target)):
                continue
            if fragment and full.endswith(".md"):
                if full not in cache:
                    cache[full] = anchors(full)
                check(fragment in cache[full], "%s: link to %s: no such heading in %s"
                      % (rel, target, os.path.relpath(full, root)))
    print("%d links checked" % n)


def snippets(text):
    """The code blocks of a Markdown page: fenced, or indented by 4+."""
    blocks, current, fenced = [], [], False
    for line in text.split("\n"):
        if line.lstrip().startswith("```"):
            if fenced:
                blocks.append("\n".join(current))
                current = []
            fenced = not fenced
            continue
        if fenced:
            current.append(line)
        elif line.startswith("    ") or (current and not line.strip()):
            current.append(line)
        else:
            if current:
                blocks.append("\n".join(current))
            current = []
    if current:
        blocks.append("\n".join(current))
    return [b for b in blocks if is_prm(b)]


PRM_LINE = re.compile(r"^\s*(set\s+[A-Za-z][^=]*=.*|subsection\s+\S.*|end|#.*|)$")


def is_prm(block):
    """Whether every line of @p block is parameter-file syntax (set,
    subsection, end, comments) and it sets something."""
    lines = block.split("\n")
    return (all(PRM_LINE.match(l) for l in lines)
            and any(l.strip().startswith("set ") for l in lines))


# The modes whose snippets are run, not only read: the ones that answer in
# seconds (the FE and transient examples take minutes and are run by the
# tests of their prm/ files).
RUN = ("analytic", "reduced", "profile")


def run_snippet(exe, prm, where, work):
    """Run @p prm on 2 ranks in @p work: exit 0 and a stiffness.csv (or
    profile.csv) with rows."""
    out = os.path.join(work, os.path.basename(prm)[:-4] + "-out")
    with open(prm) as f:
        text = re.sub(r"^set Output directory\s*=.*$", "set Output directory = " + out,
                      f.read(), flags=re.M)
    if "set Output directory" not in text:
        text = "set Output directory = %s\n" % out + text
    with open(prm, "w") as f:
        f.write(text)
    r = run_cycloid(2, exe, prm, log=out + ".log")
    check(r.returncode == 0, "%s fails to run (exit %d):\n%s" % (where, r.returncode,
                                                                r.stdout[-800:]))
    results = [os.path.join(out, f) for f in ("stiffness.csv", "profile.csv")]
    check(any(os.path.exists(f) and len(rows(f)) > 0 for f in results),
          "%s wrote no results in %s" % (where, out))


def check_snippets(root, exe, work):
    os.makedirs(work, exist_ok=True)
    n = runs = 0
    seen = set()  # a snippet printed on two pages is read and run once
    for page in pages(root):
        with open(page, encoding="utf-8") as f:
            blocks = snippets(f.read())
        for k, block in enumerate(blocks):
            lines = [l for l in block.split("\n")]
            indent = min((len(l) - len(l.lstrip()) for l in lines if l.strip()), default=0)
            prm = "\n".join(l[indent:] for l in lines) + "\n"
            if prm in seen:
                continue
            seen.add(prm)
            name = os.path.join(work, "%s-%d.prm" % (os.path.relpath(page, root).replace(
                os.sep, "_"), k))
            with open(name, "w") as f:
                f.write(prm)
            p = subprocess.run([exe, "--print-parameters=json", name], capture_output=True,
                               text=True)
            n += 1
            where = "%s, snippet %d" % (os.path.relpath(page, root), k + 1)
            if not check(p.returncode == 0, "%s is not a valid parameter file:\n%s\n%s"
                         % (where, prm, (p.stdout + p.stderr)[-600:])):
                continue
            mode = re.search(r"^set Run\s*=\s*(\S+)", prm, re.M)
            if mode and mode.group(1) in RUN:
                run_snippet(exe, name, where, work)
                runs += 1
    print("%d parameter snippets read, %d of them run" % (n, runs))
    check(n > 0, "no parameter snippet found")


def main():
    root, exe, work = os.path.abspath(sys.argv[1]), sys.argv[2], sys.argv[3]
    check_links(root)
    check_snippets(root, exe, work)
    return verdict()


if __name__ == "__main__":
    sys.exit(main())
