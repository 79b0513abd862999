//! Where a problem in a scenario file is: the keys and array indices from the document root to
//! the value, which the loader turns into a line number. Shared by the loader and the checks
//! derived from several fields.

/// One step of the way from the document root to a value, to find the line a problem is on.
#[derive(Debug, Clone, Copy)]
pub(crate) enum Seg<'a> {
    Key(&'a str),
    Index(usize),
}

/// A problem found after parsing: where it is (keys and array indices) and what it is.
pub(crate) type Problem = (Vec<Seg<'static>>, String);
