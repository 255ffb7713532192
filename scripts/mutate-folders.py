#!/usr/bin/python3
"""Mutation run over the folders and files mrloc reads from others (issue 51): a batch
folder (`mrloc batch --collect`), a run folder (`mrloc report`) or an import's input
(`mrloc import <format>`), each mutated N times at random (a byte flipped, the file cut short,
a value of another type, a huge number, 300,000 nested brackets, a link, a line repeated),
then the command run with a time limit. Every outcome is counted:
  refused   exit 1 and one line "mrloc <cmd>: error: ..." naming a file (never "unexpected")
  accepted  exit 0 (the mutation left a valid input: a byte of a name, a digit)
  unclean   any other exit, or a refusal of more than one line or an "unexpected error"
  crash     killed by a signal;   hang   over the time limit
  silent    exit 0 on a mutation no valid input survives (a link; 300,000 nested brackets
            outside a comment line, in a JSON file that no longer parses) in a file the
            command reads (a file is read if the command refuses it replaced by garbage)
Usage: scripts/mutate-folders.py <batch|report|import:FORMAT> <folder or input> N [seed]
The folder (or input) is copied for each mutation; the original is never touched."""
import json
import os
import random
import shutil
import subprocess
import sys
import tempfile
import time

MRLOC = os.environ.get("MRLOC", os.path.join(os.path.dirname(__file__), "..", "build", "apps",
                                             "mrloc", "mrloc"))


def mutate_bytes(data, rng):
    kind = rng.randrange(8)
    if not data:
        return b"{", "empty"
    i = rng.randrange(len(data))
    if kind == 0:
        return data[:i] + bytes([rng.randrange(256)]) + data[i + 1:], "byte"
    if kind == 1:
        return data[:i], "cut"
    if kind == 2:
        line = data[data.rfind(b"\n", 0, i) + 1:i].lstrip()
        commented = line.startswith((b"#", b"%", b"//"))
        return data[:i] + b"[" * 300000 + b"]" * 300000 + data[i:], \
            "nested in a comment" if commented else "nested"
    if kind == 3:
        return data[:i] + str(rng.choice(["1e19", "-1e308", "1.8e308", "nan", "-0", "4294967296",
                                          "true", "null", "\"x\"", "{}", "[]"])).encode() + data[i:], "value"
    if kind == 4:
        lines = data.split(b"\n")
        j = rng.randrange(len(lines))
        return b"\n".join(lines[:j] + [lines[j]] * rng.choice([2, 1000]) + lines[j + 1:]), "repeat"
    if kind == 5:
        return data.replace(b"\"", b"", 1), "quote"
    if kind == 6:
        try:  # a key's value swapped for another type
            j = json.loads(data)
            if isinstance(j, dict) and j:
                k = rng.choice(list(j))
                j[k] = rng.choice([5, "x", [1], {"a": 1}, None, True, 1e300])
                return json.dumps(j).encode(), "type"
        except Exception:
            pass
        return data + b"\x00", "nul"
    return data[:i] + data[i:i + 1] * 2000 + data[i:], "grow"


def still_json(path):
    if not path.endswith(".json"):
        return False
    try:
        json.loads(open(path, "rb").read())
        return True
    except Exception:
        return False


def run(cmd, limit=120):
    t0 = time.time()
    try:
        p = subprocess.run(cmd, capture_output=True, timeout=limit)
    except subprocess.TimeoutExpired:
        return "hang", time.time() - t0, ""
    dt = time.time() - t0
    err = p.stderr.decode(errors="replace").strip().split("\n")
    # mrloc's own progress lines aside, a refusal is one line: any other (a library's console
    # text before it, say) makes it unclean
    err = [l for l in err if l and not (l.startswith("mrloc batch: ") and ": error: " not in l)]
    if p.returncode < 0 or p.returncode >= 128:
        return "crash", dt, err[-1] if err else ""
    if p.returncode in (0, 3):
        return "accepted", dt, ""
    last = err[-1] if err else ""
    clean = p.returncode == 1 and len(err) == 1 and \
        "unexpected error" not in last and ": error: " in last
    return ("refused" if clean else "unclean"), dt, last


def main():
    kind, source, n = sys.argv[1], sys.argv[2], int(sys.argv[3])
    rng = random.Random(int(sys.argv[4]) if len(sys.argv) > 4 else 1)
    counts, longest, unclean = {}, (0, ""), []
    work = tempfile.mkdtemp(prefix="mrloc-mutate-")
    read_by_name = {}

    def reads(target, cmd):
        """Does `cmd` read this file? Asked once per name: the same copy with the file
        replaced by garbage must be refused."""
        name = os.path.relpath(target, os.path.join(work, "case"))
        if name not in read_by_name:
            data = open(target, "rb").read()
            open(target, "wb").write(b"\x00[garbage")
            read_by_name[name] = run(cmd)[0] != "accepted"
            open(target, "wb").write(data)
        return read_by_name[name]
    for k in range(n):
        case = os.path.join(work, "case")
        shutil.rmtree(case, ignore_errors=True)
        if kind.startswith("import:"):
            os.makedirs(case)
            inputs = source.split(",")
            if os.path.isdir(inputs[0]):  # MRCLAM: a folder of files
                copies = [shutil.copytree(inputs[0], case + "/in")]
                files = [os.path.join(copies[0], f) for f in os.listdir(copies[0])]
            else:
                copies = files = [shutil.copy(i, case) for i in inputs]
            target = rng.choice(files)
            options = sum((["--opt", o] for o in os.environ.get("MUTATE_OPTS", "").split()), [])
            cmd = [MRLOC, "import", kind.split(":", 1)[1]] + copies + options + \
                ["--out", case + "/o.rawlog"]
        else:
            shutil.copytree(source, case, symlinks=True)
            files = [os.path.join(d, f) for d, _, fs in os.walk(case) for f in fs
                     if f.endswith((".json", ".txt"))]
            target = rng.choice(files)
            cmd = [MRLOC, "batch", "--collect", case] if kind == "batch" else [MRLOC, "report", case]
        read_it = reads(target, cmd)  # asked before the mutation (a link's target is not ours)
        if rng.random() < 0.05 and not kind.startswith("import:"):
            os.remove(target)
            os.symlink("/etc/passwd", target)
            what = "link"
        else:
            data, what = mutate_bytes(open(target, "rb").read(), rng)
            open(target, "wb").write(data)
        outcome, dt, last = run(cmd)
        if outcome == "accepted" and what in ("link", "nested") and \
                not (what == "nested" and still_json(target)) and read_it:
            outcome = "silent"
        counts[outcome] = counts.get(outcome, 0) + 1
        if dt > longest[0]:
            longest = (dt, "%s %s" % (what, os.path.basename(target)))
        if outcome in ("unclean", "crash", "hang", "silent"):
            unclean.append("%d %s %s: %s: %s" % (k, what, os.path.basename(target), outcome, last))
    shutil.rmtree(work, ignore_errors=True)
    print("%s: %d mutations: %s; longest %.1f s (%s)" % (
        kind, n, ", ".join("%s %d" % kv for kv in sorted(counts.items())), longest[0], longest[1]))
    for u in unclean[:20]:
        print("  " + u)
    return 1 if unclean else 0


if __name__ == "__main__":
    sys.exit(main())
