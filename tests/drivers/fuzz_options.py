#!/usr/bin/python3
"""Fuzz test of Sable's input handling: mutated copies of the shipped option files.

Each run takes one file of cases/**/*.opts in turn (a whole case three times as often as a
one-line preset), applies one mutation drawn from a fixed seed (drop, duplicate or swap lines; a
value set to 0, negative, 1e30, 1e-30, nan, a word or nothing; a misspelt name; the file cut at
a random byte; junk bytes with NULs; a line over 4095 characters; a list one item short or long;
2147483648 for an integer; the option again with another value; a syntax slip such as CRLF, a
tab, "=" or an open quote; a cut or scribbled init frame), runs bin/sable on it with a short end
time on the command line (-dem_t_end for a dry case, -cpl_t_end for a coupled one; the file's
-io_interval is set to half of it) and -io_dir in a scratch directory, one run in five on 2
ranks, each under a timeout, and sorts the outcome:
  exit      exit status 0
  error     exit status 1 and stderr exactly one line "sable: error: ..."
  crash     a signal, exit status >= 128, a PETSc traceback, a segfault or a Python traceback
  hang      still running at the timeout
  bad       any other failure: no error line, several, other lines on stderr (Open MPI's
            MPI_ABORT banner and ORTE_ERROR_LOG lines included), an exit status other than 1,
            an error line with exit 0. On 2 ranks, mpiexec's own notice of a non-zero exit
            (which it prints for any program, and leaves out under mpiexec -q) is counted apart,
            and so is MPI_ABORT's notice after one rank's own error (which aborts to end the
            others at once).
  An error line is "sable: error: ..." or, for an error of one rank, "sable: error (rank N): ...".
and checks what each run left in -io_dir: a NaN or inf in any dataset or attribute of any .h5,
an .h5 that HDF5 cannot read, a *.tmp file (runs stopped at the timeout excepted).
The bounds are 0 crashes, 0 hangs, 0 non-finite values, 0 temporaries, every error one line;
a first check feeds the judge made-up runs of each kind to show that it can fail.
Options files with -dem_init_file start from a frame that the file of the same folder named by
the init file's prefix (silo/fill.opts for fill_000001.h5) writes first (none there: the file of
the folder the init file's directory names, silo/ for out/silo/fill_000001.h5); files without a domain
(cases/presets) are added after cases/settle/quick.opts (dry) or cases/fluidized_bed/small.opts.

Usage: fuzz_options.py [--runs N] [--seed S] [--timeout T] [--jobs J] [--case K [--keep]] [--dump F]
--case K rebuilds mutation K alone and runs it (with --keep its files stay: a reproducer).
"""
import argparse
import glob
import os
import random
import re
import shutil
import signal
import subprocess
import sys
import tempfile
import threading
import time
from concurrent.futures import ThreadPoolExecutor

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))  # tests/drivers/ -> the root
WORDS = ["abc", "yes", "none", "0x1p3", "1e5x", "--", "1,,2", "\u00e9t\u00e9", "inf", "-inf", "1e999"]
# Open MPI's own lines on stderr, by what printed them (they are counted as noise, not tolerated)
OMPI_LINES = [("MPI_ABORT banner", re.compile(r"MPI_ABORT was invoked|with errorcode|NOTE: invoking MPI_ABORT|You may or may not"
                                              r"|exactly when Open MPI|help message help-mpi-api|orte_base_help_aggregate")),
              ("ORTE_ERROR_LOG lines", re.compile(r"ORTE_ERROR_LOG")),
              ("mpiexec non-zero exit banner", re.compile(r"Primary job +terminated normally|a non-zero exit code\. Per user"
                                                          r"|exited with non-zero status|the job to be terminated|"
                                                          r"^\s*(Process name|Exit code):")),
              ("", re.compile(r"^-{20,}$"))]
LAUNCHER = OMPI_LINES[2][1]
ABORT = OMPI_LINES[0][1]
ORTE = OMPI_LINES[1][1]  # Open MPI 4.1's own race inside MPI_Abort (a bare MPI_Abort shows it too)
SEPARATOR = re.compile(r"^-{20,}$")
# an error every rank sees, or one rank's own error naming it
ONE_LINE = re.compile(r"^sable: error( \(rank \d+\))?: ")
CRASH = re.compile(r"PETSC ERROR|Segmentation|Traceback \(most recent call last\)|signal \d+|Caught signal|core dumped"
                   r"|double free|free\(\): |malloc\(\)|stack smashing|Floating point exception|Aborted|Bus error"
                   r"|Illegal instruction|exited on signal")


# ---------------------------------------------------------------------------------------------
# Cases: the shipped files, how each runs briefly


