"""The mutation check (tests/mutation/run.sh, which finds the Python): apply each mutant of
tests/mutation/mutants.txt to a scratch copy of the tree, build, run the test suite and
report whether a test killed it.

    mutation.py REPO [--mutants FILE] [--only ID,ID] [--keep] [--no-baseline] [--timeout SEC] [--list]
                     [--doc FILE]

1. The tree (tracked and untracked, not ignored, files of REPO) is copied to a scratch
   directory under $TMPDIR and built there (Release); REPO is never touched.
2. Baseline: the unmutated copy runs every test once (test_slurm aside: it checks the scan
   scripts on a Slurm cluster, not the code), in the order of tests/mutation/order.txt
   (fastest first; tests missing from it run last). A test that fails here is reported and
   left out. --no-baseline skips this (the order file's tests are all taken as passing).
3. Each mutant: the original text (any whitespace between its words) must occur exactly
   once in its file, else it "did not apply". It is replaced, the build is incremental, and
   the tests run in order, two at a time (2 cores), stopping at the first failure (a test
   that exceeds its time limit, 5 times its baseline time and at least 30 s, fails too):
   KILLED by that test, or, when all pass, the mutant's binary and the unmutated one run the
   fixed cases of EQUIVALENCE_CASES and their files are compared with
   tests/tools/regression.py same (every dataset and attribute, provenance aside): no
   difference anywhere means EQUIVALENT (not counted), else SURVIVED. A mutant that does not
   compile is "did not build" (not counted). The file is restored before the next mutant.
4. The report (one line per mutant, then a markdown table and the totals) goes to stdout;
   --doc FILE also puts the table into FILE's section DOC_HEADING (docs/verification.md),
   replacing the section of an earlier run.
Exit status 0 when every counted mutant was killed, 1 otherwise, 2 on a usage or setup error.
"""
import argparse
import os
import re
import shutil
import subprocess
import sys
import tempfile
import time
from dataclasses import dataclass, field

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "tools"))
import regression  # noqa: E402  (tests/tools/regression.py: same)

EXCLUDED_TESTS = ("test_slurm",)
DOC_HEADING = "## 7. Mutation check (`tests/mutation/run.sh`)"
DOC_TEXT = """
Does the suite catch the bugs a developer would make? `tests/mutation/mutants.txt` lists
single, plausible bugs (a sign, a factor, an index, a forgotten statement) in the scheme, the
time schemes, the energy monitor, the contact law, step control, events, restart, the
adaptive mesh, the linear algebra and the output; `tests/mutation/run.sh` applies each to a
scratch copy of the tree, builds it and runs the suite, fastest tests first, until a test
fails: that test killed the mutant. A mutant no test kills is run on 18 fixed cases (every
scheme, both laws and methods, adaptive steps and mesh, the impact, checkpoints and their
restarts) and its files compared with the unmutated program's (`tests/tools/regression.py
same`): if nothing differs it is equivalent (not a bug, not counted), else it survived, and a
test that kills it is missing. Not part of CI (about {minutes} minutes on 2 cores); run on
demand, e.g. after changing the tests or the code the mutants are anchored on (a mutant whose
text is no longer found "did not apply").

Last run: {date}, commit {commit}, `{command}`.
"""
MIN_TIMEOUT = 30.0
TIMEOUT_FACTOR = 5.0

