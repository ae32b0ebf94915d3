#!/usr/bin/env python3
"""Measures the Cortex-M figures and writes docs/firmware.md (and firmware/bench-m4f.csv).

Usage: python3 firmware/figures.py [--out PATH]      (default PATH: docs/firmware.md)

Needs: the thumbv7em-none-eabihf target, qemu-system-arm, defmt-print, and rustup's llvm-tools (llvm-size;
Debian's llvm-size or GNU size also work). What it does, every number coming from a run or a build here:
1. builds and runs `bench` on the emulated Cortex-M4F (mps2-an386, `-icount shift=10`): executed instructions
   per step for every input model x scheme x stabilizer x accumulator of the bench grid, and the README quick
   start's instructions per sample; the counts also go to firmware/bench-m4f.csv (read by the lab); then
   `burst` the same way: FIFO bursts (`push_burst` over bursts of 1, 8, 32 samples against one `push` per
   sample, and the quick start fed FIFO reads of 1, 8, 32);
2. builds `minimal` once per scheme (one scheme + History + FirstOrder, no defmt) and reads the section sizes;
3. builds and runs `stack` on the M4F: the painted stack depth of a push for every configuration, and of the
   estimator's calls (`Step::between`, `Ud::predict`, `Ud::update`);
4. builds `bench` for the cores without an FPU (thumbv7m: Cortex-M3 on mps2-an385; thumbv6m: Cortex-M0 on
   the microbit; f32 in software) and runs it there: the recommended configuration, ExpMap + Hold and the
   quick start. The microbit's SysTick clock (16 MHz) is cross-checked by running its image on mps2-an385
   too (25 MHz): the counts must agree.
5. the estimator's predict step on the M4F: builds and runs `predict` (-icount as `bench`): the recommended
   push alone and with the covariance (`Step::between` + `Ud::<f32, 6>::predict`) every step and every 10th,
   and each call alone; builds `minimal` with the features `estimator-predict` and `estimator` for its flash
   (against ExpMap + History) and names the largest functions it adds (llvm-nm).
6. the front end's in-motion estimators on the M4F: `predict` also counts `frontend::CalibrationEstimator`
   (`correct` + `update`) and `frontend::MotionBias` per sample at 1 kHz past their start-up, `stack` paints
   one sample of each, and `minimal` is built with the feature `calibration-estimator` for its flash.
Also needs the thumbv7m-none-eabi and thumbv6m-none-eabi targets.
"""
import argparse
import os
import re
import shutil
import subprocess
import sys
import tempfile

FW = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(FW)
TARGET = "thumbv7em-none-eabihf"
SCHEMES = ["ExpMap", "Magnus4", "Cf4", "Rk4"]
INPUTS = ["hold", "linear", "history", "twice-rate", "gauss-points", "delta-angles-2"]
INPUT_TYPES = {
    "hold": "Hold",
    "linear": "Linear",
    "history": "History",
    "twice-rate": "TwiceRate",
    "gauss-points": "GaussPoints",
    "delta-angles-2": "DeltaAngles(TwoSample)",
}
# (scheme, input model, cargo features) of the flash table; the first row is the baseline (no quatprop).
MINIMAL = [("none (baseline)", "", "baseline"),
           ("Euler", "History", "scheme-euler"), ("Rk2", "History", "scheme-rk2"),
           ("Rk3", "History", "scheme-rk3"), ("Rk4", "History", None), ("Rk5", "History", "scheme-rk5"),
           ("ExpMap", "History", "scheme-expmap"), ("Magnus4", "History", "scheme-magnus4"),
           ("Cf4", "History", "scheme-cf4"),
           ("ExpMap", "Hold", "scheme-expmap,input-hold"), ("ExpMap", "Linear", "scheme-expmap,input-linear"),
           ("Rk4", "Hold", "input-hold"), ("Rk4", "Linear", "input-linear")]
# The estimator's flash: `minimal` (ExpMap + History) with these features, against the same without.
ESTIMATOR_FLASH = [("the predict step every 10th step (`Step::between` + `Ud::predict`)",
                    "scheme-expmap,estimator-predict"),
                   ("... and one scalar `Ud::update` + a correction (`rotate_body` + `correct_bias`)",
                    "scheme-expmap,estimator")]
# The front end's in-motion estimators: `minimal` (ExpMap + History) with these features, against the same
# without (built with the estimator's rows: one baseline build).
FRONT_END_FLASH = [("`CalibrationEstimator::<f32>` (`new`, `correct` before each push, `update` after it)",
                    "scheme-expmap,calibration-estimator")]
# The front end's rows of the `predict` program, in order, with their labels.
FRONT_END_ROWS = [("CalibrationEstimator::correct+update", "`CalibrationEstimator::<f32>`: `correct` of the "
                   "reading, then `update` (12 states: bias and gain)"),
                  ("MotionBias::bias+update", "`MotionBias::<f32>`: the bias subtracted, then `update` "
                   "(3 states: bias), for comparison")]