def opt_lines(text):
    """(line index, name, value) of every option line of an options file's text."""
    out = []
    for i, line in enumerate(text.split("\n")):
        body = line.split("#", 1)[0].split()
        if body and body[0].startswith("-") and len(body[0]) > 1 and body[0][1].isalpha():
            out.append((i, body[0], body[1] if len(body) > 1 else ""))
    return out


def opt_value(text, name, default=None):
    vals = [v for _, n, v in opt_lines(text) if n == name]
    return vals[-1] if vals else default


def set_option(text, name, value):
    """The text with option name's value set (its last line replaced, else a line added)."""
    lines = text.split("\n")
    hits = [i for i, n, _ in opt_lines(text) if n == name]
    if hits:
        lines[hits[-1]] = "%s %s" % (name, value)
    else:
        lines.insert(len(lines) - 1 if lines and lines[-1] == "" else len(lines), "%s %s" % (name, value))
    return "\n".join(lines)


def coupled(text):
    return any(n.startswith(("-cpl_", "-fluid_")) for _, n, _ in opt_lines(text))


def short_times(text):
    """(end option, end time, output interval) for a run of a few steps of this case."""
    if coupled(text):
        dt = float(opt_value(text, "-fluid_dt", 0) or 0)
        if dt <= 0:
            dt = float(opt_value(text, "-dem_dt", 1e-3)) * float(opt_value(text, "-cpl_substeps", 1))
        return "-cpl_t_end", "%.6g" % (4 * dt), "%.6g" % (2 * dt)
    dt = float(opt_value(text, "-dem_dt", 1e-5))
    return "-dem_t_end", "%.6g" % (20 * dt), "%.6g" % (10 * dt)


class Case:
    """A shipped file as it is fuzzed: the file's text (init file pointed at a fresh frame) and,
    for a file without a domain, the base case it is added to."""

    def __init__(self, rel, text, base=None):
        self.rel, self.text, self.base = rel, text, base
        scene = base.text if base else text
        self.end_opt, self.t_end, self.interval = short_times(scene + "\n" + (text if base else ""))


def prepare_cases(work, sable):
    """Every cases/**/*.opts as a Case; runs the fill stage that an init file names. Returns
    (cases, problems)."""
    paths = sorted(glob.glob(os.path.join(ROOT, "cases", "**", "*.opts"), recursive=True))
    texts = {os.path.relpath(p, ROOT): open(p, encoding="utf-8").read() for p in paths}
    problems, cases, made = [], [], {}
    for rel, text in texts.items():
        init = opt_value(text, "-dem_init_file")
        if init:
            prefix = os.path.basename(init).rsplit("_", 1)[0]
            folder = os.path.dirname(rel)
            writes = lambda f: [r for r, t in texts.items() if os.path.dirname(r) == f and opt_value(t, "-io_prefix") == prefix
                                and not opt_value(t, "-dem_init_file")]
            # the same folder's, else the case folder the init file's directory names (out/silo/...)
            src = writes(folder) or writes(os.path.join("cases", os.path.basename(os.path.dirname(init))))
            if not src:
                problems.append("%s: no file in %s writes %s" % (rel, folder, init))
                continue
            if src[0] not in made:
                made[src[0]] = run_fill(work, sable, src[0], texts[src[0]], problems)
            if not made[src[0]]:
                continue
            text = set_option(text, "-dem_init_file", made[src[0]])
        if opt_value(text, "-domain_lo") or opt_value(text, "-dem_init_file"):
            _, _, interval = short_times(text)
            cases.append(Case(rel, set_option(text, "-io_interval", interval)))
    by_rel = {c.rel: c for c in cases}
    for rel, text in texts.items():
        if not (opt_value(text, "-domain_lo") or opt_value(text, "-dem_init_file")):
            base = by_rel.get("cases/fluidized_bed/small.opts" if coupled(text) else "cases/settle/quick.opts")
            if base is None:
                problems.append("%s: its base case is missing" % rel)
            else:
                cases.append(Case(rel, text, base))
    return cases, problems


def run_fill(work, sable, rel, text, problems):
    """Runs the fill stage rel for a few steps; returns the path of its frame 1, or None."""
    end_opt, t_end, _ = short_times(text)
    out = os.path.join(work, "init", os.path.basename(os.path.dirname(rel)))
    prefix = opt_value(text, "-io_prefix", "sable")
    os.makedirs(os.path.dirname(out), exist_ok=True)
    cmd = [sable, "-options_file", os.path.join(ROOT, rel), end_opt, t_end, "-io_interval", t_end, "-io_dir", out]
    try:
        p = subprocess.run(cmd, cwd=work, capture_output=True, text=True, errors="replace", timeout=120)
    except subprocess.TimeoutExpired:
        problems.append("init frame from %s: no exit after 120 s" % rel)
        return None
    frame = os.path.join(out, "%s_000001.h5" % prefix)
    if p.returncode != 0 or not os.path.exists(frame):
        problems.append("init frame from %s: exit %d, %s" % (rel, p.returncode, (p.stderr or p.stdout).strip()[-200:]))
        return None
    return frame


