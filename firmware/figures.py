#!/usr/bin/env python3
"""Regenerates the Cortex-M figures of README.md ("Cost on Cortex-M").

Usage: python3 firmware/figures.py > /tmp/figures.md

Needs: the thumb targets, qemu-system-arm, defmt-print, rustup's llvm-tools (llvm-objdump, llvm-size).
What it does:
1. builds and runs `bench` on the emulated Cortex-M4F (mps2-an386, `-icount shift=10`): executed
   instructions per step for every scheme x stabilizer x input model (f32), plus two f64 rows;
2. counts the floating-point operations each FirstOrder configuration needs (a cost model over the same
   tableaux as src/scheme/tableaux.rs) and compares the measured count with flops + unavoidable loads/stores;
3. estimates Cortex-M4 cycles per step: measured instructions x the average cycles per instruction of the
   static instruction mix of that configuration's loop in the disassembly, with the Cortex-M4 timings of the
   ARM Cortex-M4 TRM (r0p1, tables 3-1 and 7-1). An estimate, labelled so: QEMU counts instructions, not cycles;
   The counts also go to firmware/bench-m4f.csv (read by the lab's work-precision study);
4. builds `minimal` once per scheme (one scheme + FirstOrder, no defmt) and the smoke/isr/bench images and
   reports .text/.rodata/.data/.bss from llvm-size.
"""
import os
import re
import subprocess
import sys
from collections import Counter
from fractions import Fraction as F

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
TARGET = "thumbv7em-none-eabihf"
SYSROOT = subprocess.run(["rustc", "--print", "sysroot"], capture_output=True, text=True, check=True).stdout.strip()
TOOLS = os.path.join(SYSROOT, "lib", "rustlib", "x86_64-unknown-linux-gnu", "bin")
FW = ["--manifest-path", "firmware/Cargo.toml", "--release", "--target", TARGET]


def log(msg):
    print(msg, file=sys.stderr, flush=True)


def cargo(*args, capture=False):
    r = subprocess.run(["cargo", *args], cwd=ROOT, capture_output=capture, text=True)
    if r.returncode != 0:
        if capture:
            sys.stderr.write(r.stderr)
        raise SystemExit(f"cargo {' '.join(args)} failed")
    return r.stdout if capture else None


def elf(name):
    return os.path.join(ROOT, "firmware", "target", TARGET, "release", name)


# ---------------------------------------------------------------- 1. bench
def run_bench():
    log("building and running bench on mps2-an386 ...")
    out = cargo("run", "-q", *FW, "--bin", "bench", capture=True)
    rows = {}
    for line in out.splitlines():
        m = re.match(r"bench (f32|f64) (\S+) (\S+) (hold|linear|mid) ([\d.]+)$", line)
        if m:
            rows[m.group(1, 2, 3, 4)] = float(m.group(5))
        k = re.match(r"kahan f32 (\S+) (\S+) (hold|linear|mid) ([\d.]+)$", line)
        if k:
            rows[("kahan",) + k.group(1, 2, 3)] = float(k.group(4))
    if "bench done" not in out:
        raise SystemExit("bench did not finish")
    return rows


# ---------------------------------------------------------------- 2. flop model
# The tableaux of src/scheme/tableaux.rs (exact fractions).
TABLEAUX = {
    "Euler": ([0], [[]], [1]),
    "Rk2": ([0, F(1, 2)], [[], [F(1, 2)]], [0, 1]),
    "Rk3": ([0, F(1, 2), 1], [[], [F(1, 2)], [-1, 2]], [F(1, 6), F(2, 3), F(1, 6)]),
    "Rk4": ([0, F(1, 2), F(1, 2), 1], [[], [F(1, 2)], [0, F(1, 2)], [0, 0, 1]],
            [F(1, 6), F(1, 3), F(1, 3), F(1, 6)]),
    "Rk5": ([0, F(1, 5), F(3, 10), F(4, 5), F(8, 9), 1],
            [[], [F(1, 5)], [F(3, 40), F(9, 40)], [F(44, 45), F(-56, 15), F(32, 9)],
             [F(19372, 6561), F(-25360, 2187), F(64448, 6561), F(-212, 729)],
             [F(9017, 3168), F(-355, 33), F(46732, 5247), F(49, 176), F(-5103, 18656)]],
            [F(35, 384), 0, F(500, 1113), F(125, 192), F(-2187, 6784), F(11, 84)]),
}
MUL_PURE = 20        # q (x) (0, w): 12 mul + 8 add
QUAT_PRODUCT = 28    # 16 mul + 12 add
FIRST_ORDER = 14     # |q|^2 (7), 1 + (1 - n)/2 (3), q * f (4)


