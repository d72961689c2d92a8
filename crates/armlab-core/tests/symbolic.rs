//! docs/kinematics.md §13: the symbolic A_i and T_0i of every preset evaluate to the
//! numeric matrices, read as the textbooks write them, and say which joints they depend on.
// On wasm the tests are wasm_bindgen_tests, which clippy does not treat as tests.
#![cfg_attr(
    target_arch = "wasm32",
    allow(clippy::unwrap_used, clippy::expect_used)
)]

#[cfg(target_arch = "wasm32")]
use wasm_bindgen_test::wasm_bindgen_test as test;

use crate::common;

use armlab_core::symbolic::{EntryText, MAX_SHOWN_TERMS, number, symbolic_chain};
use armlab_core::{Convention, ForwardKinematics, preset};

#[test]
fn every_symbolic_entry_of_every_preset_matches_the_numbers_at_1000_random_q() {
    for (id, robot) in common::all_presets() {
        let chain = symbolic_chain(&robot);
        assert_eq!(chain.link_transforms.len(), robot.dof(), "{id}");
        assert_eq!(chain.base_from_frames.len(), robot.dof(), "{id}");
        let mut rng = common::rng(11);
        let mut worst: f64 = 0.0;
        for _ in 0..1000 {
            let q = rng.joint_vector(&robot);
            let fk = ForwardKinematics::new(&robot, &q).unwrap();
            for i in 0..robot.dof() {
                let a = chain.link_transforms[i].eval(&q) - fk.link_transforms[i].to_homogeneous();
                let t =
                    chain.base_from_frames[i].eval(&q) - fk.base_from_frames[i].to_homogeneous();
                worst = worst.max(a.abs().max()).max(t.abs().max());
            }
            let tool = chain.base_from_tool.eval(&q) - fk.base_from_tool.to_homogeneous();
            worst = worst.max(tool.abs().max());
        }
        assert!(worst <= 1e-9, "{id}: largest difference {worst}");
    }
}

fn plain(e: &armlab_core::symbolic::Expr) -> String {
    match e.text() {
        EntryText::Shown { plain, .. } => plain,
        EntryText::TooLong { terms } => format!("too long ({terms})"),
    }
}

#[test]
fn the_rrr_t03_reads_as_in_the_course() {
    let robot = preset("rrr").unwrap();
    let chain = symbolic_chain(&robot);
    let t = &chain.base_from_frames[2].entries;
    assert_eq!(plain(&t[0][3]), "c1(222.1 c2 + 136.2 c23)");
    assert_eq!(plain(&t[1][3]), "s1(222.1 c2 + 136.2 c23)");
    assert_eq!(plain(&t[2][3]), "100.9 + 222.1 s2 + 136.2 s23");
    // The rotation: parallel axes 2 and 3 collapse into sums, zero entries cleared.
    assert_eq!(plain(&t[0][0]), "c1 c23");
    assert_eq!(plain(&t[0][1]), "-c1 s23");
    assert_eq!(plain(&t[0][2]), "s1");
    assert_eq!(plain(&t[2][0]), "s23");
    assert_eq!(plain(&t[2][2]), "0");
    assert_eq!(plain(&t[3][3]), "1");
    match t[0][3].text() {
        EntryText::Shown { latex, .. } => {
            assert_eq!(latex, "c_{1}\\left(222.1 c_{2} + 136.2 c_{23}\\right)")
        }
        EntryText::TooLong { .. } => panic!("the RRR's x is short"),
    }
}

