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

    /// Order `k` of every lane, over `j = from ..= k`: `Σⱼ firstⱼ ⊙ w_firstₖ₋ⱼ −
    /// secondⱼ ⊙ w_secondₖ₋ⱼ`, each term `u w − u′ w′` added in turn, `j` upwards.
    ///
    /// # Panics
    /// If order `k` has not been [`CrossSums::set`] (or `from > k`).
    #[inline(always)]
    #[must_use]
    pub fn sum(&self, from: usize, k: usize) -> [S; M] {
        let mut sums = [S::ZERO; M];
        let ups = self.first[from..=k].iter().zip(&self.second[from..=k]);
        let downs = self.w_first[..=k - from]
            .iter()
            .zip(&self.w_second[..=k - from])
            .rev();
        for ((u1, u2), (w1, w2)) in ups.zip(downs) {
            for i in 0..M {
                sums[i] += u1[i] * w1[i] - u2[i] * w2[i];
            }
        }
        sums
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
}
