//! Benchmarks of what the app calls every frame: forward kinematics (every A_i and T_0i,
//! not a tool-only shortcut) and the geometric Jacobian, for the UR10 and the Panda.
//! Run: `cargo bench -p armlab-core --bench kinematics`.

use std::hint::black_box;

use armlab_core::{ForwardKinematics, SplitMix64, geometric_jacobian_into, preset};
use criterion::{Criterion, criterion_group, criterion_main};
use nalgebra::Matrix6xX;

fn bench_robot(c: &mut Criterion, id: &str) {
    let robot = preset(id).expect("preset");
    let mut rng = SplitMix64::new(1);
    let qs: Vec<Vec<f64>> = (0..64).map(|_| rng.joint_vector(&robot)).collect();
    let mut fk = ForwardKinematics::new(&robot, &qs[0]).expect("q");
    let mut j = Matrix6xX::zeros(robot.dof());
    let mut k = 0;
    c.bench_function(&format!("{id}/fk (all A_i and T_0i)"), |b| {
        b.iter(|| {
            k = (k + 1) & 63;
            fk.update(black_box(&robot), black_box(&qs[k]));
            black_box(&fk);
        })
    });
    fk.update(&robot, &qs[3]);
    c.bench_function(&format!("{id}/jacobian from frames"), |b| {
        b.iter(|| {
            geometric_jacobian_into(black_box(&fk), &mut j);
            black_box(&j);
        })
    });
    c.bench_function(&format!("{id}/fk + jacobian"), |b| {
        b.iter(|| {
            k = (k + 1) & 63;
            fk.update(black_box(&robot), black_box(&qs[k]));
            geometric_jacobian_into(&fk, &mut j);
            black_box(&j);
        })
    });
}

fn benches(c: &mut Criterion) {
    bench_robot(c, "ur10");
    bench_robot(c, "panda");
}

criterion_group!(kinematics, benches);
criterion_main!(kinematics);
