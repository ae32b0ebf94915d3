#!/usr/bin/env python3
"""Import graph of a Rust crate's modules (one binary or library crate, files under SRC).

Edges: `crate::a::b` paths anywhere in code (use trees `use crate::{a, b::c}` included) and `super::`
outside `mod tests`; comments are skipped. Each edge is resolved to the longest known module prefix.
Edges found only inside `#[cfg(test)]` blocks are marked (test). Prints the graph, the strongly connected
components with more than one module (the cycles), and, when there are none, the layers (each module
above everything it imports), top first.

usage: tools/import-cycles.py SRC [--no-tests] [--collapse PREFIX ...] [--group NAME=a,b,... ...] [--bottom NAME]

--collapse PREFIX: a module and its children are one node (a room with its own files). --group NAME=a,b:
those modules are one node NAME (a floor whose files lean on each other). --bottom NAME: NAME must import
nothing (the ground floor). Exits 1 when a cycle is left or a bottom imports.
CI runs it on the lab (`python3 tools/import-cycles.py lab/src`) and on the library, whose ground floor
(the number type, vectors, quaternions and their exact arithmetic) is one group that must import nothing
above it (`python3 tools/import-cycles.py src --collapse input scheme frontend noise error_state
--group floor=exact,quat,real,trig,vec3,error,sample --bottom floor`).
"""
import os
import re
import sys


def module_of(src, path):
    rel = os.path.relpath(path, src)[:-3].split(os.sep)
    if rel[0] == "bin":
        return None
    if rel[-1] == "mod":
        rel = rel[:-1]
    if rel in (["main"], ["lib"]):
        return "crate"
    return "::".join(rel)


def strip_comments(text):
    # Line comments and block comments; strings are left (the lab has no `crate::` inside strings).
    text = re.sub(r"/\*.*?\*/", "", text, flags=re.S)
    return "\n".join(re.sub(r"//.*", "", line) for line in text.split("\n"))


def expand_use_tree(prefix, tree):
    """`a::{b, c::{d, e}}` -> [a::b, a::c::d, a::c::e]."""
    tree = tree.strip()
    m = re.match(r"^([\w:]*?)(::)?\{(.*)\}$", tree, flags=re.S)
    if not m:
        return [prefix + tree] if tree else [prefix.rstrip(":")]
    head = m.group(1)
    inner = m.group(3)
    parts, depth, cur = [], 0, ""
    for ch in inner:
        if ch == "{":
            depth += 1
        elif ch == "}":
            depth -= 1
        if ch == "," and depth == 0:
            parts.append(cur)
            cur = ""
        else:
            cur += ch
    parts.append(cur)
    base = prefix + (head + "::" if head else "")
    out = []
    for p in parts:
        p = p.strip()
        if not p:
            continue
        if p == "self":
            out.append(base.rstrip(":"))
        else:
            out.extend(expand_use_tree(base, p))
    return out


def test_ranges(text):
    """Character ranges of `#[cfg(test)]` items (the item's braces)."""
    ranges = []
    for m in re.finditer(r"#\[cfg\(test\)\]", text):
        i = m.end()
        semi = text.find(";", i)
        brace = text.find("{", i)
        if brace == -1 or (semi != -1 and semi < brace):
            ranges.append((m.start(), semi + 1))
            continue
        depth = 0
        for j in range(brace, len(text)):
            if text[j] == "{":
                depth += 1
            elif text[j] == "}":
                depth -= 1
                if depth == 0:
                    ranges.append((m.start(), j + 1))
                    break
    return ranges


def references(text, me):
    """(path, position) of every crate path in `text`."""
    refs = []
    for m in re.finditer(r"\buse\s+crate::(\{.*?\}|[\w:]+(?:::\{.*?\})?)\s*;", text, flags=re.S):
        for p in expand_use_tree("", m.group(1)):
            refs.append((p, m.start()))
    for m in re.finditer(r"(?<!use )\bcrate::([\w:]+)", text):
        refs.append((m.group(1), m.start()))
    parent = me.rsplit("::", 1)[0] if "::" in me else "crate"
    for m in re.finditer(r"\bsuper::([\w:]+|\*)", text):
        # Inside a file's `mod tests`, `super` is the file itself (skipped by the caller).
        refs.append(("super::" + m.group(1), m.start()))
    return [(p if not p.startswith("super::") else p, pos) for p, pos in refs]
    return refs


