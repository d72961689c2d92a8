//! The symbolic matrices as the matrices panel shows them: each entry's text and the
//! joints it depends on, each matrix's LaTeX. Flat and serialisable, so that the page can
//! have them computed by its lazily loaded module and keep the algebra out of its first
//! load.

use serde::{Deserialize, Serialize};

use super::robot::Robot;
use super::symbolic::{EntryText, Expr, SymbolicMatrix, symbolic_chain};
use super::symbolic_jacobian::{SymbolicJacobian, in_tool_frame, symbolic_jacobian};

/// One entry of a [`SymbolicTable`].
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct TableEntry {
    /// Its text, or its size when it is too long to show.
    pub text: EntryText,
    /// The joints (from 0) it depends on, as a bit set ([`Expr::joint_bits`]).
    pub joints: u64,
}

impl TableEntry {
    fn of(e: &Expr) -> Self {
        TableEntry {
            text: e.text(),
            joints: e.joint_bits(),
        }
    }
}

/// One symbolic matrix: its entries row by row and its LaTeX.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct SymbolicTable {
    /// Rows (4 for a transform, 6 for a Jacobian).
    pub rows: usize,
    /// Columns (4 for a transform, n for a Jacobian).
    pub cols: usize,
    /// The entries, row `r` column `c` at `r * cols + c`.
    pub entries: Vec<TableEntry>,
    /// The whole matrix as LaTeX, every entry in full.
    pub latex: String,
}

impl SymbolicTable {
    /// The entry in row `r`, column `c` (`None` outside the matrix).
    pub fn entry(&self, r: usize, c: usize) -> Option<&TableEntry> {
        (r < self.rows && c < self.cols)
            .then(|| self.entries.get(r * self.cols + c))
            .flatten()
    }

    /// Whether the entry in row `r`, column `c` depends on joint `j` (from 0).
    pub fn depends_on(&self, r: usize, c: usize, j: usize) -> bool {
        j < 64 && self.entry(r, c).is_some_and(|e| e.joints & (1 << j) != 0)
    }

    fn transform(m: &SymbolicMatrix) -> Self {
        SymbolicTable {
            rows: 4,
            cols: 4,
            entries: m.entries.iter().flatten().map(TableEntry::of).collect(),
            latex: m.latex(),
        }
    }

    fn jacobian(j: &SymbolicJacobian) -> Self {
        let cols = j.columns.len();
        SymbolicTable {
            rows: 6,
            cols,
            entries: (0..6 * cols)
                .map(|i| TableEntry::of(j.entry(i / cols, i % cols)))
                .collect(),
            latex: j.latex(),
        }
    }
}

/// Every symbolic matrix the matrices panel shows for a robot.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct SymbolicTables {
    /// A_i for i = 1..n.
    pub link_transforms: Vec<SymbolicTable>,
    /// T_0i for i = 1..n.
    pub base_from_frames: Vec<SymbolicTable>,
    /// J in the base frame.
    pub jacobian_base: SymbolicTable,
    /// J in the tool frame.
    pub jacobian_tool: SymbolicTable,
}

/// The symbolic A_i, T_0i and J (base and tool frame) of `robot` as the panel shows them.
pub fn symbolic_tables(robot: &Robot) -> SymbolicTables {
    let chain = symbolic_chain(robot);
    let base = symbolic_jacobian(robot, &chain);
    let tool = in_tool_frame(robot, &chain, &base);
    SymbolicTables {
        link_transforms: chain
            .link_transforms
            .iter()
            .map(SymbolicTable::transform)
            .collect(),
        base_from_frames: chain
            .base_from_frames
            .iter()
            .map(SymbolicTable::transform)
            .collect(),
        jacobian_base: SymbolicTable::jacobian(&base),
        jacobian_tool: SymbolicTable::jacobian(&tool),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Each table entry says what the expression says: its text, its joints (one by one)
    /// and the matrix's LaTeX.
    fn same(table: &SymbolicTable, rows: usize, cols: usize, expr: impl Fn(usize, usize) -> Expr) {
        assert_eq!(
            (table.rows, table.cols, table.entries.len()),
            (rows, cols, rows * cols)
        );
        for r in 0..rows {
            for c in 0..cols {
                let e = expr(r, c);
                let entry = table.entry(r, c).expect("entry inside the matrix");
                assert_eq!(entry.text, e.text(), "({r}, {c})");
                assert_eq!(entry.joints, e.joint_bits(), "({r}, {c})");
                for j in 0..8 {
                    assert_eq!(
                        table.depends_on(r, c, j),
                        e.depends_on(j),
                        "({r}, {c}) on {j}"
                    );
                }
            }
        }
        assert!(table.entry(rows, 0).is_none() && table.entry(0, cols).is_none());
    }

    #[test]
    fn the_tables_say_what_the_expressions_say_for_every_preset() {
        for id in crate::preset_ids() {
            let robot = crate::preset(id).expect("preset");
            let tables = symbolic_tables(&robot);
            let chain = symbolic_chain(&robot);
            let base = symbolic_jacobian(&robot, &chain);
            let tool = in_tool_frame(&robot, &chain, &base);
            assert_eq!(tables.link_transforms.len(), robot.dof(), "{id}");
            assert_eq!(tables.base_from_frames.len(), robot.dof(), "{id}");
            for (table, m) in tables.link_transforms.iter().zip(&chain.link_transforms) {
                same(table, 4, 4, |r, c| m.entries[r][c].clone());
                assert_eq!(table.latex, m.latex(), "{id}");
            }
            for (table, m) in tables.base_from_frames.iter().zip(&chain.base_from_frames) {
                same(table, 4, 4, |r, c| m.entries[r][c].clone());
                assert_eq!(table.latex, m.latex(), "{id}");
            }
            let n = robot.dof();
            same(&tables.jacobian_base, 6, n, |r, c| base.entry(r, c).clone());
            same(&tables.jacobian_tool, 6, n, |r, c| tool.entry(r, c).clone());
            assert_eq!(tables.jacobian_base.latex, base.latex(), "{id}");
            assert_eq!(tables.jacobian_tool.latex, tool.latex(), "{id}");
            // Through JSON and back unchanged.
            let json = serde_json::to_string(&tables).expect("serialises");
            let back: SymbolicTables = serde_json::from_str(&json).expect("deserialises");
            assert_eq!(back, tables, "{id}");
        }
    }
}
