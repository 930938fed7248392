//! Many Cauchy products of one order at once, element-wise.
//!
//! A Taylor recursion's work is its Cauchy products, `(a b)ₖ = Σⱼ₌₀ᵏ aⱼ bₖ₋ⱼ` (Moore 1966,
//! ch. 11; Jorba & Zou 2005, §3). Summed one product at a time, each is a short dot product
//! with one operand reversed, which vectorizes poorly. [`CrossSums`] keeps, per order `j`, the
//! factors of `M` products side by side (lane `i` of every array belongs to product `i`), so
//! that order `k` of all of them is one pass over `j` of element-wise multiply–adds on arrays of
//! `M`, which the compiler turns into the widest vectors the target has. Each lane has the form
//! of a cross product's component, `Σⱼ uⱼ wₖ₋ⱼ − u′ⱼ w′ₖ₋ⱼ`; a lane whose second factors are
//! zero is a plain product.

use super::SeriesScalar;

/// The factors of `M` Cauchy sums per order, each lane `Σⱼ firstⱼ wₖ₋ⱼ − secondⱼ w′ₖ₋ⱼ`
/// (module doc). Grown once to the largest order asked ([`CrossSums::reserve`]); no
/// allocation after that.
#[derive(Debug, Clone)]
pub struct CrossSums<S, const M: usize> {
    first: Vec<[S; M]>,
    second: Vec<[S; M]>,
    w_first: Vec<[S; M]>,
    w_second: Vec<[S; M]>,
}

impl<S, const M: usize> Default for CrossSums<S, M> {
    fn default() -> Self {
        Self {
            first: Vec::new(),
            second: Vec::new(),
            w_first: Vec::new(),
            w_second: Vec::new(),
        }
    }
}

impl<S: SeriesScalar, const M: usize> CrossSums<S, M> {
    /// Room for orders `0 ..= order`.
    pub fn reserve(&mut self, order: usize) {
        if self.first.len() <= order {
            for v in [
                &mut self.first,
                &mut self.second,
                &mut self.w_first,
                &mut self.w_second,
            ] {
                v.resize(order + 1, [S::ZERO; M]);
            }
        }
    }

    /// The factors of order `j`: `first` and `second` as they enter at index `j` of a sum,
    /// `w_first` and `w_second` as they enter at index `k − j`.
    ///
    /// # Panics
    /// If `j` is beyond the order [`CrossSums::reserve`] made room for.
    #[inline(always)]
    pub fn set(
        &mut self,
        j: usize,
        first: [S; M],
        second: [S; M],
        w_first: [S; M],
        w_second: [S; M],
    ) {
        self.set_left(j, first, second);
        self.set_right(j, w_first, w_second);
    }

    /// The factors of order `j` that enter at index `j` of a sum (a recursion whose order-`k`
    /// `w` follows from the order-`k` sum sets the two sides apart).
    ///
    /// # Panics
    /// If `j` is beyond the order [`CrossSums::reserve`] made room for.
    #[inline(always)]
    pub fn set_left(&mut self, j: usize, first: [S; M], second: [S; M]) {
        self.first[j] = first;
        self.second[j] = second;
    }

    /// The factors of order `j` that enter at index `k − j` of a sum.
    ///
    /// # Panics
    /// If `j` is beyond the order [`CrossSums::reserve`] made room for.
    #[inline(always)]
    pub fn set_right(&mut self, j: usize, w_first: [S; M], w_second: [S; M]) {
        self.w_first[j] = w_first;
        self.w_second[j] = w_second;
    }

    /// Order `k` of every lane, over `j = from ..= k` (`from` is 0 or 1): [`CrossSums::middle`]
    /// then [`CrossSums::finish`].
    ///
    /// # Panics
    /// If order `k` has not been [`CrossSums::set`], or `from > 1`.
    #[inline(always)]
    #[must_use]
    pub fn sum(&self, from: usize, k: usize) -> [S; M] {
        self.finish(k, from, self.middle(k))
    }

