//! Named attribute columns (per vertex or per tet), structure-of-arrays like the geometry:
//! one `Vec<f64>` per column, `components` values per element (1 for a scalar, 3 for a
//! vector, up to 9 for a tensor). Columns are permuted, appended to and compacted together
//! with the elements they belong to, through the methods here.

/// One named column of f64 values.
#[derive(Clone, Debug, PartialEq)]
pub struct Attribute {
    pub name: String,
    /// Values per element (1..=9).
    pub components: usize,
    /// `components × element count` values, element-major.
    pub values: Vec<f64>,
}

impl Attribute {
    /// A column; `None` when `components` is 0 or above 9, or `values` is not a whole
    /// number of elements.
    pub fn new(name: impl Into<String>, components: usize, values: Vec<f64>) -> Option<Attribute> {
        ((1..=9).contains(&components) && values.len() % components == 0).then(|| Attribute {
            name: name.into(),
            components,
            values,
        })
    }

    /// Number of elements this column has values for.
    pub fn len(&self) -> usize {
        self.values.len() / self.components
    }

    pub fn is_empty(&self) -> bool {
        self.values.is_empty()
    }

    /// The values of element `i`.
    pub fn get(&self, i: usize) -> &[f64] {
        &self.values[i * self.components..(i + 1) * self.components]
    }
}

/// The attribute columns of one kind of element (all vertices, or all tets).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Attributes {
    columns: Vec<Attribute>,
}

impl Attributes {
    pub fn new() -> Attributes {
        Attributes::default()
    }

    pub fn is_empty(&self) -> bool {
        self.columns.is_empty()
    }

