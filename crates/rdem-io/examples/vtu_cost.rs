//! Times one `dump atom/vtk` snapshot of 8550 particles (the bench/in.dense size).
use rdem::{DVec3, NewParticle, Particles};
use rdem_io::{format_atom_vtu, XmlEncoding};
fn main() {
    let mut p = Particles::new();
    for k in 0..8550u64 {
        let s = |a: f64| (k as f64 * a).sin();
        let x = DVec3::new(
            0.05 + 0.04 * s(0.1),
            0.05 + 0.04 * s(0.7),
            0.05 + 0.04 * s(1.3),
        );
        let np = NewParticle::at(x, 0.0025 + (k % 7) as f64 * 1e-5, 2500.0)
            .with_tag(k + 1)
            .with_v(DVec3::new(0.1 / (k + 1) as f64, -0.3, 1e-3 * k as f64));
        let i = p.add_local(&np).unwrap();
        p.f[i] = DVec3::new(s(0.3), s(0.5), s(0.9));
        p.omega[i] = DVec3::new(s(1.1), s(1.7), 10.0 * s(2.3));
        p.v[i] = DVec3::new(s(3.1), s(3.7), s(4.3));
    }
    let sel: Vec<usize> = (0..p.nlocal()).collect();
    for enc in [
        XmlEncoding::Ascii,
        XmlEncoding::Binary,
        XmlEncoding::Zlib,
        XmlEncoding::Lz4,
    ] {
        let t = std::time::Instant::now();
        let mut len = 0;
        for _ in 0..10 {
            len = format_atom_vtu(&p, &sel, 0, enc).len();
        }
        let dt = t.elapsed().as_secs_f64() / 10.0;
        let t = std::time::Instant::now();
        let s = format_atom_vtu(&p, &sel, 0, enc);
        rdem_io::write_atomic(std::path::Path::new("/tmp/vtu_cost.vtu"), s.as_bytes()).unwrap();
        let dw = t.elapsed().as_secs_f64();
        println!(
            "{enc:?}: format {:.2} ms, format+write {:.2} ms, {} bytes",
            dt * 1e3,
            dw * 1e3,
            len
        );
    }
}
