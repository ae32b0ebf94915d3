//! Host half of the firmware checks: runs the firmware's own scene code (`scenes`), the README's quick start
//! (`quickstart`) and the embedded-hal driver demo (`device_model`, `driver_demo`), compiled for the host, and
//! asserts that every result is bit-identical to `firmware/expected/*.txt`. `firmware/check-boards` runs the
//! same code on each QEMU board and diffs its output against the same files. IEEE binary32 on both sides, no
//! FMA contraction, the same libm code: any difference is a bug to explain.
//!
//! Run by `firmware/check-host`, which also writes the expected files: `QUATPROP_BLESS=1 firmware/check-host`
//! (then run `firmware/check-boards`).

use crate::{device_model, driver_demo, quickstart, scenes};
use embedded_hal::spi::{Operation, SpiDevice};
use embedded_hal_mock::eh1::spi::{Mock as SpiMock, Transaction as SpiTransaction};
use scenes::{bits, run, Config, Outcome, Scene};
use std::path::PathBuf;

fn expected_path(name: &str) -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("expected")
        .join(name)
}

/// Compares `got` with `firmware/expected/<name>`, or writes it there under `QUATPROP_BLESS=1`.
fn check_or_bless(name: &str, got: &str) {
    let path = expected_path(name);
    if std::env::var_os("QUATPROP_BLESS").is_some_and(|v| v != "0") {
        std::fs::write(&path, got).expect("write the expected file");
        return;
    }
    let want = std::fs::read_to_string(&path)
        .unwrap_or_else(|e| panic!("{}: {e} (QUATPROP_BLESS=1 writes it)", path.display()));
    for (i, (g, w)) in got.lines().zip(want.lines()).enumerate() {
        assert_eq!(
            g,
            w,
            "{name} line {}: host differs from the expected file",
            i + 1
        );
    }
    assert_eq!(
        got.lines().count(),
        want.lines().count(),
        "{name}: line count"
    );
    assert_eq!(got, want, "{name}");
}

fn quat_bits(o: &Outcome) -> String {
    format!(
        "{:08x} {:08x} {:08x} {:08x}",
        bits(o.q.w),
        bits(o.q.x),
        bits(o.q.y),
        bits(o.q.z)
    )
}

/// What `firmware/src/bin/smoke.rs` prints for `steps` steps per run.
fn smoke_output(steps: u32) -> String {
    let mut out = format!("smoke steps={steps}\n");
    let mut runs = 0;
    for scene in Scene::ALL {
        for c in Config::all() {
            let o = run(scene, c, steps);
            assert_eq!(o.refused, 0, "{} {c:?} refused samples", scene.name());
            assert_eq!(o.steps, u64::from(steps));
            out += &format!(
                "{} {} {} {} steps={} corrections={} refused={}\n",
                scene.name(),
                c.scheme_name(),
                c.stabilizer_name(),
                quat_bits(&o),
                o.steps,
                o.corrections,
                o.refused
            );
            runs += 1;
        }
    }
    assert_eq!(runs, Scene::ALL.len() * Config::COUNT);
    for scene in [Scene::Constant, Scene::ConingHistory] {
        let (q, n) = scenes::run_fixed(scene, steps).expect("no sample refused");
        assert_eq!(n, u64::from(steps));
        out += &format!(
            "fixed {} Q30Propagator {:08x} {:08x} {:08x} {:08x} steps={n}\n",
            scene.name(),
            q[0] as u32,
            q[1] as u32,
            q[2] as u32,
            q[3] as u32
        );
    }
    out + "smoke done\n"
}

#[test]
fn smoke_matches_the_firmware_bit_for_bit() {
    check_or_bless("smoke.txt", &smoke_output(scenes::STEPS));
}

#[test]
fn smoke_soft_float_matches_the_firmware_bit_for_bit() {
    check_or_bless("smoke-soft.txt", &smoke_output(scenes::STEPS_SOFT));
}

