//! The state's check (CRC-32C over the whole block), against damage of every kind, beside ABI 3's word hash
//! on the same damage (`checksum_abi3`, the same state in ABI 3's layout): every single bit and every pair
//! of bits of two configurations' states through `load` (what every call runs first), the code's distance
//! and bursts from its syndromes, seeded random damage, and the C entry points on a sample.
//!
//! The counts are printed (in ffi/: `cargo test check -- --nocapture`); the CRC's are asserted to be zero,
//! ABI 3's pair count to be non-zero (the damage is the kind that hash missed).

use super::super::*;
use super::largest;
use std::collections::HashSet;

/// SplitMix64: the random damage is the same on every run (the calibration estimator's block's tests
/// draw theirs from it too).
pub(super) struct Rng(pub(super) u64);

impl Rng {
    fn next(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }
    pub(super) fn below(&mut self, n: usize) -> usize {
        (self.next() % n as u64) as usize
    }
    fn byte(&mut self) -> u8 {
        self.next() as u8
    }
}

const BITS: usize = 8 * QUATPROP_STATE_SIZE;

/// Bit `bit` of a block of any size flipped (bit `8k + i`: byte k's bit i, the order the reflected CRC
/// reads).
pub(super) fn flip<const N: usize>(b: &mut [u8; N], bit: usize) {
    b[bit / 8] ^= 1 << (bit % 8);
}

/// `b` with each of its bits flipped in turn, then with `pairs` random pairs of bits flipped (a pair that
/// draws the same bit twice is skipped): the damaged blocks the entry-point tests start from.
pub(super) fn single_bits_and_pairs<const N: usize>(
    b: &[u8; N],
    rng: &mut Rng,
    pairs: usize,
) -> Vec<[u8; N]> {
    let bits = 8 * N;
    let mut damaged = Vec::new();
    for i in 0..bits {
        let mut c = *b;
        flip(&mut c, i);
        damaged.push(c);
    }
    for _ in 0..pairs {
        let (i, j) = (rng.below(bits), rng.below(bits));
        if i != j {
            let mut c = *b;
            flip(&mut c, i);
            flip(&mut c, j);
            damaged.push(c);
        }
    }
    damaged
}

/// The syndrome of each single flipped bit of the sealed block `b` (of any size: "CRC of the data xor the
/// stored CRC", zero for `b` itself), after checking on `errors` random errors of 1 to 40 bits (from
/// `seed`) that the code is linear: a random error's syndrome is the xor of its bits'.
pub(super) fn bit_syndromes<const N: usize>(b: &[u8; N], seed: u64, errors: usize) -> Vec<u32> {
    let syndrome = |c: &[u8; N]| crc32c(&c[..N - 4]) ^ stored_sum(c);
    assert_eq!(syndrome(b), 0);
    let s: Vec<u32> = (0..8 * N)
        .map(|i| {
            let mut c = *b;
            flip(&mut c, i);
            syndrome(&c)
        })
        .collect();
    let mut rng = Rng(seed);
    for _ in 0..errors {
        let mut c = *b;
        let mut want = 0;
        for _ in 0..1 + rng.below(40) {
            let i = rng.below(8 * N);
            flip(&mut c, i);
            want ^= s[i];
        }
        assert_eq!(syndrome(&c), want, "the code is linear");
    }
    s
}

/// The block behind a C state.
fn bytes(s: &quatprop_t) -> Block {
    // SAFETY: a `quatprop_t` is QUATPROP_STATE_SIZE initialized bytes.
    unsafe { *(s as *const quatprop_t).cast::<Block>() }
}

fn state(b: &Block) -> quatprop_t {
    // SAFETY: any QUATPROP_STATE_SIZE bytes are a `quatprop_t` (plain u64 words); `Block` is no larger.
    unsafe { core::mem::transmute::<Block, quatprop_t>(*b) }
}