def weighted_sum_flops(coefs):
    """sum_j a_j k_j (quaternions), scaled by hh and added to q, skipping zeros; a == 1 costs no multiply."""
    nz = [a for a in coefs if a != 0]
    if not nz:
        return 0
    return sum(0 if a == 1 else 4 for a in nz) + 4 * (len(nz) - 1) + 4 + 4


def held_flops(name):
    """Rate held: q (x) (C(s), S(s) v), v = w*hh, s = |v|^2; polynomial degrees from R(z)."""
    c, a, b = TABLEAUX[name]
    order = len(b) if name != "Rk5" else 5
    # r_m = 1/m! up to the order, plus DP5's r_6 = 1/600.
    r = [F(1, 1)]
    fact = 1
    for m in range(1, order + 1):
        fact *= m
        r.append(F(1, fact))
    if name == "Rk5":
        r.append(F(1, 600))
    cpoly = r[0::2]
    spoly = r[1::2]
    deg_c, deg_s = len(cpoly) - 1, len(spoly) - 1
    f = 1 + 3  # hh, v
    if deg_c or deg_s:
        f += 5  # s
    f += 2 * deg_c + 2 * deg_s
    f += (3 if deg_s else 0) + (4 if deg_c else 0)
    return f + MUL_PURE + 4


def stage_flops(name, inp):
    c, a, b = TABLEAUX[name]
    interior = sorted({x for x in c if x not in (0, 1) and not (inp == "mid" and x == F(1, 2))})
    if inp == "linear":
        rates = (3 if interior else 0) + 6 * len(interior)
    else:
        rates = 15 * len(interior)
    f = 1 + rates + MUL_PURE * len(c)
    for row in a:
        f += weighted_sum_flops(row)
    return f + weighted_sum_flops(b)


def expmap_flops(inp):
    exp_half = 5 + 4 + 4 + 3  # |v|^2, cos and sin/x Taylor, v * s
    increment = {"hold": 3, "linear": 24, "mid": 30}[inp]
    return 1 + increment + exp_half + QUAT_PRODUCT


def algorithm_flops(scheme, inp):
    if scheme == "ExpMap":
        f = expmap_flops(inp)
    elif inp == "hold":
        f = held_flops(scheme)
    else:
        f = stage_flops(scheme, inp)
    return f + FIRST_ORDER


def validation_flops(scheme, inp):
    n = {"hold": 1, "linear": 2, "mid": 3}[inp]
    finite_rates = 5 * n + (n - 1)
    angle = 0 if scheme == "ExpMap" else 5 * n + 2
    finite_result = 7
    return finite_rates + angle + finite_result


def loads_stores(inp):
    n = {"hold": 1, "linear": 2, "mid": 3}[inp]
    # q: 4 loads + 4 stores; samples: 3 loads each; dt: 1; steps and corrections (u64): 4 + 4; pending: 2.
    return 8 + 3 * n + 1 + 8 + 2


# ---------------------------------------------------------------- 3. cycle estimate
def cycles_of(mnemonic, operands):
    m = mnemonic.split(".")[0]
    if m in ("vdiv", "vsqrt"):
        return 14
    if m in ("vmla", "vmls", "vfma", "vfms", "vnmla", "vnmls", "vfnma", "vfnms"):
        return 3
    if m in ("vpush", "vpop", "vldmia", "vstmia", "vldmdb", "vstmdb", "push", "pop", "ldm", "stm",
             "ldmia", "stmia", "stmdb", "ldmdb"):
        regs = operands.count(",") + 1
        if m.startswith("v") and "d" in operands:
            regs *= 2
        return 1 + regs
    if m in ("vldr", "vstr"):
        return 2
    if m.startswith("v"):
        return 1
    if m in ("ldrd", "strd"):
        return 3
    if m.startswith("ldr") or m.startswith("str"):
        return 2
    if m in ("bl", "blx"):
        return 3
    if m.startswith("b") and m not in ("bic", "bics", "bfi", "bfc"):
        return 2
    if m in ("cbz", "cbnz"):
        return 2
    if m in ("udiv", "sdiv"):
        return 7
    return 1