# ---------------------------------------------------------------------------------------------
# Mutations: each returns (new bytes, description)


def show(s, n=70):
    s = s if isinstance(s, str) else s.decode("utf-8", "backslashreplace")
    return repr(s if len(s) <= n else s[:n] + "...(%d chars)" % len(s))


def pick_line(rng, text, pred=lambda name, value: True):
    lines = [(i, n, v) for i, n, v in opt_lines(text) if pred(n, v)]
    return rng.choice(lines) if lines else None


def replace_line(text, i, new):
    lines = text.split("\n")
    old = lines[i]
    lines[i] = new
    return "\n".join(lines), "line %d: %s -> %s" % (i + 1, show(old), show(new))


def m_drop(rng, text):
    i, n, v = pick_line(rng, text)
    lines = text.split("\n")
    old = lines.pop(i)
    return "\n".join(lines), "drop line %d %s" % (i + 1, show(old))


def m_duplicate(rng, text):
    i, n, v = pick_line(rng, text)
    lines = text.split("\n")
    lines.insert(i + 1, lines[i])
    return "\n".join(lines), "duplicate line %d %s" % (i + 1, show(lines[i]))


def m_value(rng, text):
    i, n, v = pick_line(rng, text)
    items = v.split(",") if v else [""]
    new = rng.choice(["0", "-" + (items[0].lstrip("-") or "1"), "1e30", "1e-30", "nan", rng.choice(WORDS), ""])
    if len(items) > 1 and new and rng.random() < 0.5:  # one item of a list
        items[rng.randrange(len(items))] = new
        new = ",".join(items)
    return replace_line(text, i, ("%s %s" % (n, new)).rstrip())


def m_swap(rng, text):
    a, b = pick_line(rng, text), pick_line(rng, text)
    if a[0] == b[0]:
        t, d = m_drop(rng, text)
        return t, "(one line) " + d
    t, d1 = replace_line(text, a[0], ("%s %s" % (a[1], b[2])).rstrip())
    t, d2 = replace_line(t, b[0], ("%s %s" % (b[1], a[2])).rstrip())
    return t, "swap values: %s; %s" % (d1, d2)


def m_misspell(rng, text):
    i, n, v = pick_line(rng, text)
    name = list(n)
    k = rng.randrange(2, len(name))
    op = rng.choice(["delete", "double", "transpose", "replace"])
    if op == "delete":
        del name[k]
    elif op == "double":
        name.insert(k, name[k])
    elif op == "transpose" and k + 1 < len(name):
        name[k], name[k + 1] = name[k + 1], name[k]
    else:
        name[k] = rng.choice("abcdefghijklmnopqrstuvwxyz_")
    return replace_line(text, i, ("%s %s" % ("".join(name), v)).rstrip())


def m_truncate(rng, data):
    k = rng.randrange(len(data))
    line = data[:k].count(b"\n") + 1
    tail = data[:k].rsplit(b"\n", 1)[-1]
    return data[:k], "truncate at byte %d of %d (line %d ends %s)" % (k, len(data), line, show(tail))


def m_junk(rng, data):
    kind = rng.choice(["nul", "nul", "binary", "control", "utf8"])
    if kind == "nul":
        junk = b"\0" * rng.randint(1, 3)
    elif kind == "binary":
        junk = bytes(rng.randrange(256) for _ in range(rng.randint(1, 16)))
    elif kind == "control":
        junk = bytes(rng.choice([0, 1, 7, 8, 9, 11, 12, 13, 27, 127]) for _ in range(rng.randint(1, 6)))
    else:
        junk = "\u00ff\ufeff\u2212".encode()
    k = rng.randrange(len(data) + 1)
    return data[:k] + junk + data[k:], "insert %s at byte %d (line %d)" % (repr(junk), k, data[:k].count(b"\n") + 1)


