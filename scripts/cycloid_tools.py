"""What the Python of tests/, benchmarks/ and scripts/ shares: reading CSV
files and a run's parameters, running the executable under mpirun, power
fits and Richardson extrapolation.

Parameter values are read by deal.II, not here: parameter_values() takes
a run's `parameters.json` or asks the executable (`--print-parameters=json
FILE`). walk_prm() and read_prm() only look at the lines of a prm text,
for a script that edits one (benchmarks/transient/run.py) or checks what a
written file holds (tests/check_parameters_file.py).

Plain Python 3; numpy is imported only by fit_power(), so that a script
without numpy can import this module. Tests and benchmarks put this folder
on sys.path relative to their own file:

    sys.path.insert(0, str(Path(__file__).resolve().parents[N] / "scripts"))
"""
import csv
import json
import math
import os
import signal
import subprocess
import tempfile
import time


# --- CSV files -----------------------------------------------------------

def read_csv(source, numbers=(), missing_ok=False):
    """The rows of a CSV text with one header line, as a list of dicts
    {column: value} in the text's order (csv.DictReader's rows).

    @p source is a file's path, or the lines of a CSV text (a program's
    output, say). @p numbers are the types tried in turn on every value:
    the first that takes the text converts it, a text that none takes (an
    empty one, a name) stays a string. () keeps every value as text;
    (float,) gives floats wherever the text is a number (nan and inf
    included); (int, float) gives ints for integer texts and floats for the
    other numbers. A missing file raises FileNotFoundError, or gives [] if
    @p missing_ok."""
    if isinstance(source, (str, os.PathLike)):
        if missing_ok and not os.path.exists(source):
            return []
        with open(source, newline="") as f:
            rows = list(csv.DictReader(f))
    else:
        rows = list(csv.DictReader(source))
    if not numbers:
        return rows
    return [{k: _number(v, numbers) for k, v in r.items()} for r in rows]


def _number(text, types):
    for t in types:
        try:
            return t(text)
        except (TypeError, ValueError):
            pass
    return text


# --- prm files -----------------------------------------------------------

def walk_prm(lines):
    """Walk the lines of a ParameterHandler text (a file object, a list of
    lines): yield (line, sections, name, value) for every line, in order.
    @p sections is the tuple of the subsections open at the line,
    outermost first; @p name and @p value are those of a `set name =
    value` entry, stripped, with the comment (from `#` on) removed, or
    None for any other line. `subsection X` opens X and `end` closes the
    innermost open subsection."""
    sections = []
    for line in lines:
        words = line.split("#")[0].strip().split(None, 1)
        name = value = None
        if words[:1] == ["subsection"] and len(words) == 2:
            sections.append(words[1].strip())
        elif words == ["end"] and sections:
            sections.pop()
        elif words[:1] == ["set"] and len(words) == 2 and "=" in words[1]:
            name, value = (s.strip() for s in words[1].split("=", 1))
        yield line, tuple(sections), name, value


def _prm_lines(source):
    if isinstance(source, (str, os.PathLike)):
        with open(source) as f:
            return f.readlines()
    return source


def read_prm(source):
    """The `set` lines of a ParameterHandler text (not the values a run
    uses: parameter_values()) as {"Sub/Sub/Name":
    value} (a top-level entry: {"Name": value}); of an entry set twice,
    the last value. @p source is a file's path (a missing file raises
    FileNotFoundError) or the lines of a text (e.g. the output of
    `cycloid-contact --print-parameters`)."""
    return {"/".join(sections + (name,)): value
            for _, sections, name, value in walk_prm(_prm_lines(source)) if name is not None}


def parameter_values(source, exe=None):
    """The value of every declared entry as deal.II read it, as
    {"Sub/Sub/Name": value} (a top-level entry: {"Name": value}), values
    as text. @p source is a run's `parameters.json` (every run writes it
    beside `parameters.prm`), the output directory holding it, or, with
    @p exe, a parameter file: then `exe --print-parameters=json FILE`
    reads it (deal.II's parser: includes, continuation lines, defaults
    for what the file leaves out; a bad file raises RunError)."""
    if exe is not None:
        text = run_cycloid(None, exe, "--print-parameters=json", str(source), check=True).stdout
        tree = json.loads(text)
    else:
        path = os.path.join(source, "parameters.json") if os.path.isdir(source) else source
        with open(path) as f:
            tree = json.load(f)
    values = {}

    def walk(node, prefix):
        for name, child in node.items():
            if isinstance(child, dict) and isinstance(child.get("value"), str):
                values[prefix + name] = child["value"]
            elif isinstance(child, dict):
                walk(child, prefix + name + "/")

    walk(tree, "")
    return values