    /// The terms `j = 1 ..= k − 1` of order `k` of every lane, `Σⱼ firstⱼ ⊙ w_firstₖ₋ⱼ −
    /// secondⱼ ⊙ w_secondₖ₋ⱼ` (zero for `k ≤ 1`): the part whose factors are all of orders
    /// below `k`, known before any order-`k` factor is. A recursion computes it first for every
    /// stage of an order, so that the stages' sums run side by side and only their end terms
    /// ([`CrossSums::finish`]) wait on each other. Two partial sums, over odd and over even `j`
    /// (each term `u w − u′ w′` added in turn, `j` upwards), halve the chain of dependent
    /// additions; their sum is the result.
    ///
    /// # Panics
    /// If an order below `k` has not been [`CrossSums::set`].
    #[inline(always)]
    #[must_use]
    pub fn middle(&self, k: usize) -> [S; M] {
        let mut odd = [S::ZERO; M];
        let mut even = [S::ZERO; M];
        if k < 2 {
            return odd;
        }
        let ups = self.first[1..k].iter().zip(&self.second[1..k]);
        let downs = self.w_first[1..k].iter().zip(&self.w_second[1..k]).rev();
        let mut terms = ups.zip(downs);
        while let Some(((u1, u2), (w1, w2))) = terms.next() {
            for i in 0..M {
                odd[i] += u1[i] * w1[i] - u2[i] * w2[i];
            }
            let Some(((u1, u2), (w1, w2))) = terms.next() else {
                break;
            };
            for i in 0..M {
                even[i] += u1[i] * w1[i] - u2[i] * w2[i];
            }
        }
        for i in 0..M {
            odd[i] += even[i];
        }
        odd
    }

    /// Order `k` of every lane from its [`CrossSums::middle`]: the term `j = k` added, then (with
    /// `from = 0`) the term `j = 0`; at `k = 0` the one term `j = 0` (none with `from = 1`).
    /// The end terms hold the order-`k` factors, which [`CrossSums::set`] must have given.
    ///
    /// # Panics
    /// If order `k` has not been set, or `from > 1`.
    #[inline(always)]
    #[must_use]
    pub fn finish(&self, k: usize, from: usize, middle: [S; M]) -> [S; M] {
        self.finish_with(
            k,
            from,
            middle,
            [
                &self.first[k],
                &self.second[k],
                &self.w_first[k],
                &self.w_second[k],
            ],
        )
    }

    /// [`CrossSums::finish`] with the order-`k` factors given (`[first, second, w_first,
    /// w_second]`, as [`CrossSums::set`] takes them) rather than read back: a recursion that has
    /// them at hand keeps them out of memory on its critical path. Order 0's are read.
    ///
    /// # Panics
    /// If order 0 has not been set (for `k > 0`), or `from > 1`.
    #[inline(always)]
    #[must_use]
    pub fn finish_with(
        &self,
        k: usize,
        from: usize,
        middle: [S; M],
        [first, second, w_first, w_second]: [&[S; M]; 4],
    ) -> [S; M] {
        assert!(from <= 1, "a Cauchy sum starts at j = 0 or 1, not {from}");
        let mut sums = middle;
        if k == 0 {
            if from == 0 {
                add_term(&mut sums, first, second, w_first, w_second);
            }
        } else {
            add_term(
                &mut sums,
                first,
                second,
                &self.w_first[0],
                &self.w_second[0],
            );
            if from == 0 {
                add_term(
                    &mut sums,
                    &self.first[0],
                    &self.second[0],
                    w_first,
                    w_second,
                );
            }
        }
        sums
    }
}

impl<S: SeriesScalar, const M: usize> CrossSums<S, M> {
    /// [`CrossSums::set_left`] of the `R` lanes from `at` only: several stages of a recursion
    /// share one `CrossSums`, so that their [`CrossSums::middle`] is one element-wise pass over
    /// the widest vectors, and each stage sets its own lanes as its factors become known.
    ///
    /// # Panics
    /// If `j` is beyond the order [`CrossSums::reserve`] made room for, or `at + R > M`.
    #[inline(always)]
    pub fn set_left_lanes<const R: usize>(
        &mut self,
        j: usize,
        at: usize,
        first: [S; R],
        second: [S; R],
    ) {
        self.first[j][at..at + R].copy_from_slice(&first);
        self.second[j][at..at + R].copy_from_slice(&second);
    }

    /// [`CrossSums::set_right`] of the `R` lanes from `at` only ([`CrossSums::set_left_lanes`]).
    ///
    /// # Panics
    /// If `j` is beyond the order [`CrossSums::reserve`] made room for, or `at + R > M`.
    #[inline(always)]
    pub fn set_right_lanes<const R: usize>(
        &mut self,
        j: usize,
        at: usize,
        w_first: [S; R],
        w_second: [S; R],
    ) {
        self.w_first[j][at..at + R].copy_from_slice(&w_first);
        self.w_second[j][at..at + R].copy_from_slice(&w_second);
    }

