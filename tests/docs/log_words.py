#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Checks that the user-facing text reads as reference, not as a work log.

  log_words.py check --source DIR     fails naming FILE:LINE for every work-log phrase in docs/,
                                      README.md and the comments of engine/, editor/, tools/, bench/,
                                      samples/, scripts/, tests/ and python/
  log_words.py selftest               the check fails on a planted line and names its file and line
  log_words.py changelog --source DIR --version X.Y.Z
                                      CHANGELOG.md's newest version heading is the project's version

Work-log phrases: numbered work sessions or periods, issue numbers ("issue 5", "#5"), hand-over
notes for whoever comes next, "history" sections, and references to design notes that are not in the
repository. The editor's edit session (editor/session.h) is a concept, so a plain "session" is not
flagged; "session 3", "this session" and the like are.
"""
import argparse
import pathlib
import re
import sys
import tempfile

# Phrases flagged anywhere in a line (prose, comments, strings).
WORDS = [
    (r"\bsessions? *[0-9]+", "a numbered work session"),
    (r"\b(this|next|last|previous|earlier|later|that|each|every) sessions?\b(?! *[(:=.\->])",
     "a work session"),
    (r"\bwork periods?\b", "a work period"),
    (r"\bstops? [0-9]+\b", "a numbered stop"),
    (r"\bissues? *#?[0-9]+", "an issue number"),
    (r"\bwaves? [0-9]\b", "a numbered wave"),
    (r"\bTODO\b.*\bnext\b|\bnext (person|helper|one to|pass)\b|\bleft for later\b", "a note for whoever comes next"),
    (r"\b(DESIGN|STYLE)\.md\b", "a design note that is not in the repository"),
]
# "#5" as an issue reference: flagged in prose and comments only (code has colours like "#888888").
ISSUE_REF = (r"(?<![&\w/#])#[0-9]+\b(?![0-9a-fA-F])", "an issue number")
HISTORY_HEADING = (r"^#+ .*\bhistory\b", "a history section")

PROSE = {".md"}
CODE_COMMENT = {".cpp", ".h", ".c", ".hpp", ".mjs", ".js", ".in"}
HASH_COMMENT = {".py", ".sh", ".cmake", ".txt"}
DIRS = ["docs", "engine", "editor", "tools", "bench", "samples", "scripts", "tests", "python"]
# Recorded inputs are kept byte for byte (fuzz corpora and regressions); this checker names the words.
SKIP = [re.compile(p) for p in (r"^tests/fuzz/(corpus|regressions|mesh_regressions|cli_regressions|cli_corpus)/",
                                 r"^tests/docs/", r"/__pycache__/", r"\.svg$")]


def comment_of(line, suffix):
    """The comment text of a code line ("" when it has none)."""
    if suffix in CODE_COMMENT:
        at = line.find("//")
        if at >= 0:
            return line[at + 2:]
        stripped = line.lstrip()
        return stripped if stripped.startswith(("/*", "*")) else ""
    if suffix in HASH_COMMENT or pathlib.Path(suffix).name == "CMakeLists.txt":
        m = re.search(r"(^|\s)#(?!!)(.*)$", line)
        return m.group(2) if m else ""
    return ""


def files(root):
    root = pathlib.Path(root)
    out = [root / "README.md"]
    for d in DIRS:
        out += sorted(p for p in (root / d).rglob("*") if p.is_file())
    for p in out:
        rel = p.relative_to(root).as_posix()
        if p.exists() and not any(s.search(rel) for s in SKIP):
            yield p, rel


def problems(root):
    found = []
    for path, rel in files(root):
        suffix = path.suffix
        if suffix not in PROSE | CODE_COMMENT | HASH_COMMENT | {".json"} and path.name != "CMakeLists.txt":
            continue
        try:
            text = path.read_text(encoding="utf-8")
        except UnicodeDecodeError:
            continue
        in_fence = False
        for n, line in enumerate(text.splitlines(), 1):
            if suffix in PROSE and line.lstrip().startswith("```"):
                in_fence = not in_fence
            checks = [(line, WORDS)]
            if suffix in PROSE:
                if not in_fence:
                    checks.append((line, [ISSUE_REF, HISTORY_HEADING]))
            elif suffix == ".json":
                checks.append((line, [ISSUE_REF]))
            else:
                checks.append((comment_of(line, suffix if path.name != "CMakeLists.txt" else ".cmake"), [ISSUE_REF]))
            hit = next(((m, what) for text_part, rules in checks for pattern, what in rules
                        if (m := re.search(pattern, text_part, 0 if pattern == ISSUE_REF[0] else re.IGNORECASE))),
                       None)
            if hit:
                found.append(f"{rel}:{n}: {hit[1]} (\"{hit[0].group(0).strip()}\"): {line.strip()[:120]}")
    return found


def check(root):
    found = problems(root)
    for f in found:
        print(f)
    if found:
        print(f"{len(found)} work-log phrases: write what the code does and what was measured, not when "
              "or by whom (history goes to CHANGELOG.md)", file=sys.stderr)
        return 1
    print("no work-log phrases")
    return 0


def selftest():
    bad = {
        "docs/page.md": "# Page\nMeasured in session 4 of the work.\n",
        "engine/src/a.cpp": "int a; // see #12 for why\n",
        "tools/b.h": "// TODO for the next person: finish this\n",
        "docs/c.md": "# C\n\n## History\n",
        "scripts/d.sh": "echo hi # (issue 7)\n",
    }
    good = {
        "docs/ok.md": "# Ok\nThe editor session keeps the scene.\n\n```\n#1 in a code block\n```\n",
        "tools/ok.cpp": 'const char* c = "#888888"; // a grey\n',
        "engine/src/ok.h": "// Iteration order is the store's history.\n",
    }
    with tempfile.TemporaryDirectory() as tmp:
        root = pathlib.Path(tmp)
        (root / "README.md").write_text("# Readme\n")
        for name, text in {**bad, **good}.items():
            (root / name).parent.mkdir(parents=True, exist_ok=True)
            (root / name).write_text(text)
        found = problems(root)
    expected = ["docs/page.md:2:", "engine/src/a.cpp:1:", "tools/b.h:1:", "docs/c.md:3:", "scripts/d.sh:1:"]
    missing = [e for e in expected if not any(f.startswith(e) for f in found)]
    extra = [f for f in found if not any(f.startswith(e) for e in expected)]
    for m in missing:
        print(f"selftest: not flagged: {m}")
    for e in extra:
        print(f"selftest: flagged wrongly: {e}")
    return 1 if missing or extra else 0


def changelog(root, version):
    text = (pathlib.Path(root) / "CHANGELOG.md").read_text(encoding="utf-8")
    m = re.search(r"^## \[([0-9]+\.[0-9]+\.[0-9]+)\]", text, re.MULTILINE)
    if not m:
        print("CHANGELOG.md: no '## [X.Y.Z]' version heading")
        return 1
    if m.group(1) != version:
        line = text[:m.start()].count("\n") + 1
        print(f"CHANGELOG.md:{line}: newest version {m.group(1)}, but project() in CMakeLists.txt says {version}")
        return 1
    print(f"CHANGELOG.md: newest version {version}, as CMakeLists.txt")
    return 0


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("mode", choices=["check", "selftest", "changelog"])
    ap.add_argument("--source", default=".")
    ap.add_argument("--version")
    a = ap.parse_args()
    if a.mode == "check":
        return check(a.source)
    if a.mode == "selftest":
        return selftest()
    return changelog(a.source, a.version)


if __name__ == "__main__":
    sys.exit(main())