#[test]
fn isr_path_result_equals_the_direct_propagation() {
    let o = run(
        Scene::ConingHistory,
        Config::Post(
            quatprop::scheme::SchemeKind::ExpMap,
            quatprop::stabilize::StabilizerKind::FirstOrder,
        ),
        scenes::ISR_STEPS,
    );
    assert_eq!(o.refused, 0);
    // The firmware also prints max_backlog=N (emulator timing): check-boards drops it before comparing.
    let got = format!(
        "isr coning-history ExpMap FirstOrder {} steps={}\n\
         isr samples={} overflows=0 out_of_order=0 refused=0 identical_to_direct=true\n",
        quat_bits(&o),
        o.steps,
        scenes::ISR_STEPS + 1
    );
    check_or_bless("isr.txt", &got);
}

#[test]
fn quickstart_matches_the_firmware_bit_for_bit() {
    let mut attitude = quickstart::Attitude::new().expect("starts");
    for burst in scenes::quickstart_fifo() {
        attitude.on_fifo(&burst);
    }
    let (q, refused) = attitude.attitude();
    assert_eq!(refused, 0, "raw counts are always finite");
    assert!(q.norm_error().abs() < 1e-6);
    let got = format!(
        "quickstart samples={} {:08x} {:08x} {:08x} {:08x} refused={}\nquickstart done\n",
        scenes::QUICKSTART_BURSTS * scenes::QUICKSTART_BURST as u32,
        bits(q.w),
        bits(q.x),
        bits(q.y),
        bits(q.z),
        refused
    );
    check_or_bless("quickstart.txt", &got);
}

#[test]
fn estimator_matches_the_firmware_bit_for_bit() {
    use crate::estimator_run::{len, line, run};
    let mut got = format!("estimator samples={}\n", len());
    let mut last = (0, 0);
    run(|s| {
        let b = line(s);
        got += &format!(
            "estimator {} {:08x} {:08x} {:08x} {:08x} bias {:08x} {:08x} {:08x} sigma {:08x} updates={} rejected={}\n",
            s.samples, b[0], b[1], b[2], b[3], b[4], b[5], b[6], b[7], s.updates, s.rejected
        );
        last = (s.samples, s.updates);
    })
    .expect("the estimator takes every sample of the excerpt");
    assert_eq!(last.0, len());
    assert!(last.1 > 0, "accelerometer updates were applied");
    got += "estimator done\n";
    check_or_bless("estimator.txt", &got);
}

/// The driver demo's SPI bus on the host: the scripted chip, every transaction recorded as an
/// `embedded-hal-mock` expectation (and as raw bytes, to check the FIFO reads against the script).
struct Recorder {
    model: device_model::Icm42688Model,
    expectations: Vec<SpiTransaction<u8>>,
    transfers: Vec<(Vec<u8>, Vec<u8>)>,
}

impl embedded_hal::spi::ErrorType for Recorder {
    type Error = device_model::ModelError;
}