def static_cpi():
    """Average cycles per instruction of each bench::steps::<...> loop, keyed like the bench rows."""
    log("disassembling bench ...")
    dis = subprocess.run([os.path.join(TOOLS, "llvm-objdump"), "-d", "-C", "--no-show-raw-insn", elf("bench")],
                         capture_output=True, text=True, check=True).stdout
    cpi = {}
    key = None
    mix = Counter()
    cyc = 0

    def close():
        if key is not None and sum(mix.values()):
            cpi[key] = cyc / sum(mix.values())

    for line in dis.splitlines():
        h = re.match(r"^[0-9a-f]+ <(.*)>:$", line)
        if h:
            close()
            key, mix, cyc = None, Counter(), 0
            s = re.match(r"bench::steps::<(f32|f64), [\w:]*::(\w+), [\w:]*::(\w+)(?:<f32>)?, "
                         r"[\w:]*::(\w+)(?:<f32>)?, (\d)>", h.group(1))
            if s:
                stab = {"Every": "Every(16)"}.get(s.group(3), s.group(3))
                kind = s.group(1) if s.group(4) == "Plain" else "kahan"
                key = (kind, s.group(2), stab, ["hold", "linear", "mid"][int(s.group(5))])
            continue
        ins = re.match(r"^\s+[0-9a-f]+:\s+(\S+)\s*(.*)$", line)
        if key and ins and not ins.group(1).startswith("."):
            mix[ins.group(1)] += 1
            cyc += cycles_of(ins.group(1), ins.group(2))
    close()
    return cpi


# ---------------------------------------------------------------- 4. sizes
def sizes(path):
    out = subprocess.run([os.path.join(TOOLS, "llvm-size"), "-A", path], capture_output=True, text=True,
                         check=True).stdout
    s = {}
    for line in out.splitlines():
        p = line.split()
        if len(p) >= 2 and p[0].startswith(".") and p[1].isdigit():
            s[p[0]] = int(p[1])
    text = s.get(".vector_table", 0) + s.get(".text", 0)
    return text, s.get(".rodata", 0), s.get(".data", 0), s.get(".bss", 0) + s.get(".uninit", 0)


def size_table():
    rows = []
    for scheme, feat in [("Euler", "scheme-euler"), ("Rk2", "scheme-rk2"), ("Rk3", "scheme-rk3"),
                         ("Rk4", None), ("Rk5", "scheme-rk5"), ("ExpMap", "scheme-expmap")]:
        log(f"building minimal with {scheme} ...")
        args = ["build", "-q", *FW, "--no-default-features", "--bin", "minimal"]
        if feat:
            args += ["--features", feat]
        cargo(*args)
        rows.append((f"minimal ({scheme} + FirstOrder, step_linear, no defmt)", sizes(elf("minimal"))))
    log("building smoke, isr, bench ...")
    cargo("build", "-q", *FW, "--bins")
    for b, what in [("smoke", "smoke (every scheme x stabilizer via the runtime enums, defmt)"),
                    ("isr", "isr (Rk4 + FirstOrder, heapless queue, defmt)"),
                    ("bench", "bench (every measured loop monomorphized, defmt)")]:
        rows.append((what, sizes(elf(b))))
    return rows


def write_bench_csv(bench):
    """firmware/bench-m4f.csv: the bench counts for the lab's work-precision overlay (committed)."""
    with open(os.path.join(ROOT, "firmware", "bench-m4f.csv"), "w") as f:
        f.write("precision,scheme,stabilizer,input,instructions_per_step\n")
        for key, v in sorted(bench.items()):
            if key[0] == "kahan":
                f.write(f"f32-kahan,{key[1]},{key[2]},{key[3]},{v}\n")
            else:
                f.write(f"{key[0]},{key[1]},{key[2]},{key[3]},{v}\n")