def main():
    args = sys.argv[1:]
    src = args[0]
    no_tests = "--no-tests" in args
    collapse, groups, bottoms = [], {}, []
    for k, a in enumerate(args):
        following = []
        for b in args[k + 1:]:
            if b.startswith("--"):
                break
            following.append(b)
        if a == "--collapse":
            collapse += following
        elif a == "--bottom":
            bottoms += following
        elif a == "--group":
            for g in following:
                name, members = g.split("=", 1)
                for m in members.split(","):
                    groups[m] = name
    files = []
    for root, _, names in os.walk(src):
        for n in names:
            if n.endswith(".rs"):
                files.append(os.path.join(root, n))
    mods = {}
    for f in sorted(files):
        m = module_of(src, f)
        if m is not None:
            mods[m] = f

    # Re-exports (`pub use child::Name;`, `pub(crate) use ...`): `module::Name` is the child's.
    reexports = {}
    for me, f in mods.items():
        text = strip_comments(open(f).read())
        base = "" if me == "crate" else me + "::"
        for m in re.finditer(r"\bpub(?:\([\w:]+\))?\s+use\s+([\w:{}, \n]+?)\s*;", text):
            tree = m.group(1).strip()
            for p in expand_use_tree("", tree):
                segs = p.split(" as ")
                name = segs[-1].split("::")[-1].strip()
                src_path = segs[0].strip()
                if src_path.startswith("crate::"):
                    full = src_path[len("crate::"):]
                elif src_path.startswith("self::"):
                    full = base + src_path[len("self::"):]
                else:
                    full = base + src_path
                reexports[(me, name)] = full

    def resolve(path, depth=0):
        parts = [p for p in path.split("::") if p and p != "*"]
        for k in range(len(parts), -1, -1):
            cand = "::".join(parts[:k]) if k else "crate"
            if cand in mods:
                if k < len(parts) and (cand, parts[k]) in reexports and depth < 8:
                    return resolve(reexports[(cand, parts[k])], depth + 1)
                return cand if k else None
        return None

    def group(m):
        if m in groups:
            return groups[m]
        for c in collapse:
            if m == c or m.startswith(c + "::"):
                return c
        return m

    edges = {}  # (a, b) -> set of kinds
    for me, f in mods.items():
        text = strip_comments(open(f).read())
        tr = test_ranges(text)
        # A module that declares children (`mod child;`, the registry's `pub mod` lines) names them.
        prefix = "" if me == "crate" else me + "::"
        for m in re.finditer(r"\bmod\s+(\w+)\s*;", text):
            if me != "crate" and prefix + m.group(1) in mods:
                edges.setdefault((group(me), group(prefix + m.group(1))), set()).add("code")
        if me == "studies":
            for m in re.finditer(r"^\s*(\w+)::\w+,", text, flags=re.M):
                if prefix + m.group(1) in mods:
                    edges.setdefault((group(me), group(prefix + m.group(1))), set()).add("code")
        for path, pos in references(text, me):
            if path.startswith("super::"):
                if any(a <= pos < b for a, b in tr):
                    continue
                parent = me.rsplit("::", 1)[0] if "::" in me else "crate"
                path = ("" if parent == "crate" else parent + "::") + path[len("super::"):]
            target = resolve(path)
            if target is None or target == me:
                continue
            # `super::*` inside a file's own `mod tests` is the file itself.
            in_test = any(a <= pos < b for a, b in tr)
            if in_test and no_tests:
                continue
            a, b = group(me), group(target)
            if a == b or a == "crate":
                continue
            edges.setdefault((a, b), set()).add("test" if in_test else "code")
    edges = {k: v for k, v in edges.items() if k[0] != k[1]}
    nodes = sorted({group(m) for m in mods if m != "crate"})
    out = {n: sorted(b for (a, b) in edges if a == n) for n in nodes}

    print("# import graph (module -> modules it imports; (test) = only in #[cfg(test)] code)")
    for n in nodes:
        targets = [
            b + ("" if "code" in edges[(n, b)] else " (test)") for b in out[n]
        ]
        print(f"{n} -> {', '.join(targets) if targets else '(nothing)'}")

    # Tarjan's strongly connected components.
    index, low, on, stack, sccs = {}, {}, set(), [], []
    counter = [0]
    sys.setrecursionlimit(10000)

    def visit(v):
        index[v] = low[v] = counter[0]
        counter[0] += 1
        stack.append(v)
        on.add(v)
        for w in out[v]:
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
            sccs.append(sorted(comp))

    for n in nodes:
        if n not in index:
            visit(n)
    cycles = [c for c in sccs if len(c) > 1]
    print()
    print(f"# strongly connected components with more than one module: {len(cycles)}")
    for c in cycles:
        inner = [f"{a} -> {b}" for (a, b) in sorted(edges) if a in c and b in c]
        print(f"{{{', '.join(c)}}}: {'; '.join(inner)}")
    if cycles:
        return 1
    above = [(b, t) for b in bottoms for t in out.get(b, [])]
    for b, t in above:
        print(f"{b} is the ground floor but imports {t}")
    if above:
        return 1
    # Layers, top down: a module's layer is one more than the lowest layer that imports it (its deepest
    # importer); the top holds what nothing imports. Every import then points to a lower layer.
    importers = {n: [a for (a, b) in edges if b == n] for n in nodes}
    layer = {}

    def depth(v):
        if v not in layer:
            layer[v] = 1 + max((depth(a) for a in importers[v]), default=-1)
        return layer[v]

    for n in nodes:
        depth(n)
    print()
    print("# layers, top first (each module imports only from layers below it)")
    for lv in range(max(layer.values()) + 1):
        print(f"{lv}: {', '.join(sorted(n for n in nodes if layer[n] == lv))}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
