#!/usr/bin/env python3
"""Writes the measured C-vs-Rust figures into docs/c-api.md between its figure markers.

Called by `ffi/ci --docs` with the numbers that run measured (no number is typed by hand):
  figures.py DOC C_FLASH RUST_FLASH KINDS_FLASH C_PER RUST_PER KINDS_PER MONO_FLASH MONO_PER C_CALL C_SUM
             C_SUM_ABI3 GCC_VERSION RUSTC_VERSION QEMU_VERSION
(C_CALL: instructions per single quatprop_push_counts call; C_SUM: per CRC-32C of the state's block;
C_SUM_ABI3: per ABI 3's word hash of the same block, timed beside it.)
"""
import sys

BEGIN = "<!-- figures: begin (written by ffi/ci --docs) -->"
END = "<!-- figures: end -->"


def main():
    (doc, c_flash, r_flash, k_flash, c_per, r_per, k_per, m_flash, m_per, c_call, c_sum, c_sum3, gcc, rustc,
     qemu) = sys.argv[1:16]
    c_flash, r_flash, k_flash, m_flash = int(c_flash), int(r_flash), int(k_flash), int(m_flash)
    c_per, r_per, k_per, m_per = float(c_per), float(r_per), float(k_per), float(m_per)
    c_call, c_sum, c_sum3 = float(c_call), float(c_sum), float(c_sum3)
    lines = [
        BEGIN,
        "",
        "| Cortex-M4F image (mps2-an386) | flash (text + data, bytes) | instructions per sample |",
        "| --- | ---: | ---: |",
        f"| C quick start through the C API (run-time choice of everything; default build) | {c_flash} | {c_per:.2f} |",
        f"| the same, the C API built with the feature `monomorphized` | {m_flash} | {m_per:.2f} |",
        f"| Rust quick start's `Attitude` (static types), same C harness | {r_flash} | {r_per:.2f} |",
        f"| the same with the core's run-time `SchemeKind` and `StabilizerKind` | {k_flash} | {k_per:.2f} |",
        f"| C API − static Rust: what run-time choice costs | {c_flash - r_flash:+d} ({(c_flash / r_flash - 1) * 100:+.0f} %) "
        f"| {c_per - r_per:+.2f} ({(c_per / r_per - 1) * 100:+.1f} %) |",
        f"| of which the core's run-time scheme and stabilizer | {k_flash - r_flash:+d} | {k_per - r_per:+.2f} |",
        f"| of which the C layer (input model × accumulator, front end, checks) | {c_flash - k_flash:+d} "
        f"| {c_per - k_per:+.2f} |",
        "",
        f"Measured by `ffi/ci --docs`: arm-none-eabi-gcc {gcc} `-O2`, rustc {rustc} (`opt-level=3`, fat LTO, "
        f"`panic=abort`), QEMU {qemu} with `-icount shift=10`; instructions are SysTick ticks × 40 / 2¹⁰ "
        "(executed instructions, not cycles) of `on_fifo` over 256 coning samples in FIFO bursts of 32, "
        "minus the same run with no burst, per sample. Flash is the whole image: the startup, the sample "
        "generator and the harness are the same C code in all three; the Rust rows call the Rust quick start "
        "(the crate `quatprop-quickstart`, firmware/quickstart/, called by `ffi/src/baseline.rs`) through the same harness.",
        "",
        f"Per call, on the same image: a single `quatprop_push_counts` (one sample) takes {c_call:.2f} instructions. "
        f"The state's CRC-32C takes {c_sum:.2f} on the quick start's state (it reads the encoding, 8 bytes per "
        "step, and checks the zeros before it), and a call that changes the state computes it twice (to verify "
        f"the block, then to seal the new one; a getter once): {2 * c_sum / c_call * 100:.1f} % of the single push, "
        "a 32nd of that per sample in a FIFO burst of 32. ABI 3's word hash, which missed two-bit damage, took "
        f"{c_sum3:.2f} on the same block, timed beside it: the CRC costs {2 * (c_sum - c_sum3):+.0f} instructions per "
        "push call.",
        "",
        END,
    ]
    text = open(doc, encoding="utf-8").read()
    head, sep, rest = text.partition(BEGIN)
    _, sep2, tail = rest.partition(END)
    if not sep or not sep2:
        raise SystemExit(f"{doc}: figure markers not found")
    open(doc, "w", encoding="utf-8").write(head + "\n".join(lines) + tail)


if __name__ == "__main__":
    main()