impl SpiDevice for Recorder {
    fn transaction(&mut self, operations: &mut [Operation<'_, u8>]) -> Result<(), Self::Error> {
        self.expectations.push(SpiTransaction::transaction_start());
        for op in operations.iter_mut() {
            match op {
                Operation::TransferInPlace(buf) => {
                    let sent = buf.to_vec();
                    self.model
                        .transaction(&mut [Operation::TransferInPlace(buf)])?;
                    self.expectations.push(SpiTransaction::transfer_in_place(
                        sent.clone(),
                        buf.to_vec(),
                    ));
                    self.transfers.push((sent, buf.to_vec()));
                }
                Operation::Write(buf) => {
                    self.model.transaction(&mut [Operation::Write(buf)])?;
                    self.expectations
                        .push(SpiTransaction::write_vec(buf.to_vec()));
                }
                _ => return Err(device_model::ModelError),
            }
        }
        self.expectations.push(SpiTransaction::transaction_end());
        Ok(())
    }
}

/// What `firmware/src/bin/driver.rs` prints.
fn driver_output(o: &driver_demo::Outcome, transactions: u32) -> String {
    format!(
        "driver icm426xx samples={} bursts={} rails={} ticks={} {:08x} {:08x} {:08x} {:08x} refused={}\n\
         driver spi-transactions={transactions}\ndriver done\n",
        o.samples,
        o.bursts,
        o.rails,
        o.ticks,
        bits(o.q.w),
        bits(o.q.x),
        bits(o.q.y),
        bits(o.q.z),
        o.refused
    )
}

#[test]
fn driver_demo_matches_the_firmware_bit_for_bit_over_the_model_and_over_embedded_hal_mock() {
    use device_model::{counts, packet, BURSTS, PACKET, SAMPLES, TICKS};
    // 1. The driver over the scripted chip, recording the bus.
    let recorder = Recorder {
        model: device_model::Icm42688Model::new(),
        expectations: Vec::new(),
        transfers: Vec::new(),
    };
    let (o, recorder) = driver_demo::run(recorder, 10_000).expect("the driver reads the script");
    assert_eq!(
        recorder.model.served(),
        (SAMPLES, true),
        "every sample served and read"
    );
    assert_eq!(o.samples as usize, SAMPLES);
    assert_eq!(o.refused, 0);
    assert_eq!(o.rails, 1, "the one railed sample is flagged");
    let ticks: u32 = (0..SAMPLES).map(|i| u32::from(TICKS[i & 1])).sum();
    assert_eq!(o.ticks, ticks, "every packet's timestamp");
    // The burst lengths the script gives, in order.
    let mut lengths = Vec::new();
    let mut left = SAMPLES;
    for &b in BURSTS.iter().cycle() {
        if left == 0 {
            break;
        }
        lengths.push(b.min(left));
        left -= b.min(left);
    }
    assert_eq!(o.bursts as usize, lengths.len());

    // 2. The FIFO reads on the bus are the script's packets, burst by burst (INT_STATUS | 0x80 starts one).
    let fifo_reads: Vec<&(Vec<u8>, Vec<u8>)> = recorder
        .transfers
        .iter()
        .filter(|(sent, _)| sent[0] == 0xAD)
        .collect();
    assert_eq!(fifo_reads.len(), lengths.len());
    let mut i = 0;
    for ((_, got), &len) in fifo_reads.iter().zip(&lengths) {
        let count = len * PACKET;
        assert_eq!(&got[2..4], &[(count >> 8) as u8, count as u8], "FIFO count");
        let want: Vec<u8> = (i..i + len).flat_map(packet).collect();
        assert_eq!(&got[4..], &want[..], "burst at sample {i}");
        i += len;
    }

    // 3. The same counts fed straight to the quick start in the same bursts: the driver changed nothing.
    let mut direct = quickstart::Attitude::new().expect("starts");
    let mut at = 0;
    for &len in &lengths {
        let burst: Vec<[i16; 3]> = (at..at + len).map(counts).collect();
        direct.on_fifo(&burst);
        at += len;
    }
    let (q, _) = direct.attitude();
    assert_eq!(
        [q.w, q.x, q.y, q.z].map(bits),
        [o.q.w, o.q.x, o.q.y, o.q.z].map(bits),
        "driver path vs raw counts"
    );
    assert!(q.norm_error().abs() < 1e-6);

    // 4. The same driver over embedded-hal-mock, expecting exactly the recorded transactions.
    let mock = SpiMock::new(&recorder.expectations);
    let (replayed, mut mock) = driver_demo::run(mock, 10_000).expect("the driver reads the mock");
    mock.done();
    assert_eq!(
        driver_output(&replayed, recorder.model.transactions()),
        driver_output(&o, recorder.model.transactions()),
        "embedded-hal-mock vs the model"
    );

    check_or_bless(
        "driver.txt",
        &driver_output(&o, recorder.model.transactions()),
    );
}