# The estimator bench's rows, in order, with their labels.
ESTIMATOR_ROWS = [("push", "the recommended push alone (in this program's loop)"),
                  ("push+covariance-every-step", "push + covariance every step (`Step::between` over the step + "
                   "`matrices` + `Ud::predict`)"),
                  ("push+covariance-every-10th", "push + covariance every 10th step (amortized per attitude step)"),
                  ("Step::between", "`Step::between` alone (two attitudes 10 ms apart)"),
                  ("Ud::predict", "`Ud::<f32, 6>::predict` alone"),
                  ("Ud::predict_compensated", "`Ud::<f32, 6>::predict_compensated` alone (`D` carried to twice "
                   "the precision)"),
                  ("Ud::update", "one scalar `Ud::update` (an inclination row)"),
                  ("rotate_body+correct_bias", "a correction: `rotate_body` + `correct_bias`")]
# The Cortex-M4F clock the estimator's times are given at (STM32F4).
M4F_HZ = 168_000_000
# The flash target for ExpMap + History + FirstOrder: library code (bytes).
LIBRARY_TARGET = 2560
# The cores without an FPU: (triple, board, core, a typical clock of such parts (Hz), examples).
SOFT_FLOAT = [("thumbv7m-none-eabi", "mps2-an385", "Cortex-M3", 72_000_000, "STM32F103, EFM32"),
              ("thumbv6m-none-eabi", "microbit", "Cortex-M0", 48_000_000, "RP2040 (M0+), STM32G0/L0, nRF51")]
# The bench's fixed-point row (fixed::Q30Propagator), on every core.
FIXED = ("fixed", "Q30", "FirstOrder", "integer")
# The soft-float bench's rows: (input, scheme, stabilizer, accumulator).
SOFT_ROWS = [("history", "ExpMap", "FirstOrder", "Plain"), ("hold", "ExpMap", "FirstOrder", "Plain"),
             ("hold", "ExpMap", "Normalize", "Plain")]


def log(msg):
    print(msg, file=sys.stderr, flush=True)


def run(cmd, cwd=FW):
    r = subprocess.run(cmd, cwd=cwd, capture_output=True, text=True)
    if r.returncode != 0:
        sys.stderr.write(r.stdout + r.stderr)
        raise SystemExit(f"{' '.join(cmd)} failed ({r.returncode})")
    return r.stdout


def host_triple():
    out = run(["rustc", "-vV"])
    m = re.search(r"^host: (\S+)$", out, re.M)
    if not m:
        raise SystemExit("rustc -vV names no host triple")
    return m.group(1)


def size_tool():
    sysroot = run(["rustc", "--print", "sysroot"]).strip()
    tool = os.path.join(sysroot, "lib", "rustlib", host_triple(), "bin", "llvm-size")
    if os.path.exists(tool):
        return tool
    for t in ("llvm-size", "size"):
        if shutil.which(t):
            return t
    raise SystemExit("no llvm-size: rustup component add llvm-tools")


def cargo(*args, target=TARGET):
    """cargo in firmware/ (its .cargo/config.toml: runner, DEFMT_LOG)."""
    return run(["cargo", *args, "--release", "--target", target])


def elf(name, target=TARGET):
    # cargo runs in firmware/, so a relative CARGO_TARGET_DIR is relative to it.
    target_dir = os.path.join(FW, os.environ.get("CARGO_TARGET_DIR") or "target")
    return os.path.join(target_dir, target, "release", name)


# ---------------------------------------------------------------- 1. bench
def build_programs():
    """bench, burst and stack in one cargo command: their fat-LTO links run in parallel."""
    log("building bench, burst, predict and stack ...")
    cargo("build", "-q", "--bin", "bench", "--bin", "burst", "--bin", "predict", "--bin", "stack")


def start(name, target=TARGET, machine=None):
    """Starts a built program on its triple's board (mps2-an386 for the M4F) through qemu-run (the cargo
    runner), or on `machine`, its output into a file (a full pipe would stall the emulator); `finish` waits
    for it and reads the file."""
    out = tempfile.TemporaryFile(mode="w+")
    env = dict(os.environ)
    if machine:
        env["QEMU_MACHINE"] = machine
    return subprocess.Popen(["./qemu-run", elf(name, target)], cwd=FW, stdout=out, stderr=subprocess.STDOUT,
                            text=True, env=env), out


def finish(started, name):
    proc, out = started
    proc.wait()
    out.seek(0)
    text = out.read()
    if proc.returncode != 0:
        sys.stderr.write(text)
        raise SystemExit(f"{name} failed ({proc.returncode})")
    return text


def run_bench(out, expected=len(INPUTS) * len(SCHEMES) * 2 * 3):
    rows = {}
    quick = None
    for line in out.splitlines():
        m = re.match(r"bench (\S+) (\S+) (\S+) (Plain|Kahan|FloatFloat) ([\d.]+)$", line)
        if m:
            rows[m.group(1, 2, 3, 4)] = float(m.group(5))
        f = re.match(r"bench fixed Q30Propagator ([\d.]+)$", line)
        if f:
            rows[FIXED] = float(f.group(1))
        q = re.match(r"bench quickstart on_fifo per-sample ([\d.]+) \(samples=(\d+), fixed=(\d+)\)", line)
        if q:
            quick = (float(q.group(1)), int(q.group(2)), int(q.group(3)))
    if "bench done" not in out or quick is None:
        raise SystemExit("bench did not finish:\n" + out)
    if FIXED not in rows:
        raise SystemExit("bench printed no fixed-point row:\n" + out)
    if len(rows) != expected + 1:
        raise SystemExit(f"bench printed {len(rows)} rows, expected {expected}")
    return rows, quick