/// The quick start's configuration (ExpMap, History, FirstOrder, plain) set up through the C API with its
/// front end (count scale, axis remap, bias estimator, fixed period) after a FIFO burst of 32 samples.
fn quick_start() -> Block {
    let mut s = quatprop_t {
        _opaque: [0; QUATPROP_STATE_WORDS],
    };
    let mut c = quatprop_config_t {
        scheme: 0,
        stabilizer: 0,
        every: 0,
        input: 0,
        coning: 0,
        accumulator: 0,
        q0: Quat::IDENTITY.into(),
    };
    let fifo: Vec<[i16; 3]> = (0..32).map(|i| [10 + i, -20, 30 - 2 * i]).collect();
    let mut n = 0;
    // SAFETY: every pointer is to a live local of the right type; `fifo` holds 32 triples.
    unsafe {
        assert_eq!(quatprop_config_default(&mut c), S::QUATPROP_OK);
        assert_eq!(quatprop_init(&mut s, &c), S::QUATPROP_OK);
        assert_eq!(quatprop_set_count_scale_dps(&mut s, 2000.0), S::QUATPROP_OK);
        assert_eq!(
            quatprop_set_axis_remap(&mut s, QUATPROP_REMAP_PY_NX_PZ),
            S::QUATPROP_OK
        );
        assert_eq!(
            quatprop_set_bias_estimator(&mut s, 1.0, 1e-3, 0.05, QUATPROP_DEFAULT_DRIFT),
            S::QUATPROP_OK
        );
        assert_eq!(quatprop_set_fixed_period(&mut s, 1e-3), S::QUATPROP_OK);
        let st = quatprop_push_counts_burst(&mut s, fifo.as_ptr().cast(), 32, &mut n);
        assert_eq!((st, n), (S::QUATPROP_OK, 32));
    }
    bytes(&s)
}

