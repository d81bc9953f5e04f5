#![no_main]
//! EULUMDAT reader: parse; on success photometry, write both formats, re-read, compare; every number finite.

use libfuzzer_sys::fuzz_target;

mod common;

fuzz_target!(|data: &[u8]| common::reader(data, photosolid::model::Format::Ldt));
