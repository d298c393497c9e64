#!/usr/bin/env python3
"""The include and link graph of srp's libraries, checked.

    scripts/check-structure.py [--dot FILE] [--max-lines N]

Reads every libs/<m>/CMakeLists.txt (srp_add_module: PUBLIC_DEPS, PRIVATE_DEPS, TEST_DEPS)
and every #include "srp/<m>/X.h" of libs/<m>/{include,src}, then checks:
  1. the modules' link graph has no circle;
  2. no upward arrow: a module includes only headers of itself and of modules it links
     (directly or through them);
  3. no two-way include tie inside a module: units (X.h + X.cpp) that include each other,
     directly or round a longer loop;
  4. tests link no module above their own (a TEST_DEPS module that links the module under test);
  5. core links Eigen and nlohmann-json only (no ViSP, MRPT, OpenCV);
  6. no non-test function over N lines (default 100; universal-ctags), outside the files
     listed in LONG_FUNCTIONS_ALLOWED below.
Prints each module's floor (0 = links no srp module) and every violation; exit 1 on any.
--dot FILE writes the module graph (link arrows; test-only arrows dashed) for Graphviz.
"""
import argparse
import os
import re
import shutil
import subprocess
import sys
from collections import defaultdict

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
LIBS = os.path.join(ROOT, "libs")
# The placement planner is split by its own issue; MarkerFreeHandDetector by the hand detector's.
LONG_FUNCTIONS_ALLOWED = {"libs/execution/src/PlacementPlanner.cpp", "libs/perception/src/MarkerFreeHandDetector.cpp"}
KEYWORDS = ("NAME", "SOURCES", "PUBLIC_DEPS", "PRIVATE_DEPS", "TEST_SOURCES", "TEST_DEPS", "TEST_LABELS")
FORBIDDEN_IN_CORE = re.compile(r"visp|mrpt|opencv", re.I)


def module_deps():
    """{module: {"link": set, "test": set, "raw": str}} from srp_add_module calls."""
    mods = {}
    for m in sorted(os.listdir(LIBS)):
        path = os.path.join(LIBS, m, "CMakeLists.txt")
        if not os.path.isfile(path):
            continue
        text = re.sub(r"#.*", "", open(path).read())
        call = re.search(r"srp_add_module\((.*?)\)\s*(\n|$)", text, re.S)
        if not call:
            continue
        sections, key = defaultdict(list), None
        for tok in call.group(1).split():
            if tok in KEYWORDS:
                key = tok
            elif key:
                sections[key].append(tok)
        srp = lambda toks: {re.sub(r"^srp(::|_)", "", t) for t in toks if re.match(r"srp(::|_)", t)}
        mods[m] = {"link": srp(sections["PUBLIC_DEPS"] + sections["PRIVATE_DEPS"]),
                   "test": srp(sections["TEST_DEPS"]),
                   "third_party": [t for t in sections["PUBLIC_DEPS"] + sections["PRIVATE_DEPS"] if not re.match(r"srp(::|_)", t)]}
    return mods


def closure(graph, start):
    seen, todo = set(), list(graph.get(start, ()))
    while todo:
        n = todo.pop()
        if n not in seen:
            seen.add(n)
            todo.extend(graph.get(n, ()))
    return seen


def cycles(graph):
    """Strongly connected components with more than one node (Tarjan)."""
    index, low, stack, on, out, counter = {}, {}, [], set(), [], [0]

    def visit(v):
        index[v] = low[v] = counter[0]
        counter[0] += 1
        stack.append(v)
        on.add(v)
        for w in graph.get(v, ()):
            if w not in index:
                visit(w)
                low[v] = min(low[v], low[w])
            elif w in on:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            comp = []
            while True:
                w = stack.pop()
                on.discard(w)
                comp.append(w)
                if w == v:
                    break
            if len(comp) > 1:
                out.append(sorted(comp))

    sys.setrecursionlimit(10000)
    for v in list(graph):
        if v not in index:
            visit(v)
    return out


def source_files(m):
    for sub in ("include", "src"):
        base = os.path.join(LIBS, m, sub)
        for dirpath, _, files in os.walk(base):
            for f in files:
                if f.endswith((".h", ".hpp", ".cpp")):
                    yield os.path.join(dirpath, f)


