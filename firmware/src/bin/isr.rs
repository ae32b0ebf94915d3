//! The ISR-to-main sample path: SysTick interrupts at 1 kHz synthesize gyro samples (the smoke's coning
//! rates) into a `heapless::spsc::Queue`; `main` drains the queue and pushes every sample into the
//! recommended configuration (ExpMap + History + FirstOrder). At the end it checks that every sample arrived
//! exactly once, in order (overflows are counted and reported, never silent), and that the attitude is
//! bit-identical to the same samples propagated without the interrupt path (the smoke scene
//! `coning-history`, which the host snapshot test also checks).
#![no_std]
#![no_main]

use core::cell::{Cell, RefCell};
use cortex_m::peripheral::syst::SystClkSource;
use cortex_m_rt::{entry, exception};
use critical_section::Mutex;
use heapless::spsc::{Producer, Queue};
use quatprop::input::History;
use quatprop::scheme::{ExpMap, SchemeKind};
use quatprop::stabilize::{FirstOrder, StabilizerKind};
use quatprop::{GyroSample, Propagator, Quat, Vec3};
use quatprop_firmware::exit::{exit, fail};
use quatprop_firmware::scenes::{bits, run, Config, ConingRates, Scene, DT, ISR_STEPS};

/// SysTick reload for a 1 kHz interrupt on the 25 MHz mps2 core clock.
const RELOAD_1KHZ: u32 = 25_000 - 1;

#[derive(Clone, Copy)]
struct Sample {
    index: u32,
    rate: Vec3<f32>,
}

static PRODUCER: Mutex<RefCell<Option<Producer<'static, Sample>>>> = Mutex::new(RefCell::new(None));
static OVERFLOWS: Mutex<Cell<u32>> = Mutex::new(Cell::new(0));

#[exception]
fn SysTick() {
    static mut GENERATOR: Option<ConingRates> = None;
    static mut NEXT: u32 = 0;
    if *NEXT > ISR_STEPS {
        return;
    }
    let rates = GENERATOR.get_or_insert_with(ConingRates::new);
    if *NEXT > 0 {
        rates.advance();
    }
    let sample = Sample {
        index: *NEXT,
        rate: rates.rate(),
    };
    *NEXT += 1;
    critical_section::with(|cs| {
        let lost = match PRODUCER.borrow_ref_mut(cs).as_mut() {
            Some(p) => p.enqueue(sample).is_err(),
            None => true,
        };
        if lost {
            let o = OVERFLOWS.borrow(cs);
            o.set(o.get() + 1);
        }
    });
}

#[entry]
fn main() -> ! {
    let Some(queue) = cortex_m::singleton!(: Queue<Sample, 64> = Queue::new()) else {
        fail("queue")
    };
    let (producer, mut consumer) = queue.split();
    critical_section::with(|cs| *PRODUCER.borrow_ref_mut(cs) = Some(producer));

    let Some(mut cp) = cortex_m::Peripherals::take() else {
        fail("peripherals")
    };
    let Ok(mut p) = Propagator::new(Quat::<f32>::IDENTITY, ExpMap, History::new(), FirstOrder)
    else {
        fail("propagator")
    };
    cp.SYST.set_clock_source(SystClkSource::Core);
    cp.SYST.set_reload(RELOAD_1KHZ);
    cp.SYST.clear_current();
    cp.SYST.enable_interrupt();
    cp.SYST.enable_counter();

    let mut expected_index = 0u32;
    let mut out_of_order = 0u32;
    let mut refused = 0u32;
    let mut max_backlog = 0usize;
    while expected_index <= ISR_STEPS {
        max_backlog = max_backlog.max(consumer.len());
        match consumer.dequeue() {
            Some(s) => {
                if s.index != expected_index {
                    out_of_order += 1;
                }
                expected_index = s.index + 1;
                refused += p.push(GyroSample::new(s.rate), DT).is_err() as u32;
            }
            None => {
                let lost = critical_section::with(|cs| OVERFLOWS.borrow(cs).get());
                if lost > 0 {
                    break;
                }
                cortex_m::asm::wfi();
            }
        }
    }
    cp.SYST.disable_interrupt();
    let overflows = critical_section::with(|cs| OVERFLOWS.borrow(cs).get());
    let q = p.attitude();
    let direct = Config::Post(SchemeKind::ExpMap, StabilizerKind::FirstOrder);
    let reference = run(Scene::ConingHistory, direct, ISR_STEPS).q;
    let identical = bits(q.w) == bits(reference.w)
        && bits(q.x) == bits(reference.x)
        && bits(q.y) == bits(reference.y)
        && bits(q.z) == bits(reference.z);
    defmt::println!(
        "isr coning-history ExpMap FirstOrder {=u32:08x} {=u32:08x} {=u32:08x} {=u32:08x} steps={=u64}",
        bits(q.w),
        bits(q.x),
        bits(q.y),
        bits(q.z),
        p.steps()
    );
    defmt::println!(
        "isr samples={=u32} overflows={=u32} out_of_order={=u32} refused={=u32} max_backlog={=usize} identical_to_direct={=bool}",
        expected_index,
        overflows,
        out_of_order,
        refused,
        max_backlog,
        identical
    );
    exit(
        overflows == 0
            && out_of_order == 0
            && refused == 0
            && expected_index == ISR_STEPS + 1
            && p.steps() == u64::from(ISR_STEPS)
            && identical,
    )
}
