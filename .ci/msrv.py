#!/usr/bin/env python3
"""Check that each workspace package's declared rust-version is honest.

For every member, walk its normal and build dependencies in the locked
resolve graph (all features on, the widest case) and find the highest
`rust-version` any of them declares. The member must declare at least that.
Prints one line per member; exits 1 if any member declares less.
"""
import json
import subprocess
import sys


def version_tuple(v):
    return tuple(int(x) for x in v.split(".")) + (0,) * (3 - len(v.split(".")))


def main():
    meta = json.loads(
        subprocess.check_output(
            ["cargo", "metadata", "--format-version", "1", "--all-features", "--locked"]
        )
    )
    packages = {p["id"]: p for p in meta["packages"]}
    nodes = {n["id"]: n for n in meta["resolve"]["nodes"]}
    bad = 0
    for member in meta["workspace_members"]:
        seen, stack, top = set(), [member], (None, None)
        while stack:
            pid = stack.pop()
            if pid in seen:
                continue
            seen.add(pid)
            for dep in nodes[pid]["deps"]:
                kinds = {k["kind"] for k in dep["dep_kinds"]}
                if kinds - {"dev"}:
                    stack.append(dep["pkg"])
        for pid in seen - {member}:
            rv = packages[pid].get("rust_version")
            if rv and (top[0] is None or version_tuple(rv) > version_tuple(top[0])):
                top = (rv, packages[pid]["name"] + " " + packages[pid]["version"])
        own = packages[member].get("rust_version")
        name = packages[member]["name"]
        if own is None:
            print(f"msrv: {name} declares no rust-version")
            bad += 1
        elif top[0] and version_tuple(own) < version_tuple(top[0]):
            print(f"msrv: {name} declares {own} but {top[1]} needs {top[0]}")
            bad += 1
        else:
            print(f"msrv: {name} declares {own}; highest among its dependencies: {top[0]} ({top[1]})")
    sys.exit(1 if bad else 0)


if __name__ == "__main__":
    main()
