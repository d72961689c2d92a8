//! A matrix's numbers as text: each entry as the panel draws it, and the whole matrix as
//! plain text, LaTeX or NumPy for the copy buttons. Pure functions of the numbers, apart
//! from the drawing so that they need no egui.

use nalgebra::DMatrix;

use armlab_session::format::fixed;

/// Plain text rows, space-aligned.
pub(super) fn to_plain(m: &DMatrix<f64>, decimals: usize) -> String {
    (0..m.nrows())
        .map(|r| {
            (0..m.ncols())
                .map(|c| format!("{:>w$}", fixed(m[(r, c)], decimals), w = decimals + 7))
                .collect::<Vec<_>>()
                .join(" ")
        })
        .collect::<Vec<_>>()
        .join("\n")
}

/// A LaTeX `bmatrix`.
pub(super) fn to_latex(m: &DMatrix<f64>, decimals: usize) -> String {
    let rows: Vec<String> = (0..m.nrows())
        .map(|r| {
            (0..m.ncols())
                .map(|c| fixed(m[(r, c)], decimals))
                .collect::<Vec<_>>()
                .join(" & ")
        })
        .collect();
    format!(
        "\\begin{{bmatrix}}\n{}\n\\end{{bmatrix}}",
        rows.join(" \\\\\n")
    )
}

/// A NumPy array expression.
pub(super) fn to_numpy(m: &DMatrix<f64>, decimals: usize) -> String {
    let rows: Vec<String> = (0..m.nrows())
        .map(|r| {
            let cells: Vec<String> = (0..m.ncols()).map(|c| fixed(m[(r, c)], decimals)).collect();
            format!("[{}]", cells.join(", "))
        })
        .collect();
    format!("np.array([{}])", rows.join(",\n          "))
}

/// Each entry's text as the table draws it (column-major, as nalgebra stores them).
pub(super) fn number_texts(m: &DMatrix<f64>, decimals: usize) -> Vec<String> {
    m.iter().map(|v| fixed(*v, decimals)).collect()
}