def run_burst(out):
    burst = {}
    for line in out.splitlines():
        b = re.match(r"bench burst (\S+) len=(\d+) ([\d.]+) identical=(true|false)$", line)
        if b:
            if b.group(4) != "true":
                raise SystemExit("burst: an attitude differs from the single pushes':\n" + line)
            burst[(b.group(1), int(b.group(2)))] = float(b.group(3))
        c = re.match(r"bench config (\S+) len=(\d+) static=([\d.]+) configured=([\d.]+) identical=(true|false)$",
                     line)
        if c:
            if c.group(5) != "true":
                raise SystemExit("burst: the run-time configuration's attitude differs from the static types':\n"
                                 + line)
            burst[("config", c.group(1))] = (float(c.group(3)), float(c.group(4)))
    if "bench burst done" not in out:
        raise SystemExit("burst did not finish:\n" + out)
    want = [("push-const-dt", 1), ("push-period", 1)] + [(w, n) for w in ("push_burst", "quickstart")
                                                          for n in (1, 8, 32)]
    want += [("config", "recommended"), ("config", "rk4-linear-normalize-kahan")]
    if sorted(burst) != sorted(want):
        raise SystemExit(f"burst printed rows {sorted(burst)}, expected {sorted(want)}")
    return burst


def write_bench_csv(rows):
    """firmware/bench-m4f.csv: precision (f32; f32-kahan, f32-floatfloat for those accumulators), scheme,
    stabilizer, input model, instructions per step (read by the lab's work-precision overlay)."""
    with open(os.path.join(FW, "bench-m4f.csv"), "w") as f:
        f.write("precision,scheme,stabilizer,input,instructions_per_step\n")
        grid = {k: v for k, v in rows.items() if k != FIXED}
        for (inp, scheme, stab, acc), v in sorted(grid.items(), key=lambda kv: (kv[0][3], kv[0][1], kv[0][2],
                                                                               INPUTS.index(kv[0][0]))):
            prec = {"Plain": "f32", "Kahan": "f32-kahan", "FloatFloat": "f32-floatfloat"}[acc]
            f.write(f"{prec},{scheme},{stab},{inp},{v}\n")


def run_rows(out, group, rows, what):
    """{key: figure} from `out`'s lines `bench <group> <key> <figure>`; exits (naming `what`) unless they are
    the keys of `rows` ((key, label)), each once, and `bench <group> done` follows."""
    figures = {}
    for line in out.splitlines():
        m = re.match(rf"bench {group} (\S+) ([\d.]+)$", line)
        if m:
            figures[m.group(1)] = float(m.group(2))
    if f"bench {group} done" not in out or sorted(figures) != sorted(k for k, _ in rows):
        raise SystemExit(f"{what} did not finish or printed other rows:\n" + out)
    return figures


# ---------------------------------------------------------------- 2. flash
def sizes(tool, path):
    out = run([tool, "-A", path])
    s = {}
    for line in out.splitlines():
        p = line.split()
        if len(p) >= 2 and p[0].startswith(".") and p[1].isdigit():
            s[p[0]] = int(p[1])
    text = s.get(".vector_table", 0) + s.get(".text", 0)
    return text, s.get(".rodata", 0), s.get(".data", 0), s.get(".bss", 0) + s.get(".uninit", 0)


def flash_table(tool):
    rows = []
    for scheme, inp, feat in MINIMAL:
        log(f"building minimal with {scheme} {inp} ...")
        args = ["build", "-q", "--no-default-features", "--bin", "minimal"]
        if feat:
            args += ["--features", feat]
        cargo(*args)
        rows.append((scheme, inp, sizes(tool, elf("minimal"))))
    return rows


def symbols(tool, path):
    """{function or object name: size} from llvm-nm (next to llvm-size)."""
    nm = os.path.join(os.path.dirname(tool), "llvm-nm") if os.path.dirname(tool) else "llvm-nm"
    if not shutil.which(nm) and not os.path.exists(nm):
        return {}
    out = run([nm, "-C", "-S", "--size-sort", path])
    s = {}
    for line in out.splitlines():
        p = line.split(None, 3)
        if len(p) == 4:
            s[p[3]] = s.get(p[3], 0) + int(p[1], 16)
    return s


def estimator_flash(tool, features):
    """[(label, sizes, the largest functions added against ExpMap + History)] of `minimal` with each of
    `features` ((label, cargo features)): the estimator's calls, the front end's."""
    cargo("build", "-q", "--no-default-features", "--bin", "minimal", "--features", "scheme-expmap")
    base = symbols(tool, elf("minimal"))
    rows = []
    for label, feat in features:
        log(f"building minimal with {feat} ...")
        cargo("build", "-q", "--no-default-features", "--bin", "minimal", "--features", feat)
        syms = symbols(tool, elf("minimal"))
        # A function whose size changed counts with its growth (the program's `main` inlines the calls).
        added = sorted(((n, v - base.get(n, 0)) for n, v in syms.items() if v > base.get(n, 0)),
                       key=lambda kv: -kv[1])
        rows.append((label, sizes(tool, elf("minimal")), added))
    return rows