def parameter_getter(values, auto=None):
    """get(section, name[, default]) over parameter_values() @p values,
    keyed by the innermost subsection's name ("" at the top level):
    get("Mesh", "Contact refinements") is the value as text. An entry read
    as `auto` (a size the program derives) gives what the caller resolves
    it to: @p auto {(section, name): value}, else get()'s default, else
    "auto". An entry that is not declared raises KeyError unless get() is
    given a default."""
    by_section = {}
    for key, value in values.items():
        parts = key.split("/")
        by_section[(parts[-2] if len(parts) > 1 else "", parts[-1])] = value
    resolved = dict(auto or {})

    def get(section, name, *default):
        value = by_section.get((section, name))
        if value is None:
            if default:
                return default[0]
            raise KeyError((section, name))
        if value == "auto":
            return resolved.get((section, name), default[0] if default else value)
        return value

    return get


# --- running the executable ----------------------------------------------

def mpirun_command(ranks, exe, *args, oversubscribe=None, export=()):
    """The command line that runs @p exe with @p args on @p ranks MPI
    ranks: ["mpirun", flags..., "-np", ranks, exe, args...], every item a
    string. The flags: --allow-run-as-root when the user is root (uid 0);
    --oversubscribe when @p ranks exceeds os.cpu_count() (oversubscribe
    None), always (True) or never (False); "-x NAME" for each name in
    @p export (an environment variable passed on to every rank). @p ranks
    None: [exe, args...], the executable alone, without mpirun."""
    command = [str(exe)] + [str(a) for a in args]
    if ranks is None:
        return command
    flags = ["--allow-run-as-root"] if os.getuid() == 0 else []
    if oversubscribe or (oversubscribe is None and ranks > (os.cpu_count() or 1)):
        flags.append("--oversubscribe")
    for name in export:
        flags += ["-x", name]
    return ["mpirun"] + flags + ["-np", str(ranks)] + command


class RunError(subprocess.CalledProcessError):
    """A run that run_cycloid(check=True) saw fail: a CalledProcessError
    whose message ends with the last lines the run printed."""

    def __str__(self):
        text = (self.stdout or "") + (self.stderr or "")
        return super().__str__() + ("\n" + text[-2000:] if text else "")


class CycloidRun(subprocess.CompletedProcess):
    """What run_cycloid() returns: a subprocess.CompletedProcess (args:
    the command line; returncode; stdout and stderr as text) with
    @p wall_s, the whole command's wall time [s] (time.monotonic; with
    peak_memory GNU time's, to 0.01 s), @p peak_rss_MB, the largest peak
    resident memory of any one process of the run [MB] (with peak_memory,
    else None), and @p timed_out, whether the run was stopped at its
    timeout (returncode is then the signal's, negative)."""

    def __init__(self, args, returncode, stdout, stderr, wall_s, timed_out, peak_rss_MB=None):
        super().__init__(args, returncode, stdout, stderr)
        self.wall_s = wall_s
        self.timed_out = timed_out
        self.peak_rss_MB = peak_rss_MB