# Fixed runs (input file of input/, --set overrides) whose outputs decide equivalence: every
# scheme, both contact laws and both methods, adaptive steps, the adaptive mesh, events,
# a checkpoint and its restart ("@restart NAME": continue NAME's checkpoint).
EQUIVALENCE_CASES = [
    ("e1_euler", "exp1.nml", "mesh.n_elements=100 time.t_end=0.3 output.snapshot_every=500"),
    ("e1_bdf2", "exp1.nml", "mesh.n_elements=100 time.t_end=0.3 time.scheme='bdf2' output.snapshot_every=500"),
    ("e1_mid", "exp1.nml", "mesh.n_elements=100 time.t_end=0.3 time.scheme='midpoint' output.snapshot_every=500"),
    ("e1_paper", "exp1.nml", "mesh.n_elements=100 time.t_end=0.25 solver.method='paper' output.snapshot_every=500"),
    ("e2_sig", "exp2.nml", "mesh.n_elements=100 time.t_end=0.3 contact.law='signorini' output.snapshot_every=500"),
    ("e3", "exp3.nml", "mesh.n_elements=100 time.t_end=0.35 output.snapshot_every=500"),
    ("ad_euler", "exp1.nml", "mesh.n_elements=100 time.t_end=1.5 time.adaptive=.true."),
    ("ad_bdf2", "exp1.nml", "mesh.n_elements=100 time.t_end=1.5 time.adaptive=.true. time.scheme='bdf2' "
                            "output.checkpoint_every=50"),
    ("ad_bdf2_rest", "exp1.nml", "mesh.n_elements=100 time.t_end=2.0 time.adaptive=.true. time.scheme='bdf2' "
                                 "@restart ad_bdf2"),
    ("ad_mid", "exp1.nml", "mesh.n_elements=100 time.t_end=1.5 time.adaptive=.true. time.scheme='midpoint' "
                           "output.snapshot_dt=0.5"),
    ("am_bdf2", "exp2.nml", "time.t_end=0.03 mesh.adaptive=.true. mesh.max_level=3 time.adaptive=.true. "
                            "time.scheme='bdf2' time.error_tol=1e-4 output.snapshot_dt=0.01 output.checkpoint_every=20"),
    ("am_bdf2_rest", "exp2.nml", "time.t_end=0.04 mesh.adaptive=.true. mesh.max_level=3 time.adaptive=.true. "
                                 "time.scheme='bdf2' time.error_tol=1e-4 output.snapshot_dt=0.01 @restart am_bdf2"),
    ("am_euler", "exp1.nml", "time.t_end=0.3 mesh.adaptive=.true. mesh.max_level=2 mesh.n_elements=100 "
                             "time.dt=1e-3 output.snapshot_every=50"),
    ("impact_mid", "impact.nml", "mesh.n_elements=200 time.t_end=0.3"),
    ("impact_mid_half", "impact.nml", "mesh.n_elements=200 time.t_end=0.15 output.checkpoint_every=100"),
    ("impact_mid_rest", "impact.nml", "mesh.n_elements=200 time.t_end=0.3 @restart impact_mid_half"),
    ("impact_mid_sig", "impact.nml", "mesh.n_elements=200 time.t_end=0.3 contact.law='signorini'"),
    ("impact_bdf2_sig", "impact.nml", "mesh.n_elements=200 time.t_end=0.3 time.scheme='bdf2' contact.law='signorini'"),
]


@dataclass
class Mutant:
    name: str
    path: str
    what: str
    original: list = field(default_factory=list)
    replacement: list = field(default_factory=list)


def read_mutants(path):
    mutants = []
    with open(path) as f:
        for number, line in enumerate(f, 1):
            line = line.rstrip("\n")
            if line.startswith("== "):
                parts = [p.strip() for p in line[3:].split("|", 2)]
                if len(parts) != 3:
                    sys.exit(f"{path}:{number}: expected '== id | file | description'")
                mutants.append(Mutant(*parts))
            elif line.startswith("- ") or line.startswith("+ ") or line in ("-", "+"):
                if not mutants:
                    sys.exit(f"{path}:{number}: a '{line[0]}' line before the first '=='")
                (mutants[-1].original if line[0] == "-" else mutants[-1].replacement).append(line[2:])
            elif line.strip() and not line.startswith("#"):
                sys.exit(f"{path}:{number}: not a mutant line: {line}")
    for m in mutants:
        if not m.original:
            sys.exit(f"{path}: mutant {m.name} has no original text")
    names = [m.name for m in mutants]
    if len(set(names)) != len(names):
        sys.exit(f"{path}: mutant names repeat")
    return mutants