    /// [`CrossSums::finish_with`] of the `R` lanes from `at` only, from the middle of all `M`
    /// ([`CrossSums::set_left_lanes`]): the same operations, lane by lane, as
    /// [`CrossSums::finish_with`] on those lanes.
    ///
    /// # Panics
    /// If order 0 has not been set (for `k > 0`), `from > 1`, or `at + R > M`.
    #[inline(always)]
    #[must_use]
    pub fn finish_lanes<const R: usize>(
        &self,
        k: usize,
        from: usize,
        at: usize,
        middle: &[S; M],
        [first, second, w_first, w_second]: [&[S; R]; 4],
    ) -> [S; R] {
        assert!(from <= 1, "a Cauchy sum starts at j = 0 or 1, not {from}");
        let lanes = |v: &[S; M]| -> [S; R] { std::array::from_fn(|i| v[at + i]) };
        let mut sums = lanes(middle);
        if k == 0 {
            if from == 0 {
                add_term(&mut sums, first, second, w_first, w_second);
            }
        } else {
            let (w1, w2) = (lanes(&self.w_first[0]), lanes(&self.w_second[0]));
            add_term(&mut sums, first, second, &w1, &w2);
            if from == 0 {
                let (u1, u2) = (lanes(&self.first[0]), lanes(&self.second[0]));
                add_term(&mut sums, &u1, &u2, w_first, w_second);
            }
        }
        sums
    }
}

