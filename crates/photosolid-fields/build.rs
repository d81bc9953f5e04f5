//! Links the C++ runtime when the `bc6h` feature is on: intel_tex_2's prebuilt
//! ISPC kernels (its ASTC object, in the same archive as the BC6H one) refer to
//! `__gxx_personality_v0`.

fn main() {
    println!("cargo:rerun-if-changed=build.rs");
    let bc6h = std::env::var_os("CARGO_FEATURE_BC6H").is_some();
    let os = std::env::var("CARGO_CFG_TARGET_OS").unwrap_or_default();
    if bc6h && (os == "linux" || os == "android") {
        println!("cargo:rustc-link-lib=stdc++");
    } else if bc6h && os == "macos" {
        println!("cargo:rustc-link-lib=c++");
    }
}