# ---------------------------------------------------------------- 3. stack
def run_stack(out):
    per_row = {}
    worst = {}
    count = None
    for line in out.splitlines():
        m = re.match(r"stack (\S+) (\S+) small=(\d+) large=(\d+)$", line)
        if m:
            per_row[(m.group(1), m.group(2))] = (int(m.group(3)), int(m.group(4)))
        w = re.match(r"stack worst (small|large)-step (\d+) bytes \(bound (\d+)\) at (.*)$", line)
        if w:
            worst[w.group(1)] = (int(w.group(2)), int(w.group(3)), w.group(4))
        c = re.match(r"stack configurations=(\d+)$", line)
        if c:
            count = int(c.group(1))
        e = re.match(r"stack estimator between=(\d+) predict=(\d+) update=(\d+) \(bound (\d+)\)$", line)
        if e:
            worst["estimator"] = tuple(int(v) for v in e.groups())
        f = re.match(r"stack front-end calibration=(\d+) motion-bias=(\d+) size=(\d+)/(\d+) \(bound (\d+)\)$",
                     line)
        if f:
            worst["front-end"] = tuple(int(v) for v in f.groups())
    if count is None or len(worst) != 4:
        raise SystemExit("stack did not finish:\n" + out)
    return per_row, worst, count


# ---------------------------------------------------------------- 4. cores without an FPU
def build_soft():
    for target, *_ in SOFT_FLOAT:
        log(f"building bench for {target} ...")
        cargo("build", "-q", "--bin", "bench", target=target)


def run_soft(procs):
    """{core: (rows, quick)} from the soft-float benches; the microbit's clock checked on mps2-an385."""
    soft = {}
    for target, board, core, *_ in SOFT_FLOAT:
        soft[core] = run_bench(finish(procs[(target, board)], f"bench on {board}"), len(SOFT_ROWS))
    m0 = soft["Cortex-M0"][0]
    check, _ = run_bench(finish(procs[("thumbv6m-none-eabi", "mps2-an385")], "the M0 bench on mps2-an385"),
                         len(SOFT_ROWS))
    for key, v in m0.items():
        # The same image reads 25/16 as many instructions on the 25 MHz board if the microbit's SysTick
        # runs at 16 MHz.
        if abs(check[key] * 16 / 25 - v) > 0.005 * v:
            raise SystemExit(f"microbit SysTick: {key} {v} on the microbit, {check[key]} on mps2-an385")
    return soft


def soft_section(soft):
    o = ["## Cores without an FPU: Cortex-M3 and Cortex-M0\n"]
    o.append("The same `bench` program built for thumbv7m-none-eabi (Cortex-M3, QEMU `mps2-an385`) and "
             "thumbv6m-none-eabi (Cortex-M0, QEMU `microbit`), where f32 arithmetic is software "
             "(compiler-builtins' `__aeabi_fadd`, `__aeabi_fmul`, …): the recommended configuration, "
             "ExpMap + Hold (one exponential map per sample, the cheap peers' form) and the quick start, "
             "counted as above over 16 steps (32 samples for the quick start: a loop must fit one wrap of "
             "SysTick). Soft-float takes a data-dependent path, so the figures move by about 1 % with the "
             "samples. The microbit's SysTick counts QEMU's 16 MHz system clock; the script runs the M0 image "
             "on `mps2-an385` (25 MHz) too and checks that the counts agree.\n")
    cores = [c for _, _, c, *_ in SOFT_FLOAT]
    o.append("| configuration | " + " | ".join(f"{c} instructions per step" for c in cores) + " |")
    o.append("|---|" + "---:|" * len(cores))
    labels = {("history", "ExpMap", "FirstOrder", "Plain"): "ExpMap + History + FirstOrder (recommended)",
              ("hold", "ExpMap", "FirstOrder", "Plain"): "ExpMap + Hold + FirstOrder",
              ("hold", "ExpMap", "Normalize", "Plain"): "ExpMap + Hold + Normalize"}
    labels[FIXED] = "**`fixed::Q30Propagator`** (the recommended step in integers: raw counts, Q30 attitude)"
    for key in SOFT_ROWS + [FIXED]:
        o.append(f"| {labels[key]} | " + " | ".join(f"{soft[c][0][key]:.1f}" for c in cores) + " |")
    o.append("| the README's quick start, per sample | "
             + " | ".join(f"{soft[c][1][0]:.1f}" for c in cores) + " |")
    o.append("")
    o.append("What a 1 kHz update costs, at one cycle per instruction. That is a lower bound: on these cores "
             "a load takes 2 cycles and a taken branch 2 to 3, and flash wait states add more.\n")
    o.append("| core | clock | configuration | time per step (at least) | CPU share at 1 kHz (at least) |")
    o.append("|---|---:|---|---:|---:|")
    for _, _, core, hz, examples in SOFT_FLOAT:
        rows, quick = soft[core]
        for key in [SOFT_ROWS[0], FIXED, SOFT_ROWS[1]]:
            us = rows[key] / hz * 1e6
            o.append(f"| {core} ({examples}) | {hz / 1e6:.0f} MHz | {labels[key]} | {us:.0f} µs | "
                     f"{us / 10:.1f} % |")
    o.append("")
    rec, fixed = (soft["Cortex-M0"][0][k] for k in (SOFT_ROWS[0], FIXED))
    o.append(f"The fixed-point step is {rec / fixed:.1f} times cheaper than soft-float f32 on the Cortex-M0 and "
             f"{soft['Cortex-M3'][0][SOFT_ROWS[0]] / soft['Cortex-M3'][0][FIXED]:.1f} times on the Cortex-M3 "
             "(which multiplies 32 x 32 -> 64 bits in one instruction; the M0 has no such instruction and "
             "takes four 16 x 16-bit products). Its error against an f64 propagator fed the same samples is "
             "in `tests/fixed.rs` (the module's documentation, `src/fixed.rs`, says how each rounding is kept "
             "from adding up).\n")
    return "\n".join(o)


