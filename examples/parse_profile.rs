//! Parse one file many times (development aid for profiling).
fn main() {
    let p = std::env::args().nth(1).unwrap();
    let n: usize = std::env::args().nth(2).map_or(500, |s| s.parse().unwrap());
    let b = std::fs::read(&p).unwrap();
    let f = photosolid::model::Format::from_extension(std::path::Path::new(&p)).unwrap();
    let t0 = std::time::Instant::now();
    for _ in 0..n {
        std::hint::black_box(photosolid::formats::parse(&b, std::path::Path::new(&p), f, &Default::default()).unwrap());
    }
    let s = t0.elapsed().as_secs_f64() / n as f64;
    println!("{:.3} ms/parse, {:.1} MB/s", s * 1e3, b.len() as f64 / s / 1e6);
}
