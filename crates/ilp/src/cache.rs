//! The tabu cache (thesis §4.9.1, Algorithm 4.1): a long-term memory of every evaluated
//! cell, so the VNS never traces a cell twice. Because a configuration is always
//! evaluated at its cell's reference point (§4.8), the cell alone is the key.

use crate::space::Cell;
use crate::vns::Verdict;
use invlight_stats::Estimate;
use std::collections::HashMap;

/// What is remembered of a cell drawn before.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Entry {
    /// It was traced.
    Evaluated {
        /// The most precise estimate made of it.
        estimate: Estimate,
        /// What the search decided.
        verdict: Verdict,
    },
    /// The evaluator refused it untraced (it would put an object outside the scene).
    Refused,
}

/// Evaluated cells.
#[derive(Debug, Clone, Default)]
pub struct Cache {
    cells: HashMap<Cell, Entry>,
}

impl Cache {
    /// The entry of a cell already evaluated.
    pub fn get(&self, cell: &Cell) -> Option<&Entry> {
        self.cells.get(cell)
    }

    /// Remembers (or updates) a cell.
    pub fn insert(&mut self, cell: Cell, entry: Entry) {
        self.cells.insert(cell, entry);
    }

    /// Number of cells evaluated.
    pub fn len(&self) -> usize {
        self.cells.len()
    }

    /// Whether no cell was evaluated.
    pub fn is_empty(&self) -> bool {
        self.cells.is_empty()
    }
}