    pub fn iter(&self) -> std::slice::Iter<'_, Attribute> {
        self.columns.iter()
    }

    pub fn get(&self, name: &str) -> Option<&Attribute> {
        self.columns.iter().find(|c| c.name == name)
    }

    pub fn get_mut(&mut self, name: &str) -> Option<&mut Attribute> {
        self.columns.iter_mut().find(|c| c.name == name)
    }

    /// Adds `column`, replacing a column of the same name.
    pub fn insert(&mut self, column: Attribute) {
        match self.columns.iter_mut().find(|c| c.name == column.name) {
            Some(c) => *c = column,
            None => self.columns.push(column),
        }
    }

    pub fn remove(&mut self, name: &str) -> Option<Attribute> {
        let i = self.columns.iter().position(|c| c.name == name)?;
        Some(self.columns.remove(i))
    }

    /// The first column whose length is not `n`, if any.
    pub fn mismatched(&self, n: usize) -> Option<&Attribute> {
        self.columns.iter().find(|c| c.len() != n)
    }

    /// The columns, to change values in place (their lengths must stay whole elements).
    pub(crate) fn iter_mut(&mut self) -> std::slice::IterMut<'_, Attribute> {
        self.columns.iter_mut()
    }

    /// Makes room for `n` more elements in every column.
    pub fn reserve(&mut self, n: usize) {
        for c in &mut self.columns {
            c.values.reserve(n * c.components);
        }
    }

    /// Maps the memory of every column's spare capacity now ([`super::touch_spare`]).
    pub(crate) fn touch_spare(&mut self) {
        for c in &mut self.columns {
            super::touch_spare(&mut c.values);
        }
    }

    /// How many elements every column can still take without reallocating (`None`: no
    /// column).
    pub(crate) fn spare(&self) -> Option<usize> {
        self.columns
            .iter()
            .map(|c| (c.values.capacity() - c.values.len()) / c.components)
            .min()
    }

    /// Keeps the first `n` elements of every column (an edit given back).
    pub(crate) fn truncate(&mut self, n: usize) {
        for c in &mut self.columns {
            c.values.truncate(n * c.components);
        }
    }

    /// Appends to every column a copy of the values of element `src`.
    pub fn push_copy(&mut self, src: usize) {
        for c in &mut self.columns {
            let k = c.components;
            c.values.extend_from_within(src * k..(src + 1) * k);
        }
    }

    /// Appends to every column a copy of the values of each element of `src`, in order
    /// (the bulk form of [`push_copy`](Self::push_copy)).
    pub fn push_copies(&mut self, src: &[u32]) {
        for c in &mut self.columns {
            let k = c.components;
            let old = c.values.len();
            // Grown once, then filled by a gather from the old rows (a push per value
            // checked the capacity every time: 4% of a live model's scalpel step).
            c.values.resize(old + src.len() * k, 0.0);
            let (rows, new) = c.values.split_at_mut(old);
            if k == 1 {
                for (x, &i) in new.iter_mut().zip(src) {
                    *x = rows[i as usize];
                }
            } else {
                for (x, &i) in new.chunks_exact_mut(k).zip(src) {
                    let i = i as usize * k;
                    x.copy_from_slice(&rows[i..i + k]);
                }
            }
        }
    }

    /// Appends `n` rows of zeros to every column (rows of elements with no data of their
    /// own, such as the ghost tets of an MT).
    pub fn push_zeros(&mut self, n: usize) {
        for c in &mut self.columns {
            let len = c.values.len() + n * c.components;
            c.values.resize(len, 0.0);
        }
    }

    /// Appends to every column `(1 - t) × a + t × b`: the value at a point a fraction `t`
    /// of the way from element `a` to element `b` (new vertices on edges).
    pub fn push_lerp(&mut self, a: usize, b: usize, t: f64) {
        for c in &mut self.columns {
            let k = c.components;
            for j in 0..k {
                let v = (1.0 - t) * c.values[a * k + j] + t * c.values[b * k + j];
                c.values.push(v);
            }
        }
    }

    /// Appends to every column the weighted sum `Σ w_i × value(e_i)` (new vertices inside
    /// faces; weights are barycentric and sum to 1).
    pub fn push_combination(&mut self, elements: &[(usize, f64)]) {
        for c in &mut self.columns {
            let k = c.components;
            for j in 0..k {
                let v = elements.iter().map(|&(e, w)| w * c.values[e * k + j]).sum();
                c.values.push(v);
            }
        }
    }

    /// Keeps only the elements listed in `keep`, in that order (compaction, extraction).
    pub fn select(&self, keep: &[usize]) -> Attributes {
        Attributes {
            columns: self
                .columns
                .iter()
                .map(|c| {
                    let k = c.components;
                    let mut values = Vec::with_capacity(keep.len() * k);
                    for &i in keep {
                        values.extend_from_slice(&c.values[i * k..(i + 1) * k]);
                    }
                    Attribute {
                        name: c.name.clone(),
                        components: k,
                        values,
                    }
                })
                .collect(),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rows_follow_their_elements() {
        let mut a = Attributes::new();
        a.insert(Attribute::new("t", 1, vec![0.0, 10.0]).unwrap());
        a.insert(Attribute::new("v", 3, vec![1.0, 2.0, 3.0, 4.0, 5.0, 6.0]).unwrap());
        a.push_lerp(0, 1, 0.25);
        a.push_copy(0);
        assert_eq!(a.get("t").unwrap().values, vec![0.0, 10.0, 2.5, 0.0]);
        a.push_copies(&[1, 2]);
        assert_eq!(
            a.get("t").unwrap().values,
            vec![0.0, 10.0, 2.5, 0.0, 10.0, 2.5]
        );
        assert_eq!(a.get("v").unwrap().get(2), &[1.75, 2.75, 3.75]);
        assert_eq!(a.get("v").unwrap().get(4), &[4.0, 5.0, 6.0]);
        assert_eq!(a.get("v").unwrap().get(5), &[1.75, 2.75, 3.75]);
        let s = a.select(&[3, 1]);
        assert_eq!(s.get("t").unwrap().values, vec![0.0, 10.0]);
        assert!(s.mismatched(2).is_none());
        assert!(Attribute::new("bad", 2, vec![1.0]).is_none());
        assert!(Attribute::new("bad", 0, vec![]).is_none());
    }

    #[test]
    fn spare_is_the_fullest_columns_room() {
        let mut a = Attributes::new();
        assert_eq!(a.spare(), None);
        let mut values = Vec::with_capacity(12);
        values.extend([1.0, 2.0, 3.0]);
        a.insert(Attribute::new("v", 3, values).unwrap());
        let mut values = Vec::with_capacity(2);
        values.push(0.0);
        a.insert(Attribute::new("t", 1, values).unwrap());
        assert_eq!(a.spare(), Some(1));
        a.reserve(5);
        assert!(a.spare().is_some_and(|n| n >= 5));
    }
}
