//! Per-file parse time over the corpus (development aid): slowest files first.
use std::time::Instant;
fn main() {
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../shared/corpus");
    let mut files = vec![];
    let mut stack = vec![root.clone()];
    while let Some(d) = stack.pop() {
        for e in std::fs::read_dir(&d).into_iter().flatten().flatten() {
            let p = e.path();
            if p.is_dir() {
                stack.push(p)
            } else if photosolid::model::Format::from_extension(&p).is_some() {
                files.push(p)
            }
        }
    }
    let mut t: Vec<(f64, String, usize)> = files
        .iter()
        .map(|p| {
            let b = std::fs::read(p).unwrap();
            let f = photosolid::model::Format::from_extension(p).unwrap();
            let t0 = Instant::now();
            for _ in 0..20 {
                let _ = photosolid::formats::parse(&b, p, f, &Default::default());
            }
            (
                t0.elapsed().as_secs_f64() / 20.0 * 1e3,
                p.strip_prefix(&root).unwrap().display().to_string(),
                b.len(),
            )
        })
        .collect();
    t.sort_by(|a, b| b.0.total_cmp(&a.0));
    for x in t.iter().take(8) {
        println!("{:8.3} ms {:8} B {}", x.0, x.2, x.1);
    }
}
