#![no_main]
libfuzzer_sys::fuzz_target!(|data: &[u8]| quatprop_fuzz_checks::calibration::run(data));