# ---------------------------------------------------------------- document
def m4f_time_table(first_column, rows, figures):
    """A table of `figures` (instructions, by key) with their time at M4F_HZ and CPU share at 1 kHz: a line
    per (key, label) of `rows`, then a blank line."""
    o = [f"| {first_column} | instructions | µs at {M4F_HZ / 1e6:.0f} MHz (at least) | "
         "CPU share at 1 kHz (at least) |",
         "|---|---:|---:|---:|"]
    for key, label in rows:
        us = figures[key] / M4F_HZ * 1e6
        o.append(f"| {label} | {figures[key]:.1f} | {us:.2f} | {us / 10:.2f} % |")
    o.append("")
    return o


def added_flash_table(builds, flash, text_added=False):
    """The table of `minimal` builds ((label, sizes, _)) against ExpMap + History's row of the flash table:
    section sizes, the flash added (.text + .rodata + .data) and, with `text_added`, the .text added; then a
    blank line."""
    base_sizes = next(sz for s_, i, sz in flash if (s_, i) == ("ExpMap", "History"))
    base = sum(base_sizes[:3])
    o = ["| `minimal` + | .text | .rodata | .data |" + (" .text added |" if text_added else "") + " added |",
         "|---|---:|---:|---:|" + ("---:|" if text_added else "") + "---:|"]
    for label, (t, r, d, _), _ in builds:
        text = f" {t - base_sizes[0]} |" if text_added else ""
        o.append(f"| {label} | {t} | {r} | {d} |{text} **{t + r + d - base}** |")
    o.append("")
    return o


def largest_functions(intro, added):
    """`intro`, then the ten largest of `added` ((function, bytes), largest first) as a table and a blank line;
    nothing if `added` is empty."""
    if not added:
        return []
    rows = [f"| `{name}` | {size} |" for name, size in added[:10]]
    return [intro, "| function | bytes |", "|---|---:|"] + rows + [""]


def estimator_section(est, est_flash, flash, worst):
    o = ["## The estimator's predict step\n"]
    o.append("What an error-state filter's covariance costs beside the propagator (issue 28): "
             "`error_state::Step::between` (the transition `Φ` and process noise `Q` of an interval, from the "
             "attitudes at its ends) and `covariance::Ud::<f32, 6>` (the covariance of `(δθ, δb)` as `U D Uᵀ`: "
             "Thornton's predict, Bierman's scalar update), in f32 on the Cortex-M4F, counted by the "
             "`predict` program as `bench` counts (QEMU `mps2-an386`, `-icount shift=10`): ExpMap + History + "
             "FirstOrder, Plain at 1 kHz, |omega| about 1.2 rad/s, an ICM-42688-class gyro's noise "
             "(0.0028 °/s/√Hz, 5 °/h/√h), and a covariance with spread eigenvalues and correlations (0.1 rad and "
             "0.3 mrad/s standard deviations, 200 ms of prediction and two inclination updates before counting). "
             "Push rows are per attitude step over 80 steps; the others per call over 64 calls, each (the loop "
             "with the call − the same loop without it) / n, inputs opaque, results kept. The time is at "
             f"{M4F_HZ / 1e6:.0f} MHz and one cycle per instruction, a lower bound: on silicon `vdiv.f32` and "
             "`vsqrt.f32` take 14 cycles and a load 2.\n")
    o += m4f_time_table("what", ESTIMATOR_ROWS, est)
    push, every, tenth = (est[k] for k in ("push", "push+covariance-every-step", "push+covariance-every-10th"))
    o.append(f"The covariance every step multiplies the step's cost by {every / push:.0f}; every 10th step (what "
             "`Step::between` is for: `Φθθ` is then exactly the rotation the propagator took over the 10 steps) "
             f"by {tenth / push:.1f}. The push here is a call in this program's loop: {push:.1f} instructions, "
             "against the grid's figure above, where the compiler inlined it into the loop.\n")
    o.append("Flash: `minimal` (ExpMap + History + FirstOrder, as in the flash table) with the estimator's calls "
             "added (features `estimator-predict` and `estimator`), section sizes as above; **added** = flash "
             "(.text + .rodata + .data) − ExpMap + History's.\n")
    o += added_flash_table(est_flash, flash)
    _, _, added = est_flash[-1]
    o += largest_functions("The largest functions the estimator adds (bytes, llvm-nm; `main` inlines "
                           "`Ud::predict` and `Step::between`, so it grows by their code):\n", added)
    if any("sinf" in n for n, _ in added):
        o.append("libm's `sinf` and its kernels in software `f64` (`__muldf3`, `__adddf3`, ...) come with `Step`'s "
                 "closed form for a rotation beyond 2 rad per interval (`Real::sin` on `f32` is libm's, where the "
                 "propagator's large-angle branch uses quatprop's own `f32` sine); `hypotf`, `atanf` and "
                 "`sqrtf` with the rotation vector between the two attitudes.\n")
    elif any("atanf" in n or "hypotf" in n for n, _ in added):
        o.append("No libm sine: `Step`'s closed form takes quatprop's own `f32` sine and square root, as the "
                 "propagator's large-angle branch does. libm's `atanf`, `hypotf` and `sqrtf` come with the "
                 "rotation vector between the two attitudes (`Quat::to_rotation_vector` in `Step::between`).\n")
    between, predict, update, bound = worst["estimator"]
    o.append(f"Stack (painted by the `stack` program, bytes): `Step::between` with its `matrices()` "
             f"**{between}**; `Ud::predict` **{predict}** (the 168-byte `Ud` copied into the call included, `Φ` "
             f"and `Q` prepared outside it); one `Ud::update` **{update}**; the program's bound for each: "
             f"{bound}.\n")
    return "\n".join(o)


