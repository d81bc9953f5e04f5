#![no_main]
//! IES reader, parse only (plain and with the repair option): no panic, every stored number finite.

use libfuzzer_sys::fuzz_target;

mod common;

fuzz_target!(|data: &[u8]| common::parse_only(data, photosolid::model::Format::Ies));