def mutated_text(text, mutant):
    """The file's text with the mutant applied, or None with the number of matches."""
    words = " ".join(mutant.original).split()
    pattern = re.compile(r"\s+".join(re.escape(w) for w in words))
    matches = list(pattern.finditer(text))
    if len(matches) != 1:
        return None, len(matches)
    start, end = matches[0].span()
    indent = re.match(r"[ \t]*", text[text.rfind("\n", 0, start) + 1:]).group(0)
    replacement = ("\n" + indent).join(mutant.replacement)
    return text[:start] + replacement + text[end:], 1


def copy_tree(repo, dest):
    files = subprocess.run(["git", "-C", repo, "ls-files", "-z", "--cached", "--others", "--exclude-standard"],
                           check=True, capture_output=True).stdout.decode().split("\0")
    for rel in filter(None, files):
        src = os.path.join(repo, rel)
        if not os.path.isfile(src):
            continue          # deleted in the work tree
        os.makedirs(os.path.dirname(os.path.join(dest, rel)), exist_ok=True)
        shutil.copy2(src, os.path.join(dest, rel))


def build(tree, log):
    with open(log, "w") as out:
        return subprocess.run(["cmake", "--build", os.path.join(tree, "build"), "-j2"], stdout=out,
                              stderr=subprocess.STDOUT).returncode == 0


def test_order(tree, build_dir):
    listed = subprocess.run(["ctest", "--test-dir", build_dir, "-N"], check=True, capture_output=True,
                            text=True).stdout
    available = re.findall(r"Test\s+#\d+: (\S+)", listed)
    order = []
    order_file = os.path.join(tree, "tests", "mutation", "order.txt")
    if os.path.exists(order_file):
        with open(order_file) as f:
            order = [w for line in f for w in line.split("#")[0].split()]
    order = [t for t in order if t in available] + [t for t in available if t not in order]
    return [t for t in order if t not in EXCLUDED_TESTS]


def run_tests(build_dir, tests, limits, log_dir, stop_at_first=True):
    """Run tests two at a time in the given order; returns (failed test or None, times)."""
    pending, running, times, failed = list(tests), {}, {}, []
    while (pending or running) and not (failed and stop_at_first):
        while pending and len(running) < 2:
            name = pending.pop(0)
            log = open(os.path.join(log_dir, name + ".log"), "w")
            proc = subprocess.Popen(["ctest", "--test-dir", build_dir, "-R", f"^{name}$", "--output-on-failure",
                                     "--timeout", str(int(limits.get(name, 300)))],
                                    stdout=log, stderr=subprocess.STDOUT, start_new_session=True)
            running[name] = (proc, time.time(), log)
        time.sleep(0.2)
        for name, (proc, start, log) in list(running.items()):
            if proc.poll() is None:
                continue
            log.close()
            times[name] = time.time() - start
            del running[name]
            with open(os.path.join(log_dir, name + ".log")) as f:
                text = f.read()
            if proc.returncode != 0 or "0 tests failed" not in text:
                failed.append(name + (" (timeout)" if "Timeout" in text else ""))
    for name, (proc, start, log) in running.items():    # stop the other test of the pair
        try:
            os.killpg(proc.pid, 9)
        except ProcessLookupError:
            pass
        proc.wait()
        log.close()
    return (failed[0] if failed else None), times, failed


def equivalence_runs(exe, tree, out_dir):
    """Run EQUIVALENCE_CASES with exe into out_dir; returns {case: exit status}."""
    os.makedirs(out_dir, exist_ok=True)
    status = {}
    for name, inp, sets in EQUIVALENCE_CASES:
        args = [exe, os.path.join(tree, "input", inp)]
        words = sets.split()
        for k, w in enumerate(words):
            if w == "@restart":
                args += ["--set", f"time.restart_from='{os.path.join(out_dir, words[k + 1])}.h5'"]
            elif k == 0 or words[k - 1] != "@restart":
                args += ["--set", w]
        args += ["--set", "output.quiet=.true.", "--set", f"output.prefix='{os.path.join(out_dir, name)}'"]
        with open(os.path.join(out_dir, name + ".log"), "w") as log:
            try:
                status[name] = subprocess.run(args, stdout=log, stderr=subprocess.STDOUT, timeout=300).returncode
            except subprocess.TimeoutExpired:
                status[name] = "timeout"
    return status


