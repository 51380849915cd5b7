#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Finds what the public headers (engine/include/supermodal/) must export from a shared build and is
not marked SM_API (supermodal/api.h): every function declared there and defined in a library, and every
class with such a member function or with virtual functions. Reads clang's AST of the headers, so
comments, macros and line breaks cannot fool it.

  scripts/api_exports.py          list what is missing (file:line), exit 1 if anything is
  scripts/api_exports.py --fix    insert SM_API (and the api.h include) where it is missing
  --generated DIR                 also DIR/supermodal/*.h, the headers the build generates (version.h,
                                  from cmake/version.h.in): checked, never fixed

Needs clang (14 or later) and, for --fix, clang-format; CLANG, CLANGXX and CLANG_FORMAT name other
binaries.
"""
import argparse
import json
import os
import pathlib
import subprocess
import sys
import tempfile

ROOT = pathlib.Path(__file__).resolve().parent.parent
INCLUDE = ROOT / "engine" / "include"
PUBLIC = INCLUDE / "supermodal"
C_HEADER = PUBLIC / "supermodal.h"
API_HEADER = PUBLIC / "api.h"
METHOD_KINDS = ("CXXMethodDecl", "CXXConstructorDecl", "CXXDestructorDecl", "CXXConversionDecl")
GENERATED = []  # include directories of generated public headers (--generated), resolved


def public_dirs():
    return [PUBLIC] + [g / "supermodal" for g in GENERATED]


def public_headers():
    return sorted(p for d in public_dirs() if d.is_dir() for p in d.iterdir()
                  if p.suffix in (".h", ".hpp") and p != API_HEADER)


def shown(path):
    """A path as reports print it: relative to the repository when inside it."""
    path = pathlib.Path(path).resolve()
    return path.relative_to(ROOT) if path.is_relative_to(ROOT) else path


def dump_ast(compiler, args, source_text, suffix):
    """clang's JSON AST of a translation unit holding `source_text`, as a list of top-level nodes.
    SUPERMODAL_SHARED_LIBS makes SM_API a visibility attribute that shows in the AST."""
    with tempfile.NamedTemporaryFile("w", suffix=suffix, delete=False) as f:
        f.write(source_text)
        path = f.name
    try:
        includes = [f"-I{d}" for d in [INCLUDE, *GENERATED]]
        out = subprocess.run([compiler, *args, "-fsyntax-only", "-DSUPERMODAL_SHARED_LIBS", *includes,
                              "-Xclang", "-ast-dump=json", path],
                             check=True, capture_output=True, text=True).stdout
    finally:
        os.unlink(path)
    nodes, decoder, i = [], json.JSONDecoder(), 0
    while True:  # a filtered dump is a sequence of JSON objects
        while i < len(out) and out[i].isspace():
            i += 1
        if i == len(out):
            return nodes
        node, i = decoder.raw_decode(out, i)
        nodes.append(node)


class Walker:
    """Walks nodes in source order, tracking the file each location is in (the JSON dump names a file
    only when it changes)."""

    def __init__(self):
        self.file = None
        self.line = 0
        self.found = []     # (path, offset, kind, name, line, text to insert, tag)
        self.defined = set()  # ids of declarations whose definition comes later in a header

    def _track(self, loc):
        if not loc:
            return None
        for key in ("expansionLoc", "spellingLoc"):
            if key in loc:
                return self._track(loc[key])
        if "file" in loc:
            self.file = loc["file"]
        if "line" in loc:
            self.line = loc["line"]
        return loc.get("offset")

    def _begin(self, node):
        """The node's start: (file, byte offset, line). Tracks its end too, as the dump prints it."""
        self._track(node.get("loc"))
        rng = node.get("range", {})
        offset = self._track(rng.get("begin"))
        start = (self.file, offset, self.line)
        self._track(rng.get("end"))
        return start

    @staticmethod
    def _has_body(node):
        return any(c.get("kind") == "CompoundStmt" for c in node.get("inner", []))

    @staticmethod
    def _exported(node):
        return any(c.get("kind") == "VisibilityAttr" for c in node.get("inner", []))

    def _needs_export(self, node):
        """A function declared here and defined in a library."""
        return not (self._has_body(node) or node.get("inline") or node.get("isImplicit") or
                    node.get("explicitlyDeleted") or node.get("explicitlyDefaulted") or
                    node.get("pure") or node.get("storageClass") == "static" or node["id"] in self.defined)

    def collect_definitions(self, node):
        if node.get("kind") in ("FunctionDecl",) + METHOD_KINDS and self._has_body(node) and "previousDecl" in node:
            self.defined.add(node["previousDecl"])
        for c in node.get("inner", []):
            self.collect_definitions(c)

    def visit(self, node, in_record=False):
        kind = node.get("kind")
        file, offset, line = self._begin(node)
        here = file is not None and pathlib.Path(file).resolve().parent in public_dirs()
        if kind == "FriendDecl":
            for c in node.get("inner", []):  # a friend is not the class's to export; skip its subtree
                self._begin(c)
            return
        if kind == "CXXRecordDecl" and node.get("completeDefinition"):
            members = node.get("inner", [])
            if here and not self._exported(node):
                # Walk the members first (their locations move the tracked file/line forward).
                wants = False
                for c in members:
                    self.visit(c, in_record=True)
                    if c.get("kind") in METHOD_KINDS and (self._needs_export(c) or c.get("virtual")):
                        wants = True
                if wants and node.get("name"):
                    self.found.append((file, offset, "class", node["name"], line, node["tagUsed"]))
                return
            for c in members:
                self.visit(c, in_record=True)
            return
        if kind == "FunctionDecl" and not in_record and here and not self._exported(node) and \
                self._needs_export(node):
            self.found.append((file, offset, "function", node.get("name"), line, None))
        if kind == "VarDecl" and not in_record and here and node.get("storageClass") == "extern" and \
                not self._exported(node):
            self.found.append((file, offset, "variable", node.get("name"), line, None))
        if kind in ("FunctionTemplateDecl", "ClassTemplateDecl"):
            for c in node.get("inner", []):  # templates live in the headers: nothing to export
                self._begin(c)
            return
        for c in node.get("inner", []):
            self.visit(c, in_record=kind == "CXXRecordDecl")


def find_missing():
    cxx = os.environ.get("CLANGXX", "clang++")
    cc = os.environ.get("CLANG", "clang")
    cxx_headers = [h for h in public_headers() if h != C_HEADER]
    # The C++ headers: only declarations in namespace supermodal (the filter keeps the standard
    # library out of the dump). The C header alone, as C: it is small.
    units = [
        (cxx, ["-x", "c++", "-std=c++20", "-Xclang", "-ast-dump-filter=supermodal"],
         "".join(f'#include "supermodal/{h.name}"\n' for h in cxx_headers), ".cpp"),
        (cc, ["-x", "c", "-std=c99"], '#include "supermodal/supermodal.h"\n', ".c"),
    ]
    found = {}
    for compiler, args, text, suffix in units:
        nodes = dump_ast(compiler, args, text, suffix)
        walker = Walker()
        for n in nodes:
            walker.collect_definitions(n)
        for n in nodes:
            walker.visit(n)
        for f in walker.found:
            found[(f[0], f[1])] = f  # a namespace dumped twice reports its declarations twice
    return sorted(found.values(), key=lambda f: (f[0], f[1]))


def insertion_point(text, offset, kind, tag):
    """Where SM_API goes: before a function's declaration specifiers (clang's range starts after any
    [[attributes]]), after a class's key and attributes."""
    if kind != "class":
        return offset
    assert text.startswith(tag, offset), (text[offset:offset + 40], tag)
    i = offset + len(tag)
    while True:
        j = i
        while text[j].isspace():
            j += 1
        if not text.startswith("[[", j):
            return i
        i = text.index("]]", j) + 2


def add_include(text):
    if '#include "supermodal/api.h"' in text:
        return text
    lines = text.split("\n")
    first = next((i for i, l in enumerate(lines) if l.startswith("#include")), None)
    if first is None:  # no includes yet: a group of its own after #pragma once
        once = lines.index("#pragma once")
        return "\n".join(lines[:once + 1] + ["", '#include "supermodal/api.h"'] + lines[once + 1:])
    block = ['#include "supermodal/api.h"']
    if not lines[first].startswith('#include "supermodal/'):
        block.append("")  # its own group ahead of the system headers
    return "\n".join(lines[:first] + block + lines[first:])


def fix(missing):
    by_file = {}
    for f in missing:
        if pathlib.Path(f[0]).resolve().parent == PUBLIC:  # a generated header: its template is the source
            by_file.setdefault(f[0], []).append(f)
    for path, items in by_file.items():
        data = pathlib.Path(path).read_bytes()  # clang's offsets are in bytes
        text = data.decode("utf-8")
        inserts = []
        for _, offset, kind, _, _, tag in items:
            prefix = data[:offset].decode("utf-8")
            pos = insertion_point(text, len(prefix), kind, tag)
            inserts.append((pos, " SM_API" if kind == "class" else "SM_API "))
        for pos, s in sorted(inserts, reverse=True):
            text = text[:pos] + s + text[pos:]
        pathlib.Path(path).write_text(add_include(text), encoding="utf-8")
    return sorted(by_file)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--fix", action="store_true", help="insert SM_API where it is missing")
    parser.add_argument("--generated", action="append", default=[], metavar="DIR",
                        help="an include directory of generated public headers (DIR/supermodal/*.h)")
    args = parser.parse_args()
    GENERATED.extend(pathlib.Path(d).resolve() for d in args.generated)
    missing = find_missing()
    if args.fix:
        changed = fix(missing)
        for path in changed:
            print(f"annotated {shown(path)}")
        if changed:  # SM_API lengthens lines; the headers are kept clang-formatted
            subprocess.run([os.environ.get("CLANG_FORMAT", "clang-format"), "-i", *changed], check=True)
        missing = find_missing()
    for path, _, kind, name, line, _ in missing:
        print(f"{shown(path)}:{line}: {kind} {name} is not marked SM_API")
    if missing:
        print(f"{len(missing)} public declaration(s) not exported from a shared build "
              "(scripts/api_exports.py --fix marks them)", file=sys.stderr)
        return 1
    print("every public declaration that a library defines is marked SM_API")
    return 0


if __name__ == "__main__":
    sys.exit(main())