def main():
    bench = run_bench()
    write_bench_csv(bench)
    cpi = static_cpi()
    schemes = ["Euler", "Rk2", "Rk3", "Rk4", "Rk5", "ExpMap", "Magnus4", "Cf4"]
    flop_schemes = schemes[:6]  # the cost model covers the RK tableaux and the exponential map
    stabs = ["Off", "Normalize", "FirstOrder", "Every(16)", "Baumgarte"]

    print("### Instructions per step on the Cortex-M4F (f32)\n")
    print("Executed instructions per step, `-icount` on mps2-an386, release build with fat LTO; inputs through "
          "`black_box`; includes input validation and the commit. `est. cycles` = instructions x the average "
          "Cortex-M4 cycles per instruction of that configuration's static instruction mix (an estimate from the "
          "TRM timings, not a measurement).\n")
    print("| scheme | stabilizer | hold | linear | mid | est. cycles (hold / linear / mid) |")
    print("|---|---|---|---|---|---|")
    for s in schemes:
        for z in stabs:
            vals = [bench.get(("f32", s, z, i)) for i in ("hold", "linear", "mid")]
            est = []
            for i, v in zip(("hold", "linear", "mid"), vals):
                c = cpi.get(("f32", s, z, i))
                est.append(f"{v * c:.0f}" if (v is not None and c) else "–")
            print(f"| {s} | {z} | " + " | ".join(f"{v:.1f}" if v is not None else "–" for v in vals)
                  + f" | {' / '.join(est)} |")
    print("\nSoft-float f64 on the same single-precision FPU:\n")
    print("| scheme | stabilizer | hold | linear | mid |")
    print("|---|---|---|---|---|")
    for s in ("Rk4", "ExpMap"):
        vals = [bench.get(("f64", s, "FirstOrder", i)) for i in ("hold", "linear", "mid")]
        print(f"| {s} | FirstOrder | " + " | ".join(f"{v:.0f}" if v is not None else "–" for v in vals) + " |")

    print("\nCompensated (Kahan) accumulator against the plain one, f32 (target: at most 1.6x):\n")
    print("| configuration | plain | Kahan | ratio |")
    print("|---|---|---|---|")
    for key in sorted(k for k in bench if k[0] == "kahan"):
        plain = bench[("f32",) + key[1:]]
        print(f"| {key[1]} + {key[2]}, {key[3]} | {plain:.1f} | {bench[key]:.1f} | {bench[key] / plain:.2f} |")

    print("\n### Against the floating-point work each configuration needs (FirstOrder, f32)\n")
    print("`flops`: additions and multiplications the algorithm needs (cost model over the tableaux in "
          "firmware/figures.py); `checks`: flops of the input and result validation; `ld/st`: unavoidable loads "
          "and stores (attitude, samples, dt, counters). A fused multiply-add is one instruction for two flops, "
          "so a ratio below 1 is possible. Target: measured / (flops + ld/st) <= 1.5.\n")
    print("| scheme | input | flops | checks | ld/st | measured | measured / (flops + ld/st) |")
    print("|---|---|---|---|---|---|---|")
    worst = 0.0
    for s in flop_schemes:
        for i in ("hold", "linear", "mid"):
            fl = algorithm_flops(s, i)
            ch = validation_flops(s, i)
            ls = loads_stores(i)
            v = bench.get(("f32", s, "FirstOrder", i))
            ratio = v / (fl + ls)
            worst = max(worst, ratio)
            print(f"| {s} | {i} | {fl} | {ch} | {ls} | {v:.1f} | {ratio:.2f} |")
    print(f"\nWorst ratio: {worst:.2f}.\n")

    print("### Flash and RAM (thumbv7em-none-eabihf, release, fat LTO, bytes)\n")
    print("| image | .text (+ vectors) | .rodata | .data | .bss |")
    print("|---|---|---|---|---|")
    for what, (t, r, d, b) in size_table():
        print(f"| {what} | {t} | {r} | {d} | {b} |")


if __name__ == "__main__":
    main()
