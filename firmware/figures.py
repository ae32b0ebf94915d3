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
3. builds and runs `stack` on the M4F: the painted stack depth of a push for every configuration.
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
# The flash target for ExpMap + History + FirstOrder: library code (bytes).
LIBRARY_TARGET = 2560


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


def cargo(*args):
    """cargo in firmware/ (its .cargo/config.toml: runner, DEFMT_LOG)."""
    return run(["cargo", *args, "--release", "--target", TARGET])


def elf(name):
    # cargo runs in firmware/, so a relative CARGO_TARGET_DIR is relative to it.
    target_dir = os.path.join(FW, os.environ.get("CARGO_TARGET_DIR") or "target")
    return os.path.join(target_dir, TARGET, "release", name)


# ---------------------------------------------------------------- 1. bench
def build_programs():
    """bench, burst and stack in one cargo command: their fat-LTO links run in parallel."""
    log("building bench, burst and stack ...")
    cargo("build", "-q", "--bin", "bench", "--bin", "burst", "--bin", "stack")


def start(name):
    """Starts a built program on mps2-an386 through qemu-run (the cargo runner), its output into a file (a
    full pipe would stall the emulator); `finish` waits for it and reads the file."""
    out = tempfile.TemporaryFile(mode="w+")
    return subprocess.Popen(["./qemu-run", elf(name)], cwd=FW, stdout=out, stderr=subprocess.STDOUT,
                            text=True), out


def finish(started, name):
    proc, out = started
    proc.wait()
    out.seek(0)
    text = out.read()
    if proc.returncode != 0:
        sys.stderr.write(text)
        raise SystemExit(f"{name} failed on mps2-an386 ({proc.returncode})")
    return text


def run_bench(out):
    rows = {}
    quick = None
    for line in out.splitlines():
        m = re.match(r"bench (\S+) (\S+) (\S+) (Plain|Kahan|FloatFloat) ([\d.]+)$", line)
        if m:
            rows[m.group(1, 2, 3, 4)] = float(m.group(5))
        q = re.match(r"bench quickstart on_fifo per-sample ([\d.]+) \(samples=(\d+), fixed=(\d+)\)", line)
        if q:
            quick = (float(q.group(1)), int(q.group(2)), int(q.group(3)))
    if "bench done" not in out or quick is None:
        raise SystemExit("bench did not finish:\n" + out)
    expected = len(INPUTS) * len(SCHEMES) * 2 * 3
    if len(rows) != expected:
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
        for (inp, scheme, stab, acc), v in sorted(rows.items(), key=lambda kv: (kv[0][3], kv[0][1], kv[0][2],
                                                                               INPUTS.index(kv[0][0]))):
            prec = {"Plain": "f32", "Kahan": "f32-kahan", "FloatFloat": "f32-floatfloat"}[acc]
            f.write(f"{prec},{scheme},{stab},{inp},{v}\n")


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
    if count is None or len(worst) != 2:
        raise SystemExit("stack did not finish:\n" + out)
    return per_row, worst, count


# ---------------------------------------------------------------- document
def document(bench, quick, burst, flash, stack, tools):
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
    # The three emulations run side by side (bench and burst count instructions with -icount: the same
    # counts whatever else runs) while the flash table's images build.
    log("running bench, burst (-icount shift=10) and stack on mps2-an386 ...")
    procs = {name: start(name) for name in ("bench", "burst", "stack")}
    flash = flash_table(tool)
    bench, quick = run_bench(finish(procs["bench"], "bench"))
    burst = run_burst(finish(procs["burst"], "burst"))
    stack = run_stack(finish(procs["stack"], "stack"))
    write_bench_csv(bench)
    text = document(bench, quick, burst, flash, stack, tools)
    with open(args.out, "w") as f:
        f.write(text)
    log(f"wrote {args.out} and {os.path.join(FW, 'bench-m4f.csv')}")
    print(text)


if __name__ == "__main__":
    main()