#[test]
fn the_a_matrices_substitute_constants_and_offsets() {
    // UR10 standard: θ2 has an offset of π, so A_2 holds −c2 and −s2; 612.9 becomes a
    // coefficient; 90° twists give exact 0 and ±1.
    let robot = preset("ur10-standard").unwrap();
    let chain = symbolic_chain(&robot);
    let a1 = &chain.link_transforms[0].entries;
    assert_eq!(plain(&a1[0][0]), "c1");
    assert_eq!(plain(&a1[0][1]), "0");
    assert_eq!(plain(&a1[0][2]), "s1");
    assert_eq!(plain(&a1[2][1]), "1");
    assert_eq!(plain(&a1[2][3]), "128");
    let a2 = &chain.link_transforms[1].entries;
    assert_eq!(plain(&a2[0][0]), "-c2");
    assert_eq!(plain(&a2[0][3]), "612.9 c2");
    // A prismatic joint: the Stanford arm's d3 is the variable, θ3 = −90° a constant.
    let stanford = preset("stanford").unwrap();
    let a3 = &symbolic_chain(&stanford).link_transforms[2].entries;
    assert_eq!(plain(&a3[2][3]), "d3");
    assert_eq!(plain(&a3[0][0]), "0");
    assert_eq!(plain(&a3[1][0]), "-1");
    assert_eq!(plain(&a3[0][3]), "0");
    assert_eq!(plain(&a3[1][3]), "-0.0203");
    // Modified DH (UR10): A_2 = Rot_x(90°)·Rot_z(θ2).
    let ur10 = preset("ur10").unwrap();
    assert_eq!(ur10.convention, Convention::Modified);
    let a2 = &symbolic_chain(&ur10).link_transforms[1].entries;
    assert_eq!(plain(&a2[1][2]), "-1");
    assert_eq!(plain(&a2[2][0]), "s2");
}

#[test]
fn the_ur10_t06_collapses_its_parallel_axes() {
    use armlab_core::symbolic::Factor;
    for id in ["ur10", "ur10-standard"] {
        let robot = preset(id).unwrap();
        let t = &symbolic_chain(&robot).base_from_frames[5].entries;
        // Axes 2–4 are parallel: the rotation names θ2, θ3, θ4 only through θ2+θ3+θ4.
        for row in &t[..3] {
            for e in &row[..3] {
                for (factors, _) in e.terms() {
                    for f in factors {
                        if let Factor::Cos(a) | Factor::Sin(a) = f {
                            let joints: Vec<usize> = a.parts().iter().map(|p| p.0).collect();
                            assert!(
                                joints.iter().all(|j| !(1..=3).contains(j))
                                    || joints == vec![1, 2, 3],
                                "{id}: {} in {}",
                                e.plain(),
                                e.plain()
                            );
                        }
                    }
                }
            }
        }
        // The third row, as the UR10 report writes it; at q = 0 it gives r33 = 0 and
        // z = 128 + 115.7 = 243.7 (SPEC §1.2).
        assert_eq!(plain(&t[2][0]), "c234 s6 + s234 c5 c6", "{id}");
        assert_eq!(plain(&t[2][2]), "s234 s5", "{id}");
        assert_eq!(
            plain(&t[2][3]),
            "128 + 612.9 s2 + 571.6 s23 + 115.7 c234 + 92.2 s234 s5",
            "{id}"
        );
    }
}

#[test]
fn entries_name_the_joints_they_depend_on() {
    let robot = preset("rrr").unwrap();
    let chain = symbolic_chain(&robot);
    let t = &chain.base_from_frames[2].entries;
    assert_eq!(t[0][3].joints(), vec![0, 1, 2]);
    assert_eq!(t[2][3].joints(), vec![1, 2]);
    assert!(t[0][2].depends_on(0) && !t[0][2].depends_on(1));
    assert!(t[3][3].joints().is_empty());
    assert_eq!(chain.link_transforms[1].joint_bits(), 0b010);
}

#[test]
fn long_entries_report_their_size() {
    // The Panda's T_07 has the longest entries of the presets.
    let robot = preset("panda").unwrap();
    let t = &symbolic_chain(&robot).base_from_frames[6];
    let longest = t.max_terms();
    assert!(longest > MAX_SHOWN_TERMS, "{longest} terms");
    let too_long = t
        .entries
        .iter()
        .flatten()
        .filter(|e| matches!(e.text(), EntryText::TooLong { terms } if terms > MAX_SHOWN_TERMS))
        .count();
    assert!(too_long > 0);
}

#[test]
fn coefficients_print_as_people_write_them() {
    assert_eq!(number(128.0), "128");
    assert_eq!(number(222.1), "222.1");
    assert_eq!(number(0.15005), "0.15005");
    assert_eq!(number(612.9 * 1.0000000000001), "612.9");
    assert_eq!(number(2.0), "2");
}