def run_cycloid(ranks, exe, *args, log=None, cwd=None, env=None, timeout=None, check=False,
                peak_memory=False, oversubscribe=None, export=()):
    """Run mpirun_command(@p ranks, @p exe, *@p args) (@p ranks None: the
    executable alone) and wait for it; return a CycloidRun.

    Output: captured as text (undecodable bytes replaced) into
    stdout and stderr; with @p log (a path), both go to that file instead,
    interleaved as on a console, and stdout is the file's text afterwards
    (stderr "").
    @p cwd: the working directory. @p env: {name: value} on top of
    os.environ (a value None removes the name).
    @p timeout [s]: the run starts in a session of its own and, at the
    timeout, its whole process group (mpirun and the ranks) gets SIGTERM,
    and SIGKILL 30 s later if it is still there.
    @p peak_memory: the command runs under GNU time (/usr/bin/time, which
    writes into a file of its own), for peak_rss_MB (the largest process,
    mpirun or a rank: GNU time's %M) and wall_s (its %e).
    @p check: a failed run raises RunError (a CalledProcessError), a
    timed-out one subprocess.TimeoutExpired.
    @p oversubscribe, @p export: as for mpirun_command()."""
    command = mpirun_command(ranks, exe, *args, oversubscribe=oversubscribe, export=export)
    environment = None
    if env is not None:
        environment = dict(os.environ)
        for name, value in env.items():
            if value is None:
                environment.pop(name, None)
            else:
                environment[name] = str(value)
    timing = None
    if peak_memory:
        fd, timing = tempfile.mkstemp(prefix="cycloid-time-")
        os.close(fd)
        command = ["/usr/bin/time", "-f", "%e %M", "-o", timing] + command
    sink = open(log, "w") if log else None
    timed_out = False
    try:
        start = time.monotonic()
        p = subprocess.Popen(command, cwd=cwd, env=environment, text=True, errors="replace",
                             stdout=sink or subprocess.PIPE,
                             stderr=subprocess.STDOUT if sink else subprocess.PIPE,
                             start_new_session=timeout is not None)
        try:
            out, err = p.communicate(timeout=timeout)
        except subprocess.TimeoutExpired:
            timed_out = True
            os.killpg(p.pid, signal.SIGTERM)  # this run's process group only
            try:
                out, err = p.communicate(timeout=30)
            except subprocess.TimeoutExpired:
                os.killpg(p.pid, signal.SIGKILL)
                out, err = p.communicate()
        wall = time.monotonic() - start
        figures = []
        if timing:
            with open(timing) as f:
                figures = f.read().split()  # after "Command exited with ..." if it failed
    finally:
        if sink:
            sink.close()
        if timing:
            os.remove(timing)
    if sink:
        with open(log, errors="replace") as f:
            out, err = f.read(), ""
    peak = None
    if len(figures) >= 2:
        wall, peak = float(figures[-2]), int(figures[-1]) / 1024.
    result = CycloidRun(command, p.returncode, out, err, wall, timed_out, peak)
    if check and timed_out:
        raise subprocess.TimeoutExpired(command, timeout, out, err)
    if check and p.returncode != 0:
        raise RunError(p.returncode, command, out, err)
    return result


# --- fits ----------------------------------------------------------------

def fit_power(x, y):
    """Least-squares fit of y = c x^p on log-log axes (numpy.polyfit of
    log y against log x, degree 1); returns (c, p), the coefficient first.
    Every x and y must be positive, and there must be two distinct x
    (ValueError otherwise)."""
    import numpy as np
    lx, ly = np.log(np.asarray(x, dtype=float)), np.log(np.asarray(y, dtype=float))
    if len(lx) != len(ly) or len(lx) < 2 or np.ptp(lx) == 0:
        raise ValueError("fit_power needs as many y as x and two distinct x")
    p, log_c = np.polyfit(lx, ly, 1)
    return float(np.exp(log_c)), float(p)


def richardson(coarse, mid, fine, ratio=2.0):
    """Richardson extrapolation of a quantity from its values on three
    nested meshes, @p coarse to @p fine, each @p ratio times finer than the
    one before (ratio 2: the cell size halves). With the differences
    d1 = mid - coarse and d2 = fine - mid, the observed order is
    p = log(|d1| / |d2|) / log(ratio) and the extrapolated value
    fine + d2 / (ratio^p - 1). Returns (extrapolated value, p), or
    (None, None) when the differences do not shrink monotonically (a zero
    difference, a change of sign, or |d2| >= |d1|: not asymptotic)."""
    d1, d2 = mid - coarse, fine - mid
    if d1 == 0 or d2 == 0 or d1 * d2 < 0 or abs(d2) >= abs(d1):
        return None, None
    p = math.log(abs(d1) / abs(d2)) / math.log(ratio)
    return fine + d2 / (ratio ** p - 1.0), p