/// The two configurations: the largest state (delta angles, five-sample coning, float-float, every
/// front-end part) and the quick start's, each sealed as this version seals it.
fn configurations() -> [(&'static str, Block); 2] {
    [
        ("largest", encode(&largest()).unwrap()),
        ("quick start", quick_start()),
    ]
}

/// The same state as ABI 3 sealed it: "QPF3", the length, the word hash in word 2, the encoding from 12.
fn encode_abi3(b: &Block) -> Block {
    let inner = load(b).unwrap();
    let mut old: Block = [0; QUATPROP_STATE_SIZE];
    let len = postcard::to_slice(&inner, &mut old[12..]).unwrap().len();
    old[0..4].copy_from_slice(&OLD_MAGICS[1].to_ne_bytes());
    old[4..8].copy_from_slice(&(len as u32).to_ne_bytes());
    let sum = checksum_abi3(&old);
    old[8..12].copy_from_slice(&sum.to_ne_bytes());
    old
}

/// Whether ABI 3's `load` would have taken `b` past its check (tag, length, word hash).
fn passes_abi3(b: &Block) -> bool {
    word(b, 0) == OLD_MAGICS[1]
        && word(b, 1) as usize <= QUATPROP_STATE_SIZE - 12
        && word(b, 2) == checksum_abi3(b)
}

/// What a call must return for a changed block: no tag (`QUATPROP_NOT_INITIALIZED`) or corrupted.
fn expected(b: &Block) -> quatprop_status_t {
    if word(b, TAG / 4) != MAGIC && !OLD_MAGICS.contains(&word(b, 0)) {
        S::QUATPROP_NOT_INITIALIZED
    } else {
        S::QUATPROP_CORRUPTED_STATE
    }
}

/// The check's verdict on `b`: `Ok` only if it would be decoded (never for a changed block).
fn refused(b: &Block) -> bool {
    match load(b) {
        Ok(_) => false,
        Err(e) => {
            assert_eq!(e, expected(b));
            true
        }
    }
}

/// The hand-written CRC is CRC-32C: the catalogue's check value, and the `crc` crate's `CRC_32_ISCSI` on
/// random data of every length to 600 bytes.
#[test]
fn the_checksum_is_crc32c() {
    assert_eq!(crc32c(b"123456789"), 0xE306_9283);
    assert_eq!(crc32c(b""), 0);
    let oracle = ::crc::Crc::<u32>::new(&::crc::CRC_32_ISCSI);
    assert_eq!(oracle.algorithm.poly, 0x1EDC_6F41);
    let mut rng = Rng(1);
    for len in 0..600 {
        let data: Vec<u8> = (0..len).map(|_| rng.byte()).collect();
        assert_eq!(crc32c(&data), oracle.checksum(&data), "length {len}");
    }
}

/// The check covers the whole block: for every encoding length, the checksum a block is sealed with (the
/// CRC started after the leading zeros) is the CRC-32C of all 1020 bytes before it.
#[test]
fn the_checksum_covers_every_byte_before_it() {
    let oracle = ::crc::Crc::<u32>::new(&::crc::CRC_32_ISCSI);
    let mut rng = Rng(2);
    for len in 0..=PAYLOAD {
        let mut b: Block = [0; QUATPROP_STATE_SIZE];
        let start = (PAYLOAD - len) & !3;
        for x in &mut b[start..start + len] {
            *x = rng.byte();
        }
        b[TAG..TAG + 4].copy_from_slice(&MAGIC.to_ne_bytes());
        b[TAG + 4..SUM].copy_from_slice(&(len as u32).to_ne_bytes());
        assert_eq!(placement(&b), Some((start, len)));
        assert_eq!(
            checksum(&b),
            Some(oracle.checksum(&b[..SUM])),
            "length {len}"
        );
        // A non-zero byte before the encoding, or between it and the tag, is never sealed.
        for at in [0, start.wrapping_sub(1), start + len] {
            if at < PAYLOAD && !(start..start + len).contains(&at) {
                let mut c = b;
                c[at] = 1;
                assert_eq!(checksum(&c), None, "length {len}, byte {at}");
            }
        }
    }
    // Beyond PAYLOAD the length is refused.
    let mut b = encode(&largest()).unwrap();
    b[TAG + 4..SUM].copy_from_slice(&(PAYLOAD as u32 + 1).to_ne_bytes());
    assert_eq!(checksum(&b), None);
}

/// Every single bit and every pair of bits (33 550 336 pairs of the 8192 bits) of both configurations'
/// states: `load` refuses each with its code. ABI 3's check on the same flips of the same states, counted.
#[test]
fn every_bit_and_every_pair_of_bits_is_refused() {
    for (name, b) in configurations() {
        let old = encode_abi3(&b);
        assert!(load(&b).is_ok() && passes_abi3(&old));
        let (mut singles, mut old_singles) = (0, 0);
        for i in 0..BITS {
            let (mut c, mut o) = (b, old);
            flip(&mut c, i);
            flip(&mut o, i);
            singles += usize::from(!refused(&c));
            old_singles += usize::from(passes_abi3(&o));
        }
        let (mut pairs, mut old_pairs, mut tried) = (0usize, 0usize, 0usize);
        let (mut high, mut old_high) = (0, 0);
        for i in 0..BITS {
            let (mut ci, mut oi) = (b, old);
            flip(&mut ci, i);
            flip(&mut oi, i);
            for j in i + 1..BITS {
                let (mut c, mut o) = (ci, oi);
                flip(&mut c, j);
                flip(&mut o, j);
                let (new_passes, old_passes) = (!refused(&c), passes_abi3(&o));
                tried += 1;
                pairs += usize::from(new_passes);
                old_pairs += usize::from(old_passes);
                // The case: the same high bit (31) of two 32-bit words.
                if i % 32 == 31 && j % 32 == 31 {
                    high += usize::from(new_passes);
                    old_high += usize::from(old_passes);
                }
            }
        }
        println!(
            "{name} (encoding {} bytes): single bits {BITS}: CRC-32C passes {singles}, ABI 3 {old_singles}; \
             pairs {tried}: CRC-32C passes {pairs}, ABI 3 {old_pairs} (of them bit 31 of two words, 8128 pairs: \
             CRC-32C {high}, ABI 3 {old_high})",
            word(&b, TAG / 4 + 1)
        );
        assert_eq!(tried, BITS * (BITS - 1) / 2);
        assert_eq!((singles, pairs), (0, 0), "{name}");
        assert!(
            old_pairs > 0,
            "{name}: these flips no longer show ABI 3's weakness"
        );
    }
}

/// The code itself, from its syndromes (what a single flipped bit changes in "CRC of the data xor the
/// stored CRC"; the code is linear, checked on random errors): every error of up to 3 bits and every burst
/// of up to 32 bits changes the syndrome, so none is ever sealed. Over the 1024-byte block (8160 data
/// bits) CRC-32C has Hamming distance 4 (Koopman's tables: distance 6 only up to 5243 data bits): the
/// 4-bit errors that pass are counted (pairs of bit pairs with one syndrome).
#[test]
fn the_crc_detects_every_error_of_up_to_3_bits_and_every_32_bit_burst() {
    let s = bit_syndromes(&encode(&largest()).unwrap(), 3, 20_000);
    // 1 and 2 bits: every syndrome non-zero and distinct.
    let singles: HashSet<u32> = s.iter().copied().collect();
    assert!(!singles.contains(&0));
    assert_eq!(singles.len(), BITS);
    // 3 bits: no pair's syndrome is a single bit's; 4 bits: no two pairs share a syndrome.
    let mut pairs = Vec::with_capacity(BITS * (BITS - 1) / 2);
    for i in 0..BITS {
        for j in i + 1..BITS {
            let x = s[i] ^ s[j];
            assert!(!singles.contains(&x), "3 bits: {i}, {j} and another");
            pairs.push(x);
        }
    }
    pairs.sort_unstable();
    // Each run of k equal pair syndromes gives k(k − 1)/2 silent 4-bit errors (two pairs of distinct
    // bits: two pairs sharing a bit would be a 2-bit error, which no pair's syndrome matches).
    let mut silent4 = 0usize;
    let mut run = 1usize;
    for w in pairs.windows(2) {
        if w[0] == w[1] {
            run += 1;
        } else {
            silent4 += run * (run - 1) / 2;
            run = 1;
        }
    }
    silent4 += run * (run - 1) / 2;
    let all4 =
        (BITS as f64) * (BITS as f64 - 1.0) * (BITS as f64 - 2.0) * (BITS as f64 - 3.0) / 24.0;
    // Bursts: the syndromes of any 32 consecutive bits are linearly independent, so no error confined to
    // them (bit 8k + i: byte k's bit i, the order the reflected CRC reads) is silent.
    for start in 0..=BITS - 32 {
        assert_eq!(rank(&s[start..start + 32]), 32, "burst from bit {start}");
    }
    // Two bytes: the syndromes of every (byte, non-zero value) are non-zero and distinct.
    let mut by_byte = HashSet::new();
    for k in 0..QUATPROP_STATE_SIZE {
        for v in 1..256usize {
            let x = (0..8)
                .filter(|i| v >> i & 1 == 1)
                .fold(0, |x, i| x ^ s[8 * k + i]);
            assert!(x != 0 && by_byte.insert(x), "byte {k} ^ {v:#x}");
        }
    }
    println!(
        "CRC-32C over {} data bits + 32: {BITS} single, {} pair, all 3-bit errors, {} bursts of 32 bits, \
         {} two-byte errors: none passes; 4-bit errors: {silent4} of {all4:.3e} pass ({:.2e}; 2^-32 = {:.2e})",
        BITS - 32,
        pairs.len(),
        BITS - 31,
        QUATPROP_STATE_SIZE * (QUATPROP_STATE_SIZE - 1) / 2 * 255 * 255 + QUATPROP_STATE_SIZE * 255,
        silent4 as f64 / all4,
        2f64.powi(-32)
    );
    // The distance is 4, not more: some 4-bit errors pass (this length is beyond distance 6's 5243 bits).
    assert!(silent4 > 0);
}

/// The rank over GF(2) of 32-bit vectors.
pub(super) fn rank(v: &[u32]) -> usize {
    let mut basis = [0u32; 32]; // basis[b]: a vector whose highest set bit is b
    let mut r = 0;
    for &x in v {
        let mut x = x;
        while x != 0 {
            let top = 31 - x.leading_zeros() as usize;
            if basis[top] == 0 {
                basis[top] = x;
                r += 1;
                break;
            }
            x ^= basis[top];
        }
    }
    r
}

/// Random damage, seeded: random bytes changed (2 to 16), a run of 2 to 64 bytes overwritten with random
/// bytes, or zeroed, or set to 0xff, and 6 to 32 random bits flipped: 1 000 000 damaged copies of each
/// configuration's state. None passes the CRC (each would with probability 2⁻³²); ABI 3's count beside.
#[test]
fn random_multi_byte_damage_is_refused() {
    const TRIALS: usize = 1_000_000;
    for (name, b) in configurations() {
        let old = encode_abi3(&b);
        let mut rng = Rng(4);
        let (mut passes, mut old_passes, mut tried) = (0, 0, 0);
        while tried < TRIALS {
            // The same damage to both: a mask xored into the block.
            let mut mask: Block = [0; QUATPROP_STATE_SIZE];
            match rng.below(5) {
                0 => {
                    for _ in 0..2 + rng.below(15) {
                        mask[rng.below(QUATPROP_STATE_SIZE)] ^= rng.byte();
                    }
                }
                kind @ 1..=3 => {
                    let len = 2 + rng.below(63);
                    let at = rng.below(QUATPROP_STATE_SIZE - len + 1);
                    for k in at..at + len {
                        let v = match kind {
                            1 => rng.byte(),
                            2 => 0,
                            _ => 0xff,
                        };
                        mask[k] = v ^ b[k];
                    }
                }
                _ => {
                    for _ in 0..6 + rng.below(27) {
                        let i = rng.below(BITS);
                        mask[i / 8] ^= 1 << (i % 8);
                    }
                }
            }
            if mask.iter().all(|&m| m == 0) {
                continue;
            }
            tried += 1;
            let (mut c, mut o) = (b, old);
            for k in 0..QUATPROP_STATE_SIZE {
                c[k] ^= mask[k];
                o[k] ^= mask[k];
            }
            passes += usize::from(!refused(&c));
            old_passes += usize::from(passes_abi3(&o));
        }
        println!("{name}: {TRIALS} random damages: CRC-32C passes {passes}, ABI 3 {old_passes}");
        assert_eq!(passes, 0, "{name}");
    }
}

/// Through the C entry points, on both configurations: every single bit flipped, 4096 random pairs and
/// 1024 random multi-byte changes. A getter, a rate push, a delta push and a burst each return the expected code and
/// leave the bytes as they were (and the burst writes no count).
#[test]
fn the_entry_points_refuse_damaged_states_and_change_nothing() {
    let mut rng = Rng(5);
    let mut calls = 0;
    for (name, b) in configurations() {
        let mut damaged = single_bits_and_pairs(&b, &mut rng, 4096);
        for _ in 0..1024 {
            let mut c = b;
            let at = rng.below(QUATPROP_STATE_SIZE - 8);
            for x in &mut c[at..at + 1 + rng.below(8)] {
                *x ^= 1 | rng.byte();
            }
            damaged.push(c);
        }
        for c in &damaged {
            let want = expected(c);
            let mut s = state(c);
            let mut q = quatprop_quat_t {
                w: 0.0,
                x: 0.0,
                y: 0.0,
                z: 0.0,
            };
            let one = quatprop_sample_t {
                x: 0.1,
                y: 0.2,
                z: 0.3,
                saturated: 0,
            };
            let counts = [[10i16, -20, 30], [11, -21, 31]];
            let mut n = 99;
            // SAFETY: every pointer is to a live local of the right type; `counts` holds 2 triples.
            let got = unsafe {
                [
                    quatprop_get_attitude(&s, &mut q),
                    quatprop_push_rate(&mut s, &one, 1e-3),
                    quatprop_push_delta(&mut s, &one, 1e-3),
                    quatprop_push_counts_burst(&mut s, counts.as_ptr().cast(), 2, &mut n),
                ]
            };
            assert_eq!(got, [want; 4], "{name}");
            assert!(
                bytes(&s) == *c && n == 99,
                "{name}: a refused call changed something"
            );
            calls += 4;
        }
    }
    println!("{calls} calls on damaged states: all refused with their code, none changed a byte");
    assert!(calls > 4 * 2 * BITS);
}

/// A block an older version sealed ("QPF3": ABI 3, "QPF2": ABI 2, tag in word 0) is corrupted, not "never
/// set up"; a zeroed block has no tag.
#[test]
fn an_older_versions_block_is_corrupted() {
    for (name, b) in configurations() {
        let mut old = encode_abi3(&b);
        assert_eq!(
            load(&old).err(),
            Some(S::QUATPROP_CORRUPTED_STATE),
            "{name}"
        );
        old[0..4].copy_from_slice(&OLD_MAGICS[0].to_ne_bytes());
        assert_eq!(
            load(&old).err(),
            Some(S::QUATPROP_CORRUPTED_STATE),
            "{name}"
        );
    }
    let zeroed: Block = [0; QUATPROP_STATE_SIZE];
    assert_eq!(load(&zeroed).err(), Some(S::QUATPROP_NOT_INITIALIZED));
}
