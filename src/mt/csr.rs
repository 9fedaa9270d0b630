//! Compressed sparse rows: lists such as "the predecessors of fragment f", one flat array
//! each, so the DAG costs no per-fragment allocation.
//!
//! When every row is a contiguous range of consecutive items, the items are not stored:
//! the offsets alone describe the rows.

/// Row `i` holds items `offsets[i]..offsets[i + 1]` of `items`, or, when `items` is
/// `None`, the numbers in that range themselves.
#[derive(Clone, Debug, Default, PartialEq)]
pub(crate) struct Csr {
    offsets: Vec<u32>,
    items: Option<Vec<u32>>,
}

impl Csr {
    /// Rows `0..rows`, filled from `(row, item)` pairs; within a row, items keep the order
    /// in which the pairs came (so rows built from arcs in pool order are sorted).
    pub(crate) fn from_pairs(rows: usize, pairs: impl Iterator<Item = (u32, u32)> + Clone) -> Csr {
        let mut offsets = vec![0u32; rows + 1];
        for (r, _) in pairs.clone() {
            offsets[r as usize + 1] += 1;
        }
        for i in 0..rows {
            offsets[i + 1] += offsets[i];
        }
        let mut fill = offsets.clone();
        let mut items = vec![0u32; offsets[rows] as usize];
        for (r, item) in pairs {
            let slot = &mut fill[r as usize];
            items[*slot as usize] = item;
            *slot += 1;
        }
        let implicit = items.iter().enumerate().all(|(k, &x)| x as usize == k);
        Csr {
            offsets,
            items: (!implicit).then_some(items),
        }
    }

    #[inline]
    pub(crate) fn row(&self, i: usize) -> Row<'_> {
        let (a, b) = (self.offsets[i] as usize, self.offsets[i + 1] as usize);
        match &self.items {
            Some(items) => Row::Listed(&items[a..b]),
            None => Row::Range(a as u32..b as u32),
        }
    }

    pub(crate) fn heap_bytes(&self) -> usize {
        (self.offsets.capacity() + self.items.as_ref().map_or(0, |v| v.capacity())) * 4
    }
}

/// One row: a slice of items or a range of numbers.
#[derive(Clone, Debug)]
pub enum Row<'a> {
    Listed(&'a [u32]),
    Range(std::ops::Range<u32>),
}

impl Row<'_> {
    pub fn len(&self) -> usize {
        match self {
            Row::Listed(s) => s.len(),
            Row::Range(r) => r.len(),
        }
    }

    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    pub fn iter(&self) -> RowIter<'_> {
        match self {
            Row::Listed(s) => RowIter::Listed(s.iter()),
            Row::Range(r) => RowIter::Range(r.clone()),
        }
    }
}

impl<'a> IntoIterator for Row<'a> {
    type Item = u32;
    type IntoIter = RowIter<'a>;
    fn into_iter(self) -> RowIter<'a> {
        match self {
            Row::Listed(s) => RowIter::Listed(s.iter()),
            Row::Range(r) => RowIter::Range(r),
        }
    }
}

/// Iterator over a [`Row`]'s items.
#[derive(Clone, Debug)]
pub enum RowIter<'a> {
    Listed(std::slice::Iter<'a, u32>),
    Range(std::ops::Range<u32>),
}

impl Iterator for RowIter<'_> {
    type Item = u32;
    #[inline]
    fn next(&mut self) -> Option<u32> {
        match self {
            RowIter::Listed(i) => i.next().copied(),
            RowIter::Range(r) => r.next(),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn contiguous_rows_store_no_items() {
        let c = Csr::from_pairs(3, [(0, 0), (0, 1), (2, 2)].into_iter());
        assert!(c.items.is_none());
        assert_eq!(c.row(0).iter().collect::<Vec<_>>(), vec![0, 1]);
        assert!(c.row(1).is_empty());
        assert_eq!(c.row(2).iter().collect::<Vec<_>>(), vec![2]);
        let d = Csr::from_pairs(2, [(1, 0), (0, 1)].into_iter());
        assert!(d.items.is_some());
        assert_eq!(d.row(0).iter().collect::<Vec<_>>(), vec![1]);
        assert_eq!(d.row(1).into_iter().collect::<Vec<_>>(), vec![0]);
    }
}
