//! The ISR-to-main sample path: SysTick interrupts at 1 kHz synthesize gyro samples (the smoke's coning
//! rates) into a `heapless::spsc::Queue`; `main` drains the queue and propagates with Rk4 + FirstOrder,
//! `step_linear` between consecutive samples. At the end it checks that every sample arrived exactly once,
//! in order (overflows are counted and reported, never silent), and that the attitude is bit-identical to
//! the same samples propagated without the interrupt path (the smoke scene `coning-linear`, which the host
//! snapshot test also checks).
#![no_std]
#![no_main]

use core::cell::{Cell, RefCell};
use cortex_m::peripheral::syst::SystClkSource;
use cortex_m_rt::{entry, exception};
use cortex_m_semihosting::debug::{self, EXIT_FAILURE, EXIT_SUCCESS};
use critical_section::Mutex;
use defmt_semihosting as _;
use heapless::spsc::{Producer, Queue};
use quatprop::scheme::{Method, Rk4};
use quatprop::stabilize::{FirstOrder, Policy};
use quatprop::{Propagator, Quat, Vec3};
use quatprop_firmware::scenes::{bits, run, ConingRates, Scene, DT};

/// Steps to propagate (one more sample than steps).
const STEPS: u32 = 2_000;
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
    if *NEXT > STEPS {
        return;
    }
    let rates = GENERATOR.get_or_insert_with(ConingRates::new);
    let sample = Sample {
        index: *NEXT,
        rate: rates.rate(),
    };
    rates.advance_half();
    rates.advance_half();
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
    cp.SYST.set_clock_source(SystClkSource::Core);
    cp.SYST.set_reload(RELOAD_1KHZ);
    cp.SYST.clear_current();
    cp.SYST.enable_interrupt();
    cp.SYST.enable_counter();

    let mut p = match Propagator::new(Quat::<f32>::IDENTITY, Rk4, FirstOrder) {
        Ok(p) => p,
        Err(_) => fail("propagator"),
    };
    let mut expected_index = 0u32;
    let mut prev: Option<Vec3<f32>> = None;
    let mut out_of_order = 0u32;
    let mut refused = 0u32;
    let mut max_backlog = 0usize;
    while expected_index <= STEPS {
        max_backlog = max_backlog.max(consumer.len());
        match consumer.dequeue() {
            Some(s) => {
                if s.index != expected_index {
                    out_of_order += 1;
                }
                expected_index = s.index + 1;
                if let Some(w0) = prev {
                    refused += p.step_linear(w0, s.rate, DT).is_err() as u32;
                }
                prev = Some(s.rate);
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
    let reference = run(Scene::ConingLinear, Method::Rk4, Policy::FirstOrder, STEPS).q;
    let identical = bits(q.w) == bits(reference.w)
        && bits(q.x) == bits(reference.x)
        && bits(q.y) == bits(reference.y)
        && bits(q.z) == bits(reference.z);
    defmt::println!(
        "isr coning-linear Rk4 FirstOrder {=u32:08x} {=u32:08x} {=u32:08x} {=u32:08x} steps={=u64}",
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
    let ok = overflows == 0
        && out_of_order == 0
        && refused == 0
        && expected_index == STEPS + 1
        && p.steps() == STEPS as u64
        && identical;
    debug::exit(if ok { EXIT_SUCCESS } else { EXIT_FAILURE });
    loop {
        cortex_m::asm::wfi();
    }
}

fn fail(what: &str) -> ! {
    defmt::println!("isr setup failed: {=str}", what);
    debug::exit(EXIT_FAILURE);
    loop {
        cortex_m::asm::wfi();
    }
}

#[panic_handler]
fn panic(_: &core::panic::PanicInfo<'_>) -> ! {
    debug::exit(EXIT_FAILURE);
    loop {
        cortex_m::asm::wfi();
    }
}