def front_end_section(front, front_flash, flash, worst):
    # Opens as the estimator's section does, a heading then its own prose: alike in shape only.
    o = ["## The front end's in-motion estimators\n"]
    o.append("What learning the gyro in motion from the accelerometer costs beside the propagator: "
             "`frontend::CalibrationEstimator` (the gyro's 3x3 gain and residual bias, a 12-state Kalman filter "
             "on the low-passed inclination drift) and, for comparison, `frontend::MotionBias` (the bias alone, "
             "VQF's 3-state filter on the same shadow attitude and low-pass), in f32 on the Cortex-M4F, counted "
             "by the `predict` program as above (QEMU `mps2-an386`, `-icount shift=10`). The samples are a body "
             "turning about every axis at up to about 1.2 rad/s under gravity, 1 kHz, read by a gyro with a "
             "gain error of up to 1 % and a bias of about 0.1 °/s (`firmware/src/motion.rs`); each estimator "
             "first takes 3.1 s of them, past its start-up (the accelerometer's low-pass averages its first "
             "3 s), so that its Kalman update runs on every counted sample (the program checks that the gain's "
             "uncertainty shrank over them). Per sample over 64 samples (four loops of 16), each (the loop with "
             "the calls − the same loop without them) / n, inputs opaque, results kept; the time at "
             f"{M4F_HZ / 1e6:.0f} MHz and one cycle per instruction, a lower bound as above.\n")
    o += m4f_time_table("what, per sample", FRONT_END_ROWS, front)
    o.append("Flash: `minimal` (ExpMap + History + FirstOrder, as in the flash table) with the rates through "
             "the calibration estimator (feature `calibration-estimator`: built from constants, `correct` "
             "before each push, `update` with a black-boxed accelerometer after it), section sizes as above; "
             "**added** = flash (.text + .rodata + .data) − ExpMap + History's, .text added beside it.\n")
    o += added_flash_table(front_flash, flash, text_added=True)
    _, _, added = front_flash[-1]
    o += largest_functions("The largest functions it adds (bytes, llvm-nm; a function that grew counts with its "
                           "growth):\n", added)
    cal, mb, cal_size, mb_size, bound = worst["front-end"]
    o.append(f"Stack (painted by the `stack` program, bytes, past the start-up): one sample of "
             f"`CalibrationEstimator` (`correct` + `update`) **{cal}**, of `MotionBias` **{mb}**, each with the "
             f"estimator copied into the call ({cal_size} and {mb_size} bytes: `update` also keeps a copy, to "
             f"restore on a non-finite result); the program's bound for each: {bound}.\n")
    return "\n".join(o)


