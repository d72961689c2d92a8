//! The symbolic matrices as the matrices panel shows them: each entry's text and the
//! joints it depends on, each matrix's LaTeX. Flat and written as text, so that the page
//! can have them computed by its lazily loaded module and keep the algebra out of its
//! first load. The text is split on control characters, not JSON: serde_json's reader of
//! these types cost the page's wasm more than a third of what the move saved.

use super::robot::Robot;
use super::symbolic::{EntryText, Expr, SymbolicMatrix, symbolic_chain};
use super::symbolic_jacobian::{SymbolicJacobian, in_tool_frame, symbolic_jacobian};

/// One entry of a [`SymbolicTable`].
#[derive(Debug, Clone, PartialEq)]
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
#[derive(Debug, Clone, PartialEq)]
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
#[derive(Debug, Clone, PartialEq)]
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

/// Between the fields of a table in [`SymbolicTables::to_text`] (the unit separator: no
/// entry's text or LaTeX holds it).
const FIELD: char = '\u{1f}';
/// Between the tables (the record separator).
const TABLE: char = '\u{1e}';

impl SymbolicTables {
    /// The tables as text: each table's rows, columns and LaTeX, then per entry its joints,
    /// its plain text and its LaTeX (a too long entry: no text, and its term count), the
    /// fields apart by the unit separator (U+001F); the tables (A_i, T_0i, J in the base
    /// frame, J in the tool frame) apart by the record separator (U+001E).
    pub fn to_text(&self) -> String {
        let tables = self.link_transforms.iter().chain(&self.base_from_frames);
        let tables = tables.chain([&self.jacobian_base, &self.jacobian_tool]);
        let mut out = String::new();
        for (i, t) in tables.enumerate() {
            if i > 0 {
                out.push(TABLE);
            }
            out += &format!("{}{FIELD}{}{FIELD}{}", t.rows, t.cols, t.latex);
            for e in &t.entries {
                let (plain, latex) = match &e.text {
                    EntryText::Shown { plain, latex } => (plain.as_str(), latex.clone()),
                    EntryText::TooLong { terms } => ("", terms.to_string()),
                };
                out += &format!("{FIELD}{}{FIELD}{plain}{FIELD}{latex}", e.joints);
            }
        }
        out
    }

    /// The tables from [`SymbolicTables::to_text`]'s text; `None` when it is not such text.
    pub fn from_text(text: &str) -> Option<Self> {
        let mut tables = text
            .split(TABLE)
            .map(SymbolicTable::from_text)
            .collect::<Option<Vec<_>>>()?;
        if tables.len() % 2 != 0 {
            return None;
        }
        let jacobian_tool = tables.pop()?;
        let jacobian_base = tables.pop()?;
        let base_from_frames = tables.split_off(tables.len() / 2);
        Some(SymbolicTables {
            link_transforms: tables,
            base_from_frames,
            jacobian_base,
            jacobian_tool,
        })
    }
}

impl SymbolicTable {
    /// One table of [`SymbolicTables::to_text`]'s text.
    fn from_text(text: &str) -> Option<Self> {
        let mut fields = text.split(FIELD);
        let rows = fields.next()?.parse().ok()?;
        let cols = fields.next()?.parse().ok()?;
        let latex = fields.next()?.to_string();
        let mut entries = Vec::new();
        while let Some(joints) = fields.next() {
            let joints = joints.parse().ok()?;
            let (plain, latex) = (fields.next()?, fields.next()?);
            let text = if plain.is_empty() {
                EntryText::TooLong {
                    terms: latex.parse().ok()?,
                }
            } else {
                EntryText::Shown {
                    plain: plain.to_string(),
                    latex: latex.to_string(),
                }
            };
            entries.push(TableEntry { text, joints });
        }
        (entries.len() == rows * cols).then_some(SymbolicTable {
            rows,
            cols,
            entries,
            latex,
        })
    }
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
// On wasm the tests are wasm_bindgen_tests (run in Node like the other core tests), which
// clippy does not treat as tests.
#[cfg_attr(
    target_arch = "wasm32",
    allow(clippy::unwrap_used, clippy::expect_used)
)]
mod tests {
    use super::*;
    #[cfg(target_arch = "wasm32")]
    use wasm_bindgen_test::wasm_bindgen_test as test;

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
            // Through text and back unchanged.
            let back = SymbolicTables::from_text(&tables.to_text());
            assert_eq!(back.as_ref(), Some(&tables), "{id}");
        }
    }

    #[test]
    fn a_too_long_entry_and_a_robot_without_joints_go_through_text_and_bad_text_does_not() {
        let mut tables = symbolic_tables(&crate::preset("ur10").expect("preset"));
        tables.jacobian_tool.entries[0].text = EntryText::TooLong { terms: 31 };
        let back = SymbolicTables::from_text(&tables.to_text()).expect("reads back");
        assert_eq!(
            back.jacobian_tool.entries[0].text,
            EntryText::TooLong { terms: 31 }
        );
        assert_eq!(back, tables);
        let mut none = tables.clone();
        none.link_transforms.clear();
        none.base_from_frames.clear();
        for j in [&mut none.jacobian_base, &mut none.jacobian_tool] {
            j.cols = 0;
            j.entries.clear();
        }
        assert_eq!(SymbolicTables::from_text(&none.to_text()), Some(none));
        let text = tables.to_text();
        // A table short of an entry, one table missing, not a number, nothing.
        let cut = text.rfind(FIELD).expect("fields");
        let cut = text[..cut].rfind(FIELD).expect("fields");
        let cut = text[..cut].rfind(FIELD).expect("fields");
        assert_eq!(SymbolicTables::from_text(&text[..cut]), None);
        let first = text.find(TABLE).expect("tables");
        assert_eq!(SymbolicTables::from_text(&text[first + 1..]), None);
        assert_eq!(SymbolicTables::from_text(&text.replacen('4', "x", 1)), None);
        assert_eq!(SymbolicTables::from_text(""), None);
    }
}