INCLUDE = re.compile(r'^\s*#\s*include\s*"([^"]+)"', re.M)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--dot", help="write the module graph in Graphviz dot form")
    ap.add_argument("--max-lines", type=int, default=100)
    args = ap.parse_args()
    mods = module_deps()
    link = {m: d["link"] for m, d in mods.items()}
    problems = []

    for c in cycles(link):
        problems.append("link circle: " + " -> ".join(c))
    reach = {m: closure(link, m) for m in mods}

    floors = {}
    def floor(m, depth=0):
        if m not in floors:
            floors[m] = 0 if not link[m] or depth > len(mods) else 1 + max(floor(d, depth + 1) for d in link[m] if d in mods)
        return floors[m]
    for m in mods:
        floor(m)

    unit_edges = defaultdict(set)
    for m in mods:
        for path in source_files(m):
            rel = os.path.relpath(path, ROOT)
            text = open(path, errors="replace").read()
            unit = (m, os.path.splitext(os.path.basename(path))[0])
            for inc in INCLUDE.findall(text):
                parts = inc.split("/")
                if len(parts) == 3 and parts[0] == "srp":
                    other = parts[1]
                    if other != m and other not in reach[m]:
                        problems.append(f"upward or undeclared arrow: {rel} includes {inc} but {m} does not link srp::{other}")
                    if other == m:
                        unit_edges[unit].add((m, os.path.splitext(parts[2])[0]))
                elif len(parts) == 1 and path.endswith(".cpp"):  # a private header beside the source
                    unit_edges[unit].add((m, os.path.splitext(inc)[0]))
    for u in list(unit_edges):
        unit_edges[u].discard(u)
    for c in cycles(unit_edges):
        problems.append(f"two-way include tie in {c[0][0]}: " + " <-> ".join(n for _, n in c))

    notes = []
    for m, d in mods.items():
        for t in sorted(d["test"]):
            if t in mods and m in reach.get(t, set()):
                problems.append(f"test dependency runs up: {m}'s tests link srp::{t}, which links {m}")
            elif t in mods and floors[t] > floors[m]:
                notes.append(f"{m}'s tests (floor {floors[m]}) link srp::{t} (floor {floors[t]}), which does not link {m}")
    core_third = [t for t in mods.get("core", {}).get("third_party", []) if FORBIDDEN_IN_CORE.search(t)]
    if core_third:
        problems.append("core links " + ", ".join(core_third) + " (Eigen and nlohmann-json only)")

    long_functions = []
    ctags = shutil.which("ctags-universal") or shutil.which("ctags")
    if ctags:
        files = [os.path.relpath(p, ROOT) for m in mods for p in source_files(m) if p.endswith(".cpp")]
        out = subprocess.run([ctags, "--c++-kinds=f", "--fields=+ne", "-o", "-"] + files, cwd=ROOT,
                             capture_output=True, text=True).stdout
        for line in out.splitlines():
            f = line.split("\t")
            start = re.search(r"\tline:(\d+)", line)
            end = re.search(r"\tend:(\d+)", line)
            if start and end:
                n = int(end.group(1)) - int(start.group(1)) + 1
                if n > args.max_lines:
                    long_functions.append((n, f[1], f[0]))
    else:
        problems.append("universal-ctags is not installed: function lengths not checked (apt-get install universal-ctags)")
    for n, path, name in sorted(long_functions, reverse=True):
        where = "allowed" if path in LONG_FUNCTIONS_ALLOWED else "too long"
        msg = f"function over {args.max_lines} lines ({where}): {path} {name} {n} lines"
        if path in LONG_FUNCTIONS_ALLOWED:
            print(msg)
        else:
            problems.append(msg)

    print("modules by floor (0 links no srp module):")
    for m in sorted(mods, key=lambda m: (floors[m], m)):
        print(f"  {floors[m]}  {m:12s} links {', '.join(sorted(link[m])) or '-'}"
              + (f"; tests also {', '.join(sorted(mods[m]['test']))}" if mods[m]["test"] else ""))
    if args.dot:
        with open(args.dot, "w") as dot:
            dot.write("digraph srp {\n  rankdir=BT;\n")
            for m in mods:
                for d in sorted(link[m]):
                    dot.write(f'  "{m}" -> "{d}";\n')
                for d in sorted(mods[m]["test"] - link[m]):
                    dot.write(f'  "{m}" -> "{d}" [style=dashed, label="tests"];\n')
            dot.write("}\n")
    for n in notes:
        print("note: " + n)
    for p in problems:
        print("problem: " + p)
    print(f"check-structure: {len(problems)} problem(s)")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