def m_long_line(rng, text):
    length = rng.choice([4095, 4096, rng.randint(4097, 6000), 100000])
    kind = rng.choice(["comment", "value", "name", "list"])
    if kind == "comment":
        line = "#" + "x" * (length - 1)
    elif kind == "name":
        line = "-dem_" + "k" * (length - 5)
    elif kind == "list":
        i, n, v = pick_line(rng, text)
        item = (v.split(",")[0] or "1")
        line = n + " " + ",".join([item] * (length // (len(item) + 1)))
        line = line[:length].rstrip(",")
    else:
        i, n, v = pick_line(rng, text)
        line = n + " " + "9" * max(1, length - len(n) - 1)
    lines = text.split("\n")
    k = rng.randrange(len(lines) + 1)
    lines.insert(k, line)
    return "\n".join(lines), "insert at line %d a %s line of %d characters: %s" % (k + 1, kind, len(line), show(line, 40))


def m_list_count(rng, text):
    hit = pick_line(rng, text, lambda n, v: "," in v)
    if not hit:
        t, d = m_value(rng, text)
        return t, "(no list) " + d
    i, n, v = hit
    items = v.split(",")
    new = items[:-1] if rng.random() < 0.5 else items + [items[-1]]
    return replace_line(text, i, "%s %s" % (n, ",".join(new)))


def m_huge_int(rng, text):
    hit = pick_line(rng, text, lambda n, v: bool(re.fullmatch(r"-?\d+(,-?\d+)*", v)))
    if not hit:
        t, d = m_value(rng, text)
        return t, "(no integer) " + d
    i, n, v = hit
    big = rng.choice(["2147483648", "4294967296", "9223372036854775808", "-2147483649", "99999999999999999999"])
    items = v.split(",")
    items[rng.randrange(len(items))] = big
    return replace_line(text, i, "%s %s" % (n, ",".join(items)))


def m_redefine(rng, text):
    i, n, v = pick_line(rng, text)
    other = rng.choice(["0", "1", "-1", "2", "0.5", "abc", ""])
    lines = text.split("\n")
    k = rng.randrange(len(lines) + 1)
    lines.insert(k, ("%s %s" % (n, other)).rstrip())
    return "\n".join(lines), "line %d %s given again at line %d as %s" % (i + 1, show(n + " " + v), k + 1, show(other))


def m_syntax(rng, text):
    i, n, v = pick_line(rng, text)
    form = rng.choice(["crlf", "tab", "dashdash", "quote", "equals", "two values", "comment in value", "unknown word"])
    lines = text.split("\n")
    if form == "crlf":
        return "\r\n".join(lines), "CRLF line ends"
    new = {"tab": "%s\t%s" % (n, v), "dashdash": "-%s %s" % (n, v), "quote": '%s "%s' % (n, v),
           "equals": "%s=%s" % (n, v), "two values": "%s %s %s" % (n, v, v), "comment in value": "%s #%s" % (n, v),
           "unknown word": "%s %s" % (n.lstrip("-"), v)}[form]
    return replace_line(text, i, new)


MUTATIONS = [("drop", m_drop, "text"), ("duplicate", m_duplicate, "text"), ("value", m_value, "text"),
             ("value", m_value, "text"), ("swap", m_swap, "text"), ("misspell", m_misspell, "text"),
             ("truncate", m_truncate, "bytes"), ("junk", m_junk, "bytes"), ("long line", m_long_line, "text"),
             ("list count", m_list_count, "text"), ("huge integer", m_huge_int, "text"),
             ("redefine", m_redefine, "text"), ("syntax", m_syntax, "text"), ("init file", None, "init")]


def schedule(cases):
    """The order in which runs visit the files: each whole case three times per round, each
    one-line file added to a base case (cases/presets) once."""
    full = [c for c in cases if not c.base]
    return full + [c for c in cases if c.base] + full + full


def make_run(k, order, seed, work):
    """Builds mutation k (reproducible: its own generator seeded by seed and k): writes the
    mutated file(s) under work/k and returns the run's description."""
    rng = random.Random("%d:%d" % (seed, k))
    case = order[k % len(order)]
    kind, fn, form = rng.choice(MUTATIONS)
    d = os.path.join(work, "run%04d" % k)
    os.makedirs(d)
    text = case.text
    if form == "init":
        init = opt_value(text, "-dem_init_file")
        if not init:
            kind, fn, form = "value", m_value, "text"
        else:
            data = open(init, "rb").read()
            how = rng.choice(["cut", "scribble"])
            if how == "cut":
                at = rng.randrange(len(data))
                desc = "init frame %s cut at byte %d of %d" % (os.path.basename(init), at, len(data))
                data = data[:at]
            else:
                data = bytearray(data)
                at = rng.randrange(len(data))
                n = rng.randint(1, 64)
                data[at:at + n] = bytes(rng.randrange(256) for _ in range(len(data[at:at + n])))
                desc = "init frame %s: %d random bytes at byte %d" % (os.path.basename(init), n, at)
            bad = os.path.join(d, "init.h5")
            open(bad, "wb").write(bytes(data))
            mutated = set_option(text, "-dem_init_file", bad).encode()
    if form == "text":
        new, desc = fn(rng, text)
        mutated = new.encode("utf-8", "surrogateescape")
    elif form == "bytes":
        mutated, desc = fn(rng, text.encode())
    path = os.path.join(d, os.path.basename(case.rel))
    open(path, "wb").write(mutated)
    ranks = 2 if rng.random() < 0.2 else 1
    files = []
    if case.base:
        base = os.path.join(d, "base_" + os.path.basename(case.base.rel))
        open(base, "w", encoding="utf-8").write(case.base.text)
        files += ["-options_file", base]
    files += ["-options_file", path]
    sable = os.path.join(ROOT, os.environ.get("BIN", "bin"), "sable")
    cmd = [sable] + files + [case.end_opt, case.t_end, "-io_dir", os.path.join(d, "out")]
    if ranks == 2:
        cmd = ["mpiexec", "--oversubscribe", "-n", "2"] + cmd
    return {"k": k, "case": case.rel, "kind": kind, "desc": desc, "cmd": cmd, "dir": d, "ranks": ranks}


# ---------------------------------------------------------------------------------------------
# Running and judging


class Slots:
    """At most `jobs` processes at once; a 2-rank run takes two slots."""

    def __init__(self, jobs):
        self.jobs, self.used, self.cv = jobs, 0, threading.Condition()

    def take(self, n):
        n = min(n, self.jobs)
        with self.cv:
            self.cv.wait_for(lambda: self.used + n <= self.jobs)
            self.used += n
        return n

    def give(self, n):
        with self.cv:
            self.used -= n
            self.cv.notify_all()


def execute(run, timeout, slots):
    n = slots.take(run["ranks"])
    try:
        t0 = time.time()
        p = subprocess.Popen(run["cmd"], cwd=run["dir"], stdin=subprocess.DEVNULL, stdout=subprocess.PIPE,
                             stderr=subprocess.PIPE, start_new_session=True)
        try:
            out, err = p.communicate(timeout=timeout)
            run["hang"] = False
        except subprocess.TimeoutExpired:
            os.killpg(p.pid, signal.SIGTERM)
            try:
                out, err = p.communicate(timeout=5)
            except subprocess.TimeoutExpired:
                os.killpg(p.pid, signal.SIGKILL)
                out, err = p.communicate()
            run["hang"] = True
        run["rc"], run["seconds"], run["timeout"] = p.returncode, time.time() - t0, timeout
        run["out"] = out.decode("utf-8", "backslashreplace")
        run["err"] = err.decode("utf-8", "backslashreplace")
    finally:
        slots.give(n)
    judge(run)
    return run


def scan_h5(path):
    """Non-finite values in every dataset and attribute of one HDF5 file: (count, where)."""
    import h5py
    import numpy as np
    bad = []

    def check(name, arr):
        arr = np.asarray(arr)
        if arr.dtype.kind in "fc":
            nbad = int(np.size(arr) - np.count_nonzero(np.isfinite(arr)))
            if nbad:
                bad.append((nbad, name))

    def visit(name, obj):
        for a, val in obj.attrs.items():
            check("%s@%s" % (name, a), val)
        if isinstance(obj, h5py.Dataset):
            check(name, obj[()])

    with h5py.File(path, "r") as f:
        visit("/", f)
        f.visititems(visit)
    return bad


def judge(run):
    """Sorts one finished run into its class and failure signature."""
    err_lines = [l for l in run["err"].split("\n") if l.strip()]
    errors = [l for l in err_lines if l.startswith("sable: error")]
    other = [l for l in err_lines if not l.startswith("sable: error")]
    # mpiexec's own notice that a rank exited non-zero: the launcher reports any program's
    # non-zero exit so (mpiexec -n 2 false prints it too; mpiexec -q leaves it out); it is
    # counted apart, while MPI_ABORT's banner and ORTE_ERROR_LOG lines stay failures
    # one rank's own error ends the run through MPI_Abort (the launcher then ends the others at
    # once), so MPI_ABORT's notice follows it, and sometimes Open MPI's ORTE_ERROR_LOG line of a
    # race inside MPI_Abort; after any other error both are failures
    own = len(errors) == 1 and errors[0].startswith("sable: error (rank ")
    notices = (LAUNCHER, ABORT, ORTE) if own else (LAUNCHER,)
    launcher = [l for l in other if run.get("ranks", 1) == 2 and (any(p.search(l) for p in notices) or SEPARATOR.match(l))]
    run["launcher"] = bool(launcher) and any(p.search(l) for l in launcher for p in notices)
    other = [l for l in other if l not in launcher]
    rc, text = run["rc"], run["out"] + "\n" + run["err"]
    crash = CRASH.search(text)
    run["problems"] = []
    if run["hang"]:
        cls, why = "hang", "no exit after %g s" % run["timeout"]
    elif rc < 0 or rc >= 128 or crash:
        cls, why = "crash", "exit %d: %s" % (rc, crash.group(0) if crash else "signal %d" % -rc if rc < 0 else "status")
    elif rc == 0 and not errors:
        cls, why = "exit", ""
    elif rc == 1 and len(errors) == 1 and ONE_LINE.match(errors[0]) and not other:
        cls, why = "error", ""
    else:
        cls = "bad"
        if rc == 0:
            why = "exit 0 with an error line"
        elif not errors:
            why = "exit %d without a 'sable: error:' line" % rc
        elif len(errors) > 1:
            why = "%d 'sable: error' lines" % len(errors)
        elif not ONE_LINE.match(errors[0]):
            why = "error line not 'sable: error: ...': %s" % errors[0][:40]
        elif other and all(any(p.search(l) for _, p in OMPI_LINES) for l in other):
            why = "Open MPI lines besides the error: " + ", ".join(
                w for w, p in OMPI_LINES if w and any(p.search(l) for l in other))
        elif other:
            why = "other lines on stderr"
        else:
            why = "exit %d" % rc
    run["class"], run["why"] = cls, why
    out = os.path.join(run["dir"], "out")
    run["nonfinite"], run["tmp"], run["unreadable"] = [], [], []
    if os.path.isdir(out):
        for f in sorted(os.listdir(out)):
            path = os.path.join(out, f)
            if ".tmp" in f and not run["hang"]:
                run["tmp"].append(f)
            elif f.endswith(".h5") and not run["hang"]:
                try:
                    run["nonfinite"] += [(f, n, w) for n, w in scan_h5(path)]
                except Exception as e:  # a frame HDF5 cannot read
                    run["unreadable"].append("%s: %s" % (f, str(e).split("\n")[0][:100]))


def signature(run):
    """What makes two failures the same defect, roughly: class, reason, the first error line with
    its numbers blanked."""
    first = ([l for l in run["err"].split("\n") if l.startswith("sable: error")] or [""])[0]
    first = re.sub(r"-?\d[\d.e+-]*", "#", first)[:60]
    if run["class"] in ("crash", "hang"):
        opt = re.search(r"-[a-z][a-z0-9_]*", run["desc"])
        return (run["class"], run["why"].split(":")[0], opt.group(0) if opt else run["desc"])
    return (run["class"], run["why"], first if run["class"] == "bad" and "Open MPI" not in run["why"] else "")


def reproducer(run, extra=""):
    """A failure as NOTE lines (tests/run.sh shows only PASS, FAIL and NOTE lines): the mutation,
    the command (D: the run's scratch directory) and the first lines of its output."""
    cmd = " ".join(c if re.fullmatch(r"[-\w./,=]+", c) else "'%s'" % c for c in run["cmd"])
    cmd = cmd.replace(run["dir"], "$D").replace(ROOT + "/", "")
    tag = "NOTE fuzz repro #%d:" % run["k"]
    lines = ["%s %s [%s] %s" % (tag, run["case"], run["kind"], run["desc"]),
             "%s   command: %s  (D: tests/drivers/fuzz_options.py --case %d --keep rebuilds it)" % (tag, cmd, run["k"]),
             "%s   %s, exit %s%s" % (tag, run["class"] + (": " + run["why"] if run["why"] else ""), run["rc"], extra)]
    err = [l for l in run["err"].split("\n") if l.strip()]
    err = [l for l in err if l.startswith("sable: error")] + [l for l in err if not l.startswith("sable: error")]
    lines += ["%s   stderr: %s" % (tag, l[:200]) for l in err[:3]]
    if not err:
        lines += ["%s   stdout: %s" % (tag, l[:200]) for l in [l for l in run["out"].split("\n") if l.strip()][-2:]]
    return "\n".join(lines)


def report(runs, problems, seed, elapsed, show_max=8):
    n = len(runs)
    counts = {}
    for r in runs:
        counts[r["class"]] = counts.get(r["class"], 0) + 1
    nf = [r for r in runs if r["nonfinite"]]
    unread = [r for r in runs if r["unreadable"]]
    tmp = [r for r in runs if r["tmp"]]
    two = sum(r["ranks"] == 2 for r in runs)
    fail = bool(problems)
    for p in problems:
        print("FAIL fuzz setup: %s" % p)

    def line(ok, what, bad, extra_fn=None):
        print("%s fuzz: %s (0 allowed)" % ("PASS" if ok else "FAIL", what))
        if not ok:
            seen = {}
            for r in bad:
                seen.setdefault(signature(r), r)
            print("NOTE fuzz repro: %d kinds of failure; the first run of each (up to %d):" % (len(seen), show_max))
            for r in list(seen.values())[:show_max]:
                print(reproducer(r, extra_fn(r) if extra_fn else ""))
        return not ok

    crashes = [r for r in runs if r["class"] == "crash"]
    hangs = [r for r in runs if r["class"] == "hang"]
    bad = [r for r in runs if r["class"] == "bad"]
    fail |= line(not crashes, "%d crashes in %d runs" % (len(crashes), n), crashes)
    fail |= line(not hangs, "%d hangs in %d runs" % (len(hangs), n), hangs)
    fail |= line(not nf, "%d non-finite values written (%d runs)" % (sum(x[1] for r in nf for x in r["nonfinite"]), len(nf)),
                 nf, lambda r: "; non-finite: " + ", ".join("%s:%s %d" % (f, w, c) for f, c, w in r["nonfinite"][:3]))
    fail |= line(not unread, "%d unreadable .h5 files written (%d runs)" % (sum(len(r["unreadable"]) for r in unread), len(unread)),
                 unread, lambda r: "; " + r["unreadable"][0])
    errs = counts.get("error", 0) + len(bad)
    fail |= line(not bad, "every error exactly one 'sable: error:' line: %d of %d failing runs are not" % (len(bad), errs), bad)
    fail |= line(not tmp, "%d temporaries left (%d runs)" % (sum(len(r["tmp"]) for r in tmp), len(tmp)), tmp,
                 lambda r: "; left: " + ", ".join(r["tmp"][:3]))
    reasons = {}
    for r in bad:
        reasons[r["why"]] = reasons.get(r["why"], 0) + 1
    kinds = {}
    for r in runs:
        kinds.setdefault(r["kind"], {}).setdefault(r["class"], 0)
        kinds[r["kind"]][r["class"]] += 1
    print("NOTE fuzz classes: %d runs (%d on 2 ranks, %d case files, seed %d, %.0f s): clean exit %d, clean error %d, "
          "crash %d, hang %d, bad error %d%s, non-finite %d, unreadable frame %d, temporaries %d"
          % (n, two, len({r["case"] for r in runs}), seed, elapsed, counts.get("exit", 0), counts.get("error", 0),
             len(crashes), len(hangs), len(bad),
             " (" + "; ".join("%s %d" % kv for kv in sorted(reasons.items())) + ")" if reasons else "",
             len(nf), len(unread), len(tmp)))
    vague = {}
    for r in runs:
        for l in r["err"].split("\n"):
            msg = re.sub(r"^sable: error( \(rank \d+\))?: ", "", l)
            if msg != l and not re.search(r"(^|[\s'(])--?[a-z]", msg):
                vague.setdefault(re.sub(r"-?\d[\d.e+-]*", "#", msg)[:80], (r, msg))
    print("NOTE fuzz: %d distinct error messages name no option (the first 5 below)" % len(vague))
    for r, msg in list(vague.values())[:5]:
        print("NOTE fuzz vague #%d: %s [%s] %s: %s" % (r["k"], r["case"], r["kind"], r["desc"][:100], msg[:120]))
    print("NOTE fuzz: %d of %d runs on 2 ranks that failed also got Open MPI's own notice of the exit (mpiexec's of a non-zero exit, or MPI_ABORT's after one rank's error)"
          % (sum(r.get("launcher", False) for r in runs), sum(r["ranks"] == 2 and r["class"] != "exit" for r in runs)))
    print("NOTE fuzz by mutation: " + "; ".join("%s %s" % (k, " ".join("%s %d" % kv for kv in sorted(v.items())))
                                               for k, v in sorted(kinds.items())))
    return fail


def self_check(work, slots):
    """The judge on made-up runs, one per failure class it must see: returns the misjudged ones."""
    import h5py
    import numpy as np
    sable_err = "sable: error: -dem_kn 0. must be > 0\n"
    banner = "-" * 74 + "\nMPI_ABORT was invoked on rank 1 in communicator MPI_COMM_WORLD\nwith errorcode 1.\n"
    notice = ("-" * 74 + "\nPrimary job  terminated normally, but 1 process returned\na non-zero exit code. Per user-direction, "
              "the job has been aborted.\n" + "-" * 74 + "\n")
    made = [("exit", "", 0, "", None), ("error", "", 1, sable_err, None), ("crash", "", 1, sable_err + "[0]PETSC ERROR: x\n", None),
            ("bad", "", 1, sable_err + banner, None), ("bad", "", 1, sable_err * 2, None), ("bad", "", 2, "", None),
            ("bad", "", 0, sable_err, None), ("nonfinite", "", 0, "", "nan"), ("tmp", "", 0, "", "tmp"),
            ("error", 2, 1, sable_err + notice, None), ("error", 2, 1, "sable: error (rank 1): t = 1 s: x\n", None),
            ("bad", 2, 1, sable_err + notice + banner, None), ("bad", 1, 1, sable_err + notice, None),
            ("error", 2, 1, "sable: error (rank 1): t = 1 s: x\n" + banner, None)]
    wrong = []
    for i, (want, ranks, rc, err, frame) in enumerate(made):
        d = os.path.join(work, "judge%d" % i)
        os.makedirs(os.path.join(d, "out"))
        if frame == "nan":
            with h5py.File(os.path.join(d, "out", "s_000000.h5"), "w") as f:
                f["particles/position"] = np.array([[0.0, np.nan, 1.0]])
        elif frame == "tmp":
            open(os.path.join(d, "out", "s_000001.h5.tmp"), "w").close()
        r = {"k": -1, "dir": d, "rc": rc, "out": "", "err": err, "hang": False, "timeout": 1, "ranks": ranks or 1}
        judge(r)
        got = "nonfinite" if r["nonfinite"] else "tmp" if r["tmp"] else r["class"]
        if got != want:
            wrong.append("%s judged %s" % (want, got))
    for want, cmd, t in [("crash", ["sh", "-c", "kill -SEGV $$"], 10), ("hang", ["sleep", "10"], 0.5)]:
        d = os.path.join(work, "judge_" + want)
        os.makedirs(d)
        r = execute({"k": -1, "cmd": cmd, "dir": d, "ranks": 1}, t, slots)
        if r["class"] != want:
            wrong.append("%s judged %s" % (want, r["class"]))
    return wrong, len(made) + 2


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    # 150: with today's 29 files two rounds of the schedule (every whole case 6 times, every preset twice)
    ap.add_argument("--runs", type=int, default=int(os.environ.get("FUZZ_RUNS", 150)))
    ap.add_argument("--seed", type=int, default=int(os.environ.get("FUZZ_SEED", 20240611)))
    ap.add_argument("--timeout", type=float, default=float(os.environ.get("FUZZ_TIMEOUT", 20)))
    ap.add_argument("--jobs", type=int, default=int(os.environ.get("FUZZ_JOBS", 2)))
    ap.add_argument("--case", type=int, default=None, help="rebuild and run mutation K alone")
    ap.add_argument("--keep", action="store_true", help="keep the scratch directory")
    ap.add_argument("--dump", help="write every run (command, class, output) to this JSON file")
    a = ap.parse_args()
    try:
        import h5py  # noqa: F401
    except ImportError as e:
        print("FAIL fuzz: cannot check the frames: %s" % e)
        return 1
    sable = os.path.join(ROOT, os.environ.get("BIN", "bin"), "sable")
    if not os.access(sable, os.X_OK):
        print("FAIL fuzz: %s is not built" % sable)
        return 1
    os.environ.setdefault("OMPI_MCA_rmaps_base_oversubscribe", "1")
    if os.getuid() == 0:  # as tests/run.sh does
        os.environ.update(OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")
    work = tempfile.mkdtemp(prefix="sable-fuzz-")
    t0 = time.time()
    try:
        cases, problems = prepare_cases(work, sable)
        if not cases:
            print("FAIL fuzz: no case files")
            return 1
        ks = [a.case] if a.case is not None else range(a.runs)
        order = schedule(cases)
        runs = [make_run(k, order, a.seed, work) for k in ks]
        slots = Slots(max(1, a.jobs))
        wrong, nmade = self_check(work, slots)
        if a.case is None:
            print("%s fuzz judge: %d of %d made-up runs misjudged%s (0 allowed: a crash, a hang, a NaN in a frame, "
                  "a .tmp, an MPI_ABORT banner, two error lines, no error line, an error with exit 0 are each caught; "
                  "one rank's error line (with MPI_ABORT's notice) and, on 2 ranks, mpiexec's notice of the non-zero exit pass)"
                  % ("FAIL" if wrong else "PASS", len(wrong), nmade, ": " + "; ".join(wrong) if wrong else ""))
        with ThreadPoolExecutor(max_workers=max(1, a.jobs)) as pool:
            runs = list(pool.map(lambda r: execute(r, a.timeout, slots), runs))
        if a.case is not None:
            r = runs[0]
            print("mutation #%d of %s [%s]: %s" % (r["k"], r["case"], r["kind"], r["desc"]))
            print("command: (cd %s && %s)" % (r["dir"], " ".join("'%s'" % c for c in r["cmd"])))
            print("class %s %s, exit %s, %.1f s" % (r["class"], r["why"], r["rc"], r["seconds"]))
            print("stderr:\n" + r["err"])
            if a.keep:
                print("kept: %s" % work)
            return 0
        fail = report(runs, problems, a.seed, time.time() - t0) or bool(wrong)
        if a.dump:
            import json
            with open(a.dump, "w") as f:
                json.dump(runs, f, indent=1)
        return 1 if fail else 0
    finally:
        if not a.keep:
            shutil.rmtree(work, ignore_errors=True)


if __name__ == "__main__":
    sys.exit(main())
