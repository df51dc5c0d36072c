//! Work spread over the cores with rayon (feature `parallel`, on by default), or the same calls
//! run in order on one thread where it is off (a WebAssembly page has one thread per worker):
//! the physics is written once, with rayon's names, and gives the same results either way
//! (every parallel loop here keeps its items' order).

#[cfg(feature = "parallel")]
pub(crate) use rayon::join;
#[cfg(feature = "parallel")]
pub(crate) use rayon::prelude::*;

#[cfg(not(feature = "parallel"))]
pub(crate) use sequential::*;

/// How many threads the parallel loops are spread over: rayon's pool, or 1 without it.
pub fn current_num_threads() -> usize {
    #[cfg(feature = "parallel")]
    return rayon::current_num_threads();
    #[cfg(not(feature = "parallel"))]
    return 1;
}

#[cfg(not(feature = "parallel"))]
mod sequential {
    /// Runs `a`, then `b`.
    pub(crate) fn join<A, B, RA, RB>(a: A, b: B) -> (RA, RB)
    where
        A: FnOnce() -> RA,
        B: FnOnce() -> RB,
    {
        let ra = a();
        (ra, b())
    }

    /// `par_iter` as a plain iterator.
    pub(crate) trait IntoParallelRefIterator<'a> {
        /// The iterator.
        type Iter: Iterator;
        /// The items in order.
        fn par_iter(&'a self) -> Self::Iter;
    }

    impl<'a, T: 'a> IntoParallelRefIterator<'a> for [T] {
        type Iter = std::slice::Iter<'a, T>;
        fn par_iter(&'a self) -> Self::Iter {
            self.iter()
        }
    }

    impl<'a, T: 'a> IntoParallelRefIterator<'a> for Vec<T> {
        type Iter = std::slice::Iter<'a, T>;
        fn par_iter(&'a self) -> Self::Iter {
            self.iter()
        }
    }

    /// `par_chunks` as plain chunks.
    pub(crate) trait ParallelSlice<T> {
        /// Chunks of `n` items, in order.
        fn par_chunks(&self, n: usize) -> std::slice::Chunks<'_, T>;
    }

    impl<T> ParallelSlice<T> for [T] {
        fn par_chunks(&self, n: usize) -> std::slice::Chunks<'_, T> {
            self.chunks(n)
        }
    }

    /// `par_chunks_mut` as plain chunks.
    pub(crate) trait ParallelSliceMut<T> {
        /// Mutable chunks of `n` items, in order.
        fn par_chunks_mut(&mut self, n: usize) -> std::slice::ChunksMut<'_, T>;
    }

    impl<T> ParallelSliceMut<T> for [T] {
        fn par_chunks_mut(&mut self, n: usize) -> std::slice::ChunksMut<'_, T> {
            self.chunks_mut(n)
        }
    }

    /// Rayon's iterator adaptors that plain iterators lack.
    pub(crate) trait ParallelIterator: Iterator + Sized {
        /// No splitting to bound: the iterator itself.
        fn with_min_len(self, _min: usize) -> Self {
            self
        }

        /// No splitting to force: the iterator itself.
        fn with_max_len(self, _max: usize) -> Self {
            self
        }

        /// One state made by `init`, used for every item in order.
        fn for_each_init<S>(self, init: impl Fn() -> S, mut f: impl FnMut(&mut S, Self::Item)) {
            let mut state = init();
            self.for_each(|x| f(&mut state, x));
        }

        /// The items into `v`, replacing what it held.
        fn collect_into_vec(self, v: &mut Vec<Self::Item>) {
            v.clear();
            v.extend(self);
        }
    }

    impl<I: Iterator> ParallelIterator for I {}
}