/// `sums += u1 ⊙ w1 − u2 ⊙ w2`, lane by lane.
#[inline(always)]
fn add_term<S: SeriesScalar, const M: usize>(
    sums: &mut [S; M],
    u1: &[S; M],
    u2: &[S; M],
    w1: &[S; M],
    w2: &[S; M],
) {
    for i in 0..M {
        sums[i] += u1[i] * w1[i] - u2[i] * w2[i];
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Against the products summed one at a time: the series of `a b − c d` and of `a b` for
    /// the exponential series `aⱼ = 1/j!` (the product of two is `2ᵏ/k!`).
    #[test]
    fn lanes_are_the_cauchy_products_of_their_factors() {
        let order = 12;
        let fact = |j: usize| (1..=j).fold(1.0, |p, i| p * i as f64);
        let a: Vec<f64> = (0..=order).map(|j| 1.0 / fact(j)).collect();
        let b: Vec<f64> = (0..=order)
            .map(|j| (-1.0f64).powi(j as i32) / fact(j))
            .collect();
        let mut sums = CrossSums::<f64, 3>::default();
        sums.reserve(order);
        for j in 0..=order {
            // lane 0: e^t e^t = e^{2t}; lane 1: e^t e^{−t} − e^{−t} e^{−t} = 1 − e^{−2t};
            // lane 2: e^t e^{−t} = 1.
            sums.set(
                j,
                [a[j], a[j], a[j]],
                [0.0, b[j], 0.0],
                [a[j], b[j], b[j]],
                [0.0, b[j], 0.0],
            );
        }
        for k in 0..=order {
            let s = sums.sum(0, k);
            let two = 2f64.powi(k as i32) / fact(k);
            let one = if k == 0 { 1.0 } else { 0.0 };
            let minus_two = (-2f64).powi(k as i32) / fact(k);
            assert!(
                (s[0] - two).abs() <= 1e-15 * two,
                "k = {k}: {} vs {two}",
                s[0]
            );
            assert!(
                (s[1] - (one - minus_two)).abs() <= 1e-15,
                "k = {k}: {}",
                s[1]
            );
            assert!((s[2] - one).abs() <= 1e-15, "k = {k}: {}", s[2]);
        }
        // From j = 1: the j = 0 term left out.
        let k = 5;
        let tail = sums.sum(1, k)[0];
        assert!((tail - (2f64.powi(5) / fact(5) - a[0] * a[5])).abs() <= 1e-16);
    }

    /// [`CrossSums::finish_with`] takes order k's factors from its arguments: with zeros
    /// stored at order k, it gives the sums of the true factors (against the products summed
    /// term by term in a plain double loop), for every `k` and both starts.
    #[test]
    fn finish_with_uses_the_given_order_k_factors() {
        let order = 9;
        let f = |j: usize, lane: usize, which: usize| {
            ((j * 7 + lane * 3 + which * 11) % 13) as f64 / 13.0 - 0.4
        };
        let lanes = |j: usize, which: usize| -> [f64; 2] { [f(j, 0, which), f(j, 1, which)] };
        for k in 0..=order {
            let mut sums = CrossSums::<f64, 2>::default();
            sums.reserve(order);
            for j in 0..k {
                sums.set(j, lanes(j, 0), lanes(j, 1), lanes(j, 2), lanes(j, 3));
            }
            sums.set(k, [0.0; 2], [0.0; 2], [0.0; 2], [0.0; 2]);
            let given = [lanes(k, 0), lanes(k, 1), lanes(k, 2), lanes(k, 3)];
            for from in 0..=1 {
                let got = sums.finish_with(
                    k,
                    from,
                    sums.middle(k),
                    [&given[0], &given[1], &given[2], &given[3]],
                );
                for lane in 0..2 {
                    let plain: f64 = (from..=k)
                        .map(|j| {
                            f(j, lane, 0) * f(k - j, lane, 2) - f(j, lane, 1) * f(k - j, lane, 3)
                        })
                        .sum();
                    assert!(
                        (got[lane] - plain).abs() <= 1e-15,
                        "k = {k}, from = {from}, lane {lane}: {} vs {plain}",
                        got[lane]
                    );
                }
            }
        }
    }

    /// Lanes set and finished in groups ([`CrossSums::set_left_lanes`],
    /// [`CrossSums::finish_lanes`]) give, bit for bit, what the whole arrays give: six lanes in
    /// groups of 3, 2 and 1, over orders 0 … 9, for sums from `j = 0` and from `j = 1`.
    #[test]
    fn lanes_set_and_finished_in_groups_are_the_whole_sums_bit_for_bit() {
        let order = 9;
        let f = |j: usize, lane: usize, which: usize| {
            ((j * 7 + lane * 3 + which * 5) as f64 * 0.37).sin() / (1.0 + j as f64)
        };
        let row = |j: usize, which: usize| -> [f64; 6] { std::array::from_fn(|l| f(j, l, which)) };
        let mut whole = CrossSums::<f64, 6>::default();
        let mut grouped = CrossSums::<f64, 6>::default();
        whole.reserve(order);
        grouped.reserve(order);
        for j in 0..=order {
            whole.set(j, row(j, 0), row(j, 1), row(j, 2), row(j, 3));
            set_group::<3>(&mut grouped, j, 0, &row);
            set_group::<2>(&mut grouped, j, 3, &row);
            set_group::<1>(&mut grouped, j, 5, &row);
        }
        for k in 0..=order {
            for from in 0..=1 {
                let expected = whole.sum(from, k);
                let middle = grouped.middle(k);
                let first: [f64; 3] = grouped.finish_lanes(
                    k,
                    from,
                    0,
                    &middle,
                    [
                        &row(k, 0)[..3].try_into().unwrap(),
                        &row(k, 1)[..3].try_into().unwrap(),
                        &row(k, 2)[..3].try_into().unwrap(),
                        &row(k, 3)[..3].try_into().unwrap(),
                    ],
                );
                let second: [f64; 2] = grouped.finish_lanes(
                    k,
                    from,
                    3,
                    &middle,
                    [
                        &row(k, 0)[3..5].try_into().unwrap(),
                        &row(k, 1)[3..5].try_into().unwrap(),
                        &row(k, 2)[3..5].try_into().unwrap(),
                        &row(k, 3)[3..5].try_into().unwrap(),
                    ],
                );
                let third: [f64; 1] = grouped.finish_lanes(
                    k,
                    from,
                    5,
                    &middle,
                    [&[f(k, 5, 0)], &[f(k, 5, 1)], &[f(k, 5, 2)], &[f(k, 5, 3)]],
                );
                let got = [first[0], first[1], first[2], second[0], second[1], third[0]];
                for lane in 0..6 {
                    assert_eq!(
                        got[lane].to_bits(),
                        expected[lane].to_bits(),
                        "k = {k}, from = {from}, lane {lane}: {} vs {}",
                        got[lane],
                        expected[lane]
                    );
                }
            }
        }
    }

    /// Sets lanes `at .. at + R` of order `j` from `row(j, which)`.
    fn set_group<const R: usize>(
        sums: &mut CrossSums<f64, 6>,
        j: usize,
        at: usize,
        row: &impl Fn(usize, usize) -> [f64; 6],
    ) {
        let part = |which: usize| -> [f64; R] { std::array::from_fn(|i| row(j, which)[at + i]) };
        sums.set_left_lanes(j, at, part(0), part(1));
        sums.set_right_lanes(j, at, part(2), part(3));
    }
}
