//! IQM build time (the standard decomposition) on grids of growing size — near-linear growth
//! expected — and on the real data's largest surface and tetrahedral mesh when present.

use criterion::{BenchmarkId, Criterion, criterion_group, criterion_main};
use topoplex::Complex;
use topoplex::structures::iqm::Iqm;

/// An n×n grid of squares, each cut into two triangles, with every other row of squares also
/// carrying a fin triangle on its diagonal's edge (non-manifold edges, so joints are tested).
fn grid(n: u32) -> Complex {
    let id = |i: u32, j: u32| i * (n + 1) + j;
    let extra = (n + 1) * (n + 1);
    let mut tris: Vec<Vec<u32>> = Vec::new();
    let mut fin = extra;
    for i in 0..n {
        for j in 0..n {
            let (a, b, c, d) = (id(i, j), id(i, j + 1), id(i + 1, j), id(i + 1, j + 1));
            tris.push(vec![a, b, d]);
            tris.push(vec![a, c, d]);
            if i % 2 == 0 {
                tris.push(vec![a, d, fin]);
                fin += 1;
            }
        }
    }
    let refs: Vec<&[u32]> = tris.iter().map(Vec::as_slice).collect();
    Complex::from_simplices(fin, &refs).unwrap()
}

fn bench(c: &mut Criterion) {
    let mut g = c.benchmark_group("iqm_build_grid");
    for n in [50u32, 100, 200, 400] {
        let complex = grid(n);
        g.bench_with_input(BenchmarkId::from_parameter(n * n), &complex, |b, cx| {
            b.iter(|| Iqm::build(cx).unwrap())
        });
    }
    g.finish();
    let data = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../shared/data");
    for file in ["surfaces/bunny00.off", "tetrahedral/slug.mesh"] {
        if let Ok(complex) = Complex::from_path(&data.join(file)) {
            c.bench_function(&format!("iqm_build {file}"), |b| {
                b.iter(|| Iqm::build(&complex).unwrap())
            });
        }
    }
}

criterion_group! {
    name = benches;
    config = Criterion::default().sample_size(10);
    targets = bench
}
criterion_main!(benches);
