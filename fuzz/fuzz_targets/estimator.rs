#![no_main]
libfuzzer_sys::fuzz_target!(|data: &[u8]| quatprop_fuzz_checks::estimator::run(data));
