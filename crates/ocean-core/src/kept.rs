//! Values that depend only on their inputs, made once and handed out again: what a frame's
//! encode asks every frame although the scene did not change (the floor's mesh, the sky table,
//! the near patch). A kept value is the one made anew, bit for bit, so keeping changes no
//! picture.

use std::sync::{Mutex, PoisonError};

/// How many values of one kind are kept: the CPU and GPU frames of a comparison and a few
/// views in turn each ask for their own.
const KEPT: usize = 4;

/// The last [`KEPT`] values of one kind, by key (the oldest let go first).
pub(crate) struct Kept<K, V> {
    list: Mutex<Vec<(K, V)>>,
}

impl<K: PartialEq, V: Clone> Kept<K, V> {
    /// An empty list (for a `static`).
    pub(crate) const fn new() -> Self {
        Self { list: Mutex::new(Vec::new()) }
    }

    /// [`Self::get_or_make`] of a `make` that cannot fail.
    pub(crate) fn get(&self, key: K, make: impl FnOnce() -> V) -> V {
        match self.get_or_make::<std::convert::Infallible>(key, || Ok(make())) {
            Ok(v) => v,
        }
    }

    /// The value kept for `key`, else `make()`, kept (an error is not).
    ///
    /// # Errors
    /// `make`'s.
    pub(crate) fn get_or_make<E>(
        &self,
        key: K,
        make: impl FnOnce() -> Result<V, E>,
    ) -> Result<V, E> {
        // A poisoned list still holds whole values (each is pushed complete).
        let lock = || self.list.lock().unwrap_or_else(PoisonError::into_inner);
        if let Some((_, v)) = lock().iter().find(|(k, _)| *k == key) {
            return Ok(v.clone());
        }
        let value = make()?;
        let mut list = lock();
        if list.len() >= KEPT {
            list.remove(0);
        }
        list.push((key, value.clone()));
        Ok(value)
    }
}
