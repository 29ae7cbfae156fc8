use decimate::decimate::{decimate_scene, Params, Target};
use decimate::mesh::{measure, shapes, Scene};
fn main() {
    for m in [shapes::test005(), shapes::test006()] {
        for p in [60.0, 80.0, 90.0, 100.0] {
            let v0 = measure::volume(&m);
            let mut s = Scene {
                models: vec![m.clone()],
            };
            let r = decimate_scene(
                &mut s,
                &Params {
                    target: Target::RemovePercent(p),
                    ..Params::default()
                },
                &mut |_| {},
            );
            let a = &s.models[0];
            let rims: Vec<usize> = [(2.0f32, 0.0f32), (2.0, 5.0), (1.5, 0.0), (1.5, 5.0)]
                .iter()
                .map(|&(rad, z)| {
                    a.positions
                        .iter()
                        .filter(|p| {
                            (p.truncate().length() - rad).abs() < 1e-4 && (p.z - z).abs() < 1e-4
                        })
                        .count()
                })
                .collect();
            println!(
                "{} -p {p}: {} v {} t, vol ratio {:.4}, max err {:.4}, rims {:?}, full {}",
                m.name,
                a.positions.len(),
                a.triangles.len(),
                measure::volume(a) / v0,
                r.models[0].max_error,
                rims,
                r.fully_decimated()
            );
        }
    }
}