def outputs_differ(base_dir, base_status, mutant_dir, mutant_status):
    """The cases whose exit status or file differs (regression.same), quietly."""
    differ = []
    for name, _, _ in EQUIVALENCE_CASES:
        if base_status[name] != mutant_status[name]:
            differ.append(f"{name} (exit {base_status[name]} vs {mutant_status[name]})")
            continue
        a, b = os.path.join(base_dir, name + ".h5"), os.path.join(mutant_dir, name + ".h5")
        if not os.path.exists(a) and not os.path.exists(b):
            continue
        if not (os.path.exists(a) and os.path.exists(b)):
            differ.append(f"{name} (file in one run only)")
            continue
        with open(os.devnull, "w") as quiet:
            saved, sys.stdout = sys.stdout, quiet
            try:
                same = regression.same(a, b) == 0
            finally:
                sys.stdout = saved
        if not same:
            differ.append(name)
    return differ


def write_doc(doc, table, summary, minutes, command, commit):
    """Put the section DOC_HEADING (the last of doc) with the table into doc."""
    section = DOC_HEADING + "\n" + DOC_TEXT.format(minutes=minutes, date=time.strftime("%Y-%m-%d"),
                                                  commit=commit, command=command) + \
        "\n" + "\n".join(table) + "\n\n" + summary + "\n"
    with open(doc, encoding="utf-8") as f:
        text = f.read()
    at = text.find(DOC_HEADING + "\n")
    if at >= 0:
        following = text.find("\n## ", at + len(DOC_HEADING))
        text = text[:at] + section + ("\n" + text[following + 1:] if following >= 0 else "")
    else:
        text = text.rstrip("\n") + "\n\n" + section
    with open(doc + ".tmp", "w", encoding="utf-8") as f:
        f.write(text)
    os.replace(doc + ".tmp", doc)


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("repo")
    parser.add_argument("--mutants", help="the list of mutants (default: tests/mutation/mutants.txt of REPO)")
    parser.add_argument("--only", help="comma-separated mutant ids")
    parser.add_argument("--keep", action="store_true", help="keep the scratch directory")
    parser.add_argument("--no-baseline", action="store_true", help="do not run the suite on the unmutated copy")
    parser.add_argument("--timeout", type=float, default=300.0, help="per-test limit without a baseline time")
    parser.add_argument("--list", action="store_true", help="only check which mutants apply")
    parser.add_argument("--doc", help="markdown file whose section '" + DOC_HEADING + "' gets the result")
    args = parser.parse_args()
    repo = os.path.abspath(args.repo)
    mutants = read_mutants(args.mutants or os.path.join(repo, "tests", "mutation", "mutants.txt"))
    if args.only:
        wanted = set(args.only.split(","))
        unknown = wanted - {m.name for m in mutants}
        if unknown:
            print(f"unknown mutant(s): {', '.join(sorted(unknown))}", file=sys.stderr)
            return 2
        mutants = [m for m in mutants if m.name in wanted]
    if args.list:
        for m in mutants:
            with open(os.path.join(repo, m.path)) as f:
                _, n = mutated_text(f.read(), m)
            print(f"{m.name:26s} {'applies' if n == 1 else f'did not apply ({n} matches)'}  {m.path}")
        return 0

    started = time.time()
    scratch = tempfile.mkdtemp(prefix="rodcontact-mutation.")
    tree, build_dir = os.path.join(scratch, "tree"), os.path.join(scratch, "tree", "build")
    logs = os.path.join(scratch, "logs")
    os.makedirs(logs)
    print(f"scratch copy: {tree}", flush=True)
    copy_tree(repo, tree)
    if subprocess.run(["cmake", "-S", tree, "-B", build_dir, "-DCMAKE_BUILD_TYPE=Release"],
                      stdout=subprocess.DEVNULL, stderr=subprocess.STDOUT).returncode != 0 or \
            not build(tree, os.path.join(logs, "build-baseline.log")):
        print(f"the unmutated copy does not build (see {logs})", file=sys.stderr)
        return 2
    base_exe = os.path.join(scratch, "rodcontact-baseline")
    shutil.copy2(os.path.join(build_dir, "rodcontact"), base_exe)
    tests = test_order(tree, build_dir)
    limits = {t: args.timeout for t in tests}
    if not args.no_baseline:
        t0 = time.time()
        _, times, failed = run_tests(build_dir, tests, limits, logs, stop_at_first=False)
        for name in failed:
            print(f"baseline: {name} fails on the unmutated copy: left out", flush=True)
        failed_names = {f.split()[0] for f in failed}
        tests = sorted((t for t in tests if t not in failed_names), key=lambda t: times.get(t, 1e9))
        limits = {t: max(MIN_TIMEOUT, TIMEOUT_FACTOR * times[t]) for t in tests}
        print(f"baseline: {len(tests)} tests pass, {time.time() - t0:.0f} s; order: {' '.join(tests)}", flush=True)
    base_dir = os.path.join(scratch, "equivalence", "baseline")
    base_status = None

    results = []
    for m in mutants:
        t0 = time.time()
        target = os.path.join(tree, m.path)
        if not os.path.exists(target):
            results.append((m, "did not apply", "no such file", 0.0))
            print(f"{m.name:26s} did not apply (no file {m.path})", flush=True)
            continue
        with open(target) as f:
            original = f.read()
        text, n = mutated_text(original, m)
        if text is None:
            results.append((m, "did not apply", f"{n} matches", 0.0))
            print(f"{m.name:26s} did not apply ({n} matches of the original text)", flush=True)
            continue
        try:
            with open(target, "w") as f:
                f.write(text)
            if not build(tree, os.path.join(logs, f"build-{m.name}.log")):
                verdict, by = "did not build", ""
            else:
                mlogs = os.path.join(logs, m.name)
                os.makedirs(mlogs)
                killer, _, _ = run_tests(build_dir, tests, limits, mlogs)
                if killer:
                    verdict, by = "KILLED", killer
                else:
                    if base_status is None:
                        base_status = equivalence_runs(base_exe, tree, base_dir)
                    mdir = os.path.join(scratch, "equivalence", m.name)
                    differ = outputs_differ(base_dir, base_status, mdir,
                                            equivalence_runs(os.path.join(build_dir, "rodcontact"), tree, mdir))
                    verdict, by = ("SURVIVED", "outputs differ: " + ", ".join(differ)) if differ else \
                        ("equivalent", "no output of the fixed runs changes")
        finally:
            with open(target, "w") as f:
                f.write(original)
        results.append((m, verdict, by, time.time() - t0))
        print(f"{m.name:26s} {verdict:13s} {by}  ({time.time() - t0:.0f} s)", flush=True)

    counted = [r for r in results if r[1] in ("KILLED", "SURVIVED")]
    killed = [r for r in counted if r[1] == "KILLED"]
    table = ["| mutant | file | change | result | by |", "|---|---|---|---|---|"]
    table += [f"| {m.name} | {m.path.replace('src/', '')} | {m.what} | {verdict} | {by} |"
              for m, verdict, by, _ in results]
    summary = (f"{len(killed)} of {len(counted)} counted mutants killed; "
               f"{sum(r[1] == 'equivalent' for r in results)} equivalent, "
               f"{sum(r[1] == 'did not apply' for r in results)} did not apply, "
               f"{sum(r[1] == 'did not build' for r in results)} did not build; "
               f"total {time.time() - started:.0f} s wall")
    print("\n" + "\n".join(table) + "\n\n" + summary)
    if args.doc:
        commit = subprocess.run(["git", "-C", repo, "describe", "--always", "--dirty"], capture_output=True,
                                text=True).stdout.strip() or "unknown"
        command = "tests/mutation/run.sh " + " ".join(a for a in sys.argv[2:])
        write_doc(args.doc, table, summary, round((time.time() - started) / 60), command.strip(), commit)
    if args.keep:
        print(f"scratch kept: {scratch}")
    else:
        shutil.rmtree(scratch, ignore_errors=True)
    return 0 if len(killed) == len(counted) else 1


if __name__ == "__main__":
    sys.exit(main())