def document(bench, quick, burst, flash, stack, tools, soft, est, est_flash, front, front_flash):
    per_row, worst, count = stack
    o = []
    o.append(f"_Generated by `python3 firmware/figures.py` with {tools['rustc']} and {tools['qemu']}; "
             "do not edit by hand, re-run it._\n")
    o.append("# quatprop on Cortex-M: instructions, flash, stack\n")
    o.append("Measured on the firmware in `firmware/` (release profile, fat LTO, `codegen-units = 1`, f32 "
             "throughout) under QEMU; every number below comes from that run.\n")

    o.append("## Instructions per step on the Cortex-M4F\n")
    o.append("Executed instructions per step of 1 ms, counted on the emulated Cortex-M4F (QEMU `mps2-an386`, "
             "`-icount shift=10`, SysTick at 25 MHz: instructions = ticks x 40 / 1024) by the `bench` program. "
             "Each figure is (instructions of 64 steps of pushes - instructions of the same loop without the push) "
             "/ 64, after the input model's warm-up; a step is one push for Hold, Linear and History and two for "
             "TwiceRate, GaussPoints and DeltaAngles(TwoSample). Included: the `dt` and sample checks, the input "
             "model, the step, the stabilizer and the commit. Samples are opaque (`black_box`), |omega| about "
             "1.2 rad/s (the exponential maps' Taylor branch). These are instructions, not cycles: on silicon "
             "`vdiv.f32`/`vsqrt.f32` take 14 cycles and a load 2, so cycles are higher, most for Normalize "
             "(libm's `sqrtf` in software plus a division). Raw figures: `firmware/bench-m4f.csv`.\n")
    for acc in ("Plain", "Kahan", "FloatFloat"):
        for stab in ("FirstOrder", "Normalize"):
            o.append(f"### {stab}, {acc} accumulator\n")
            o.append("| input model | " + " | ".join(SCHEMES) + " |")
            o.append("|---|" + "---:|" * len(SCHEMES))
            for inp in INPUTS:
                cells = [f"{bench[(inp, s, stab, acc)]:.1f}" for s in SCHEMES]
                o.append(f"| {INPUT_TYPES[inp]} | " + " | ".join(cells) + " |")
            o.append("")
    rec = bench[("history", "ExpMap", "FirstOrder", "Plain")]
    per, n, fixed = quick
    o.append("### The recommended configuration and the quick start\n")
    o.append(f"- ExpMap + History + FirstOrder, Plain: **{rec:.1f}** instructions per step.")
    o.append(f"- The same step in fixed point (`fixed::Q30Propagator`, raw counts in, Q30 attitude; for cores "
             f"without an FPU, see below): {bench[FIXED]:.1f} instructions per step here, where the FPU "
             f"makes f32 the cheaper.")
    o.append(f"- The README's quick start (`Attitude::on_fifo`: raw counts → axis remap → bias estimator → "
             f"`push_burst` with the exact period, the configuration above): **{per:.1f}** instructions per "
             f"sample (over {n} samples in FIFO bursts of 32; {fixed} instructions for the call overhead).\n")

    o.append("### FIFO bursts\n")
    o.append("Instructions per sample of a FIFO burst through `Propagator::push_burst` (ExpMap + History + "
             "FirstOrder, Plain, f32; `dt` from a `FixedPeriod` of 1 ms) against the same samples pushed one "
             "at a time, measured by the `burst` program (a program of its own, so the table above keeps "
             "`bench`'s code layout) the same way but counting everything a caller runs: (instructions of "
             "the loop over 256 samples - instructions of the same timed call over none) / 256, so the loop, "
             "the `dt` and the error check are included. Every burst length ends on the attitude of the single "
             "pushes bit for bit (the bench checks it and fails otherwise).\n")
    single = burst[("push-period", 1)]
    o.append("| how the samples are pushed | instructions per sample |")
    o.append("|---|---:|")
    o.append(f"| one `push` per sample, `dt` = `FixedPeriod::next_dt()`, a refusal carried over and counted "
             f"(what `push_burst` does per sample) | {single:.1f} |")
    o.append(f"| one `push` per sample, a constant `dt`, errors ignored | {burst[('push-const-dt', 1)]:.1f} |")
    for n in (1, 8, 32):
        o.append(f"| `push_burst`, bursts of {n} | {burst[('push_burst', n)]:.1f} |")
    o.append("")
    o.append("The README's quick start (`Attitude::on_fifo`, raw counts in, as above) fed the same 256 samples "
             "in FIFO reads of 1, 8 and 32 (every read length ends on the same bits):\n")
    o.append("| FIFO read length | instructions per sample |")
    o.append("|---:|---:|")
    for n in (1, 8, 32):
        o.append(f"| {n} | {burst[('quickstart', n)]:.1f} |")
    o.append("")
    o.append("### The run-time configuration\n")
    o.append("Bursts of 32 through `config::Configured` (a `Config` value chosen at run time: one `match` per "
             "burst, then the loop of the static types) against the static types' `push_burst`, measured by "
             "the `burst` program as above; both end on the same bits (checked). The stabilizer is the run-time "
             "`StabilizerKind` inside the loop; scheme, input model and accumulator are the static types.\n")
    o.append("| configuration | static types | `Configured` | ratio |")
    o.append("|---|---:|---:|---:|")
    for key, label in (("recommended", "ExpMap + History + FirstOrder, Plain (`Config::RECOMMENDED`)"),
                       ("rk4-linear-normalize-kahan", "Rk4 + Linear + Normalize, Kahan")):
        st, cf = burst[("config", key)]
        o.append(f"| {label} | {st:.1f} | {cf:.1f} | {cf / st:.3f} |")
    o.append("")
    o.append("## Flash per configuration\n")
    o.append("Section sizes (bytes, `llvm-size -A`) of the `minimal` program on thumbv7em-none-eabihf: one "
             "scheme + one input model + FirstOrder in f32, 1000 pushes, no defmt, no formatting, panic handler = "
             "exit via semihosting. `.text` includes the vector table, cortex-m-rt's start-up code and the "
             "semihosting exit; the baseline is the same program without quatprop (the same loop over "
             "black-boxed samples, the same exit), and **library code** = flash (.text + .rodata + .data) − the "
             "baseline's: what naming the configuration costs a firmware.\n")
    o.append("| scheme | input model | .text | .rodata | .data | .bss | library code |")
    o.append("|---|---|---:|---:|---:|---:|---:|")
    base = sum(flash[0][2][:3])
    for scheme, inp, (t, r, d, b) in flash:
        lib = "—" if not inp else f"{t + r + d - base}"
        o.append(f"| {scheme} | {inp or '—'} | {t} | {r} | {d} | {b} | {lib} |")
    lib = next(t + r + d - base for s_, i, (t, r, d, _) in flash if (s_, i) == ("ExpMap", "History"))
    o.append(f"\nExpMap + History + FirstOrder: **{lib}** bytes of library code, against a target of "
             f"{LIBRARY_TARGET} (2.5 KiB): {'met' if lib <= LIBRARY_TARGET else 'not met'}. Its large-angle "
             "branch (steps beyond 0.2 rad) uses quatprop's own `f32` sine and square root (src/trig.rs, "
             "tested exhaustively over their ranges), not libm's general `sinf` and table-driven `sqrtf`.\n")

    o.append("## Stack\n")
    s_bytes, s_bound, s_at = worst["small"]
    l_bytes, l_bound, l_at = worst["large"]
    o.append(f"Painted stack depth (bytes) of building a propagator and pushing until it took a full step, "
             f"for each of the {count} configurations of `firmware/src/configs.rs` (every input model x scheme, "
             "including the run-time `SchemeKind` and Baumgarte on each Runge-Kutta scheme x stabilizer, "
             "including `StabilizerKind` x accumulator), measured by the `stack` program on the Cortex-M4F. "
             "The figure includes the propagator itself. Small steps take the polynomial/Taylor paths; 0.3 rad "
             "steps take the exponential maps' trigonometric branch (quatprop's `f32` sine and square root).\n")
    o.append(f"- Worst, small steps: **{s_bytes}** bytes ({s_at}); the program's bound: {s_bound}.")
    o.append(f"- Worst, 0.3 rad steps: **{l_bytes}** bytes ({l_at}); the program's bound: {l_bound}.\n")
    o.append("Worst over stabilizers and accumulators, per input model and scheme (small / 0.3 rad steps):\n")
    schemes = []
    for (_, s) in per_row:
        if s not in schemes:
            schemes.append(s)
    inputs = []
    for (i, _) in per_row:
        if i not in inputs:
            inputs.append(i)
    o.append("| scheme | " + " | ".join(inputs) + " |")
    o.append("|---|" + "---:|" * len(inputs))
    for s in schemes:
        cells = []
        for i in inputs:
            v = per_row.get((i, s))
            cells.append(f"{v[0]} / {v[1]}" if v else "-")
        o.append(f"| {s} | " + " | ".join(cells) + " |")
    o.append("")
    o.append(estimator_section(est, est_flash, flash, worst))
    o.append(front_end_section(front, front_flash, flash, worst))
    o.append(soft_section(soft))
    return "\n".join(o)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--out", default=os.path.join(ROOT, "docs", "firmware.md"))
    args = ap.parse_args()
    tool = size_tool()
    tools = {
        "rustc": run(["rustc", "-V"]).strip(),
        "qemu": run(["qemu-system-arm", "--version"]).splitlines()[0].strip(),
    }
    build_programs()
    build_soft()
    # The emulations run side by side (bench and burst count instructions with -icount: the same counts
    # whatever else runs) while the flash table's images build.
    log("running bench, burst, predict (-icount shift=10) and stack on mps2-an386, bench on mps2-an385 and "
        "microbit ...")
    procs = {name: start(name) for name in ("bench", "burst", "predict", "stack")}
    soft_procs = {(t, b): start("bench", t) for t, b, *_ in SOFT_FLOAT}
    soft_procs[("thumbv6m-none-eabi", "mps2-an385")] = start("bench", "thumbv6m-none-eabi", "mps2-an385")
    flash = flash_table(tool)
    both_flash = estimator_flash(tool, ESTIMATOR_FLASH + FRONT_END_FLASH)
    est_flash, front_flash = both_flash[:len(ESTIMATOR_FLASH)], both_flash[len(ESTIMATOR_FLASH):]
    bench, quick = run_bench(finish(procs["bench"], "bench"))
    burst = run_burst(finish(procs["burst"], "burst"))
    predict = finish(procs["predict"], "predict")
    est = run_rows(predict, "estimator", ESTIMATOR_ROWS, "predict")
    front = run_rows(predict, "front-end", FRONT_END_ROWS, "predict's front end")
    stack = run_stack(finish(procs["stack"], "stack"))
    soft = run_soft(soft_procs)
    write_bench_csv(bench)
    text = document(bench, quick, burst, flash, stack, tools, soft, est, est_flash, front, front_flash)
    with open(args.out, "w") as f:
        f.write(text)
    log(f"wrote {args.out} and {os.path.join(FW, 'bench-m4f.csv')}")
    print(text)


if __name__ == "__main__":
    main()
